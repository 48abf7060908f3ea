// The course edition gives students the book without the answers their kits grade: no
// solution line of any exercise region (see book/AUTHORING.md, "Exercise regions") may
// appear in any HTML page of build/book-course/. The same search run on the public book
// (build/book/), which prints every listing whole, must find them, so the check is shown
// to see what it looks for.
//
// The regions are read here from the source tree, independently of the book's filter that
// cuts them out: an oracle that shares the filter's reading would share its mistakes.
// A solution line counts when it is code: not blank, not braces alone, not a comment.
//
// Label `bookcheck`: runs in the `book` workflow after the editions are built.
#include "support/text_file.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using exactpixels::testing::read_text;

std::string trimmed(const std::string& line) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) {
        return "";
    }
    return line.substr(first, line.find_last_not_of(" \t\r") - first + 1);
}

/// Runs of white space as one space, so that a line compares equal however a page
/// breaks or indents it.
std::string collapsed(const std::string& text) {
    std::string out;
    bool space = false;
    for (const char c : text) {
        if (c == ' ' || c == '\n' || c == '\t' || c == '\r') {
            space = !out.empty();
            continue;
        }
        if (space) {
            out += ' ';
            space = false;
        }
        out += c;
    }
    return out;
}

/// One code point as UTF-8.
std::string utf8(std::uint32_t code) {
    std::string out;
    exactpixels::testing::append_utf8(out, code);
    return out;
}

/// The text a reader sees in an HTML page: tags removed (highlighting splits a line of
/// code into many spans), entities decoded (`&lt;`, `&amp;`, `&#39;`, `&#x2014;`).
std::string html_text(const std::string& html) {
    static const std::map<std::string, std::string> named = {
        {"lt", "<"},    {"gt", ">"},   {"amp", "&"},
        {"quot", "\""}, {"apos", "'"}, {"nbsp", " "}};
    std::string out;
    for (std::size_t i = 0; i < html.size(); ++i) {
        const char c = html[i];
        if (c == '<') {
            const auto close = html.find('>', i);
            i = close == std::string::npos ? html.size() : close;
            continue;
        }
        if (c == '&') {
            const auto semicolon = html.find(';', i);
            if (semicolon != std::string::npos && semicolon - i <= 10) {
                const std::string entity = html.substr(i + 1, semicolon - i - 1);
                std::string decoded;
                if (entity.size() > 2 && entity[0] == '#' &&
                    (entity[1] == 'x' || entity[1] == 'X')) {
                    decoded = utf8(static_cast<std::uint32_t>(
                        std::stoul(entity.substr(2), nullptr, 16)));
                } else if (entity.size() > 1 && entity[0] == '#') {
                    decoded =
                        utf8(static_cast<std::uint32_t>(std::stoul(entity.substr(1))));
                } else if (const auto it = named.find(entity); it != named.end()) {
                    decoded = it->second;
                }
                if (!decoded.empty()) {
                    out += decoded;
                    i = semicolon;
                    continue;
                }
            }
        }
        out += c;
    }
    return out;
}

/// A solution line of one exercise region.
struct SolutionLine {
    std::string exercise; // e.g. "ch02-edge-bias"
    std::string where;    // file:line
    std::string code;     // trimmed, white space collapsed
};

/// Only braces, parentheses and semicolons: "}", "};", "})": too common to tell anything.
bool braces_only(const std::string& code) {
    return code.find_first_not_of("{}();, ") == std::string::npos;
}

bool comment_only(const std::string& code) {
    return code.rfind("//", 0) == 0 || code.rfind("/*", 0) == 0 ||
           code.rfind("*", 0) == 0;
}

/// A line's code: trimmed, without a trailing `// comment` (outside string literals),
/// white space collapsed.
std::string code_of(const std::string& line) {
    std::string t = trimmed(line);
    bool in_string = false;
    for (std::size_t i = 0; i + 1 < t.size(); ++i) {
        if (t[i] == '"' && (i == 0 || t[i - 1] != '\\')) {
            in_string = !in_string;
        } else if (!in_string && i > 0 && t[i] == '/' && t[i + 1] == '/') {
            t = trimmed(t.substr(0, i));
            break;
        }
    }
    return collapsed(t);
}

