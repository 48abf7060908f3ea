// The one doctest main shared by every chapter's test executable. Besides doctest's own
// options it takes --facts=FILE: after a run in which every selected test passed, it
// writes the values the tests recorded with record_fact (support/measured_facts.hpp) to
// FILE. (In the assignment kits' fake fixture project, which has no base layer, it is
// doctest's plain main.)
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#if __has_include("exactpixels/base/error.hpp")
#define EXACTPIXELS_MEASURED_FACTS 1
#include "exactpixels/base/error.hpp"
#include "support/measured_facts.hpp"
#endif

#include <iostream>
#include <string>
#include <string_view>
#include <vector>

int main(int argc, char** argv) {
    std::string facts;
    std::vector<char*> doctest_args;
    for (int i = 0; i < argc; ++i) {
        const std::string_view arg = argv[i];
        if (arg.starts_with("--facts=")) {
            facts = arg.substr(8);
        } else {
            doctest_args.push_back(argv[i]);
        }
    }
    doctest::Context context(static_cast<int>(doctest_args.size()), doctest_args.data());
    const int result = context.run();
    if (context.shouldExit() || result != 0 || facts.empty()) {
        return result;
    }
#ifdef EXACTPIXELS_MEASURED_FACTS
    try {
        exactpixels::testing::write_measured_facts(facts);
    } catch (const exactpixels::Error& error) {
        std::cerr << error.what() << '\n';
        return 2;
    }
    return 0;
#else
    std::cerr << "--facts needs the library's base layer, which this project lacks\n";
    return 2;
#endif
}
