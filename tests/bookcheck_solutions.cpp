// The teacher's edition and the students' editions: every exercise's worked solution and
// every exam answer and rubric (a `::: solution` block in a chapter's source or in a page
// of book/, see book/AUTHORING.md) appears in the teacher's edition (build/book-teacher/)
// and nowhere in the public book (build/book/) or the course edition
// (build/book-course/): their HTML pages and the LaTeX source of their PDFs. The kits are
// checked by the kit tests (tests/assignments_kits.cpp), which prove no solution text
// reaches a kit.
//
// A solution is recognised by phrases of its plain text: runs of at least six words with
// no mathematics, code or markup, compared with the outputs' text after tags and extra
// white space are removed.
//
// Label `bookcheck`: runs in the `book` workflow after both books are built.
#include "bookcheck_editions.hpp"
#include "support/text_file.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using exactpixels::testing::read_text;

/// Tags and LaTeX commands removed, the entities of quote marks undone, white space
/// collapsed. (A loop, not std::regex: libstdc++'s regex recurses per character and
/// overflows the stack on pages this long.)
std::string plain_text(const std::string& raw) {
    std::string text = raw;
    for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
             {"\u2019", "'"}, {"\u2018", "'"}, {"&#39;", "'"}, {"&quot;", "\""}}) {
        for (auto at = text.find(from); at != std::string::npos;
             at = text.find(from, at)) {
            text.replace(at, from.size(), to);
        }
    }
    std::string out;
    bool space = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        char c = text[i];
        if (c == '<') { // an HTML tag
            const auto close = text.find('>', i);
            i = close == std::string::npos ? text.size() : close;
            c = ' ';
        } else if (c == '\\') { // a LaTeX command name
            while (i + 1 < text.size() &&
                   std::isalpha(static_cast<unsigned char>(text[i + 1]))) {
                ++i;
            }
            c = ' ';
        } else if (c == '{' || c == '}' || c == '\n' || c == '\t' || c == '\r') {
            c = ' ';
        }
        if (c == ' ') {
            if (!space) {
                out += ' ';
            }
            space = true;
        } else {
            out += c;
            space = false;
        }
    }
    return out;
}

/// One solution block: where it is and the plain phrases it contains.
struct Solution {
    std::string where;
    std::vector<std::string> phrases;
};

/// Every `::: solution` block of every chapter and of every page of book/ (the exam
/// answers and rubrics), with its phrases of six or more plain words (letters, digits,
/// commas, apostrophes between words).
std::vector<Solution> solutions() {
    std::vector<Solution> found;
    const fs::path source = EXACTPIXELS_SOURCE_DIR;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(source / "chapters")) {
        if (fs::exists(entry.path() / "chapter.md")) {
            files.push_back(entry.path() / "chapter.md");
        }
    }
    for (const auto& entry : fs::directory_iterator(source / "book")) {
        if (entry.path().extension() == ".md") {
            files.push_back(entry.path());
        }
    }
    std::sort(files.begin(), files.end());
    const std::regex phrase("([A-Za-z]+[,']? ){5,}[A-Za-z]+");
    for (const auto& file : files) {
        std::istringstream in(read_text(file));
        std::string line, body;
        int line_number = 0, start = 0, depth = 0;
        bool in_code = false;
        bool inside = false;
        while (std::getline(in, line)) {
            ++line_number;
            const auto first = line.find_first_not_of(' ');
            const std::string t = first == std::string::npos ? "" : line.substr(first);
            if (!inside && t.rfind("```", 0) == 0) {
                in_code = !in_code; // an example of the markup (book/AUTHORING.md)
                continue;
            }
            if (in_code) {
                continue;
            }
            if (!inside && (t == "::: solution" || t == "::: {.solution}")) {
                inside = true;
                depth = 0;
                start = line_number;
                body.clear();
            } else if (inside && t.rfind(":::", 0) == 0 && t != ":::") {
                ++depth; // a div inside the solution (a rubric)
            } else if (inside && t == ":::" && depth > 0) {
                --depth;
            } else if (inside && t == ":::") {
                inside = false;
                // Mathematics and code are not compared: the outputs render them.
                body = std::regex_replace(
                    body, std::regex("\\$[^$]*\\$|`[^`]*`|@[a-z:-]+"), " | ");
                Solution solution{file.parent_path().filename().string() + "/" +
                                      file.filename().string() + ":" +
                                      std::to_string(start),
                                  {}};
                for (std::sregex_iterator it(body.begin(), body.end(), phrase), end;
                     it != end; ++it) {
                    solution.phrases.push_back(it->str());
                }
                found.push_back(solution);
            } else if (inside) {
                body += t + " ";
            }
        }
    }
    return found;
}

/// The plain text of every HTML page of `book` and of its LaTeX source.
std::string book_text(const fs::path& book) {
    std::string text;
    for (const auto& entry : fs::directory_iterator(book)) {
        if (entry.path().extension() == ".html") {
            text += plain_text(read_text(entry.path())) + "\n";
        }
    }
    text += plain_text(read_text(book / "latex/exact-pixels.tex"));
    return text;
}

} // namespace

TEST_CASE("the teacher's edition holds every worked solution, exam answer and rubric; "
          "the other editions none") {
    const auto all = solutions();
    REQUIRE(!all.empty());
    // Exam answers and rubrics too, not only the chapters' solutions.
    CHECK(std::count_if(all.begin(), all.end(), [](const Solution& s) {
              return s.where.rfind("book/", 0) == 0;
          }) >= 20);
    for (const auto& edition : exactpixels::bookcheck::editions) {
        const fs::path book = exactpixels::bookcheck::edition_folder(edition);
        const std::string name = edition.folder; // doctest prints a char* as a pointer
        INFO("edition " << name);
        REQUIRE(fs::exists(book / "latex/exact-pixels.tex"));
        const std::string text = book_text(book);
        int phrases = 0;
        for (const auto& solution : all) {
            CAPTURE(solution.where);
            CHECK(!solution.phrases.empty()); // every solution can be recognised
            for (const auto& phrase : solution.phrases) {
                CAPTURE(phrase);
                CHECK((text.find(phrase) != std::string::npos) == edition.with_solutions);
                ++phrases;
            }
        }
        MESSAGE(name << ": " << all.size() << " solutions, " << phrases
                     << " phrases checked");
        // The markers themselves: a student's edition has no solution, answer or rubric
        // block at all.
        CHECK((text.find("Solution.") != std::string::npos) == edition.with_solutions);
        if (!edition.with_solutions) {
            CHECK(text.find("Answer.") == std::string::npos);
            CHECK(text.find("(derive, 2 marks):") == std::string::npos);
        }
    }
}