/// Every solution line of every exercise region (`//> exercise ID: hint` to
/// `//< exercise ID`, minus stub lines `//|`) in the code under src/, chapters/ and
/// tests/, except a line whose code (comments aside) the source also holds outside every
/// exercise region ("break;", "return choice;", a common loop head) or as a stub line:
/// the students' kit holds that line anyway, and the course edition may print it in any
/// other listing, or as the stub.
std::vector<SolutionLine> solution_lines() {
    std::vector<SolutionLine> found;
    std::set<std::string> elsewhere; // code outside every region, and the stubs' code
    const fs::path root(EXACTPIXELS_SOURCE_DIR);
    std::vector<fs::path> files;
    for (const char* top : {"src", "chapters", "tests"}) {
        for (const auto& entry : fs::recursive_directory_iterator(root / top)) {
            const auto extension = entry.path().extension();
            if (entry.is_regular_file() && (extension == ".hpp" || extension == ".cpp")) {
                files.push_back(entry.path());
            }
        }
    }
    std::sort(files.begin(), files.end());
    for (const auto& file : files) {
        std::istringstream in(read_text(file));
        std::string line, exercise;
        int number = 0;
        while (std::getline(in, line)) {
            ++number;
            const std::string t = trimmed(line);
            if (t.rfind("//> exercise ", 0) == 0) {
                exercise = t.substr(13, t.find(':') - 13);
            } else if (t.rfind("//< exercise ", 0) == 0) {
                exercise.clear();
            } else if (t.rfind("//|", 0) == 0) {
                elsewhere.insert(code_of(t.substr(3)));
            } else if (exercise.empty()) {
                elsewhere.insert(code_of(t));
            } else if (!t.empty() && !braces_only(t) && !comment_only(t)) {
                found.push_back(
                    {exercise,
                     fs::relative(file, root).string() + ":" + std::to_string(number),
                     code_of(t)});
            }
        }
    }
    std::erase_if(found, [&](const SolutionLine& solution) {
        return elsewhere.count(solution.code) != 0;
    });
    return found;
}

/// The solution lines that appear in some HTML page of `book` (its top level and its
/// source pages).
std::vector<SolutionLine> printed_solutions(const fs::path& book) {
    std::string text;
    for (const auto& entry : fs::recursive_directory_iterator(book)) {
        const auto rel = fs::relative(entry.path(), book).string();
        // The API reference is Doxygen's, of the whole library, and in the public book
        // only: the course edition has none.
        if (entry.path().extension() == ".html" && rel.rfind("api/", 0) != 0) {
            text += collapsed(html_text(read_text(entry.path()))) + "\n";
        }
    }
    std::vector<SolutionLine> printed;
    for (const auto& line : solution_lines()) {
        if (text.find(line.code) != std::string::npos) {
            printed.push_back(line);
        }
    }
    return printed;
}

} // namespace

TEST_CASE("the course edition prints no solution line of any exercise region") {
    const fs::path course = fs::path(EXACTPIXELS_BINARY_DIR) / "book-course";
    REQUIRE_MESSAGE(fs::exists(course / "index.html"),
                    "build the course edition first: cmake --build build --target "
                    "book-course");
    REQUIRE(solution_lines().size() > 0);
    for (const auto& line : printed_solutions(course)) {
        FAIL_CHECK(line.where << " (exercise " << line.exercise
                              << ") is printed in the course edition: " << line.code);
    }
}

TEST_CASE("the same search finds the exercises' solutions in the public book") {
    const fs::path public_book = fs::path(EXACTPIXELS_BINARY_DIR) / "book";
    REQUIRE(fs::exists(public_book / "index.html"));
    const auto printed = printed_solutions(public_book);
    std::map<std::string, int> per_exercise;
    for (const auto& line : printed) {
        ++per_exercise[line.exercise];
    }
    MESSAGE(printed.size() << " solution lines of " << per_exercise.size()
                           << " exercises are printed in the public book");
    // The whole of exercise ch02-edge-bias, chapter 2's top-left rule, is one of them.
    CHECK(per_exercise["ch02-edge-bias"] == 1);
    CHECK(per_exercise.size() >= 10);
}
