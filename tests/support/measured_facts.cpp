// measured_facts.cpp: the values tests record for the book, written on request.
#include "support/measured_facts.hpp"

// The assignment kits' own fixture tree (the kit test's fake project) is a project
// without the library's base layer; there the test programs are built without --facts.
#if __has_include("exactpixels/base/atomic_file.hpp")
#include "exactpixels/base/atomic_file.hpp"

#include <cassert>
#include <cstdio>
#include <map>

namespace exactpixels::testing {

namespace {
std::map<std::string, double>& recorded() {
    static std::map<std::string, double> facts;
    return facts;
}
} // namespace

void record_fact(const std::string& name, double value) {
    assert(!name.empty() && name.find_first_of(" \t\n#") == std::string::npos);
    recorded()[name] = value;
}

void write_measured_facts(const std::filesystem::path& path) {
    std::string text =
        "# Measured by the chapter's tests (tests/support/measured_facts.hpp)\n";
    for (const auto& [name, value] : recorded()) {
        char number[40];
        std::snprintf(number, sizeof number, "%.17g", value);
        text += name + " " + number + "\n";
    }
    write_file_atomically(path, "measured facts", text);
}

} // namespace exactpixels::testing

#endif // the base layer is there
