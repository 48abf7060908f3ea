// The PDF book as printed pages: build/book/exact-pixels.pdf is rendered page by page to
// PNG (build/book/pages/, poppler's pdftoppm) and the check fails on
//   - a listing or display equation wider than the text block by more than 5 pt
//     (LaTeX's "Overfull \hbox" in the log; the place is found in the .tex),
//   - a word in a table cell wider than its column (book/latex/header.tex forbids
//     breaking a word in a cell, so such a word makes an Overfull \hbox inside the
//     table instead of being split over two lines), or a table wider than the page,
//   - a figure LaTeX did not find, did not include, or that is blank,
//   - an unresolved reference: "??" in the text (pdftotext), or LaTeX's undefined
//     references or "labels may have changed" (one pass too few),
//   - a character the font lacks (LaTeX drops it from the page silently),
//   - a listing font in which 90 columns (the code's column limit) do not fit the text
//     width of the paper the book was built for.
// Overfull lines of prose are listed but do not fail: the text can be reworded later, a
// listing or an equation cannot be read when it runs off the page.
//
// It runs on each edition's PDF in turn (build/book/, build/book-course/,
// build/book-teacher/; bookcheck_editions.hpp), each rendered into its own pages/.
//
// Label `bookcheck`: runs in the `book` workflow after the editions are built.
#include "support/process.hpp"
#include "support/text_lines.hpp"

#include "exactpixels/base/png.hpp"

#include "support/text_file.hpp"
#include "bookcheck_editions.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using exactpixels::testing::run_command;

namespace {

// How far a listing or an equation may stick out into the margin: 5 pt (1.8 mm), less
// than one character of the listing font, so no code character is ever outside the text
// block.
constexpr double overfull_limit_pt = 5.0;
// How far a word may stick out of its table column: 1 pt, well inside the 6 pt of space
// LaTeX leaves on each side of a column, so the word never touches its neighbour.
constexpr double table_overfull_limit_pt = 1.0;

using exactpixels::testing::read_text;

// (Built up step by step: GCC 12 warns wrongly about "'" + string + "'" at -O2.)
std::string quoted(const fs::path& path) {
    std::string out = "'";
    out += path.string();
    out += '\'';
    return out;
}

using exactpixels::testing::lines_of;

enum class Place { text, listing, equation, table };

// What each line of a LaTeX file is part of: a listing (verbatim environments, as Pandoc
// writes code), a display equation, or running text. Index 0 is line 1.
std::vector<Place> places_of(const std::string& tex) {
    static const std::regex listing_begin(
        R"(\\begin\{(Highlighting|verbatim|Verbatim)\})");
    static const std::regex listing_end(R"(\\end\{(Highlighting|verbatim|Verbatim)\})");
    static const std::regex math_begin(
        R"(\\\[|\\begin\{(equation|align|gather|multline)\*?\})");
    static const std::regex math_end(
        R"(\\\]|\\end\{(equation|align|gather|multline)\*?\})");
    static const std::regex table_begin(R"(\\begin\{(longtable|tabular)\})");
    static const std::regex table_end(R"(\\end\{(longtable|tabular)\})");
    std::vector<Place> places;
    Place now = Place::text;
    for (const auto& line : lines_of(tex)) {
        Place here = now;
        if (now == Place::text && std::regex_search(line, listing_begin)) {
            here = now = Place::listing;
        } else if (now == Place::text && std::regex_search(line, math_begin)) {
            here = now = Place::equation;
        } else if (now == Place::text && std::regex_search(line, table_begin)) {
            here = now = Place::table;
        }
        if (now == Place::listing && std::regex_search(line, listing_end)) {
            now = Place::text;
        } else if (now == Place::equation && std::regex_search(line, math_end)) {
            now = Place::text;
        } else if (now == Place::table && std::regex_search(line, table_end)) {
            now = Place::text;
        }
        places.push_back(here);
    }
    return places;
}

// Problems the LaTeX log of `tex` reports. `notes` receives what is worth reading but
// does not fail (overfull prose).
std::vector<std::string> latex_log_problems(const std::string& log,
                                            const std::string& tex,
                                            std::vector<std::string>& notes) {
    std::vector<std::string> problems;
    const std::vector<Place> places = places_of(tex);
    const auto tex_lines = lines_of(tex);
    static const std::regex overfull(
        R"(Overfull \\hbox \(([0-9.]+)pt too wide\) (in paragraph at lines|in alignment at lines|detected at line) ([0-9]+)(--([0-9]+))?)");
    for (std::sregex_iterator it(log.begin(), log.end(), overfull), end; it != end;
         ++it) {
        const double width = std::stod((*it)[1]);
        const std::size_t first = std::stoul((*it)[3]);
        const std::size_t last = (*it)[5].matched ? std::stoul((*it)[5]) : first;
        Place place = Place::text;
        for (std::size_t line = first; line <= last && line <= places.size(); ++line) {
            if (places[line - 1] != Place::text) {
                place = places[line - 1];
            }
        }
        const std::string where = first <= tex_lines.size() ? tex_lines[first - 1] : "";
        const std::string what = place == Place::listing    ? "a listing"
                                 : place == Place::equation ? "an equation"
                                 : place == Place::table    ? "a table cell"
                                                            : "text";
        const std::string room = place == Place::table
                                     ? " pt wider than its column or the page "
                                     : " pt wider than the page ";
        const std::string message = what + " " + (*it)[1].str() + room + "(.tex line " +
                                    std::to_string(first) + ": " + where.substr(0, 100) +
                                    ")";
        if (place == Place::table && width > table_overfull_limit_pt) {
            problems.push_back(message);
        } else if (place != Place::text && width > overfull_limit_pt) {
            problems.push_back(message);
        } else if (width > overfull_limit_pt) {
            notes.push_back(message);
        }
    }
    // fancyvrb (Pandoc's listings) pads each line with \hss, so LaTeX never reports an
    // overfull listing line; book/latex/header.tex measures every line and logs this.
    static const std::regex wide_line(
        R"(exactpixels-wide-listing-line: ([0-9.]+)pt too wide at line ([0-9]+))");
    for (std::sregex_iterator it(log.begin(), log.end(), wide_line), end; it != end;
         ++it) {
        const std::size_t line = std::stoul((*it)[2]);
        const std::string where = line <= tex_lines.size() ? tex_lines[line - 1] : "";
        const std::string message =
            "a listing line " + (*it)[1].str() + " pt wider than the page (.tex line " +
            std::to_string(line) + ": " + where.substr(0, 100) + ")";
        if (std::stod((*it)[1]) > overfull_limit_pt) {
            problems.push_back(message);
        } else {
            notes.push_back(message);
        }
    }
    static const std::regex missing_file(R"(File `([^']+)' not found)");
    for (std::sregex_iterator it(log.begin(), log.end(), missing_file), end; it != end;
         ++it) {
        problems.push_back("file not found by LaTeX: " + (*it)[1].str());
    }
    static const std::regex undefined(
        R"(LaTeX Warning: (Reference|Citation) `([^']+)' )");
    for (std::sregex_iterator it(log.begin(), log.end(), undefined), end; it != end;
         ++it) {
        problems.push_back("undefined " + (*it)[1].str() + " '" + (*it)[2].str() + "'");
    }
    if (log.find("There were undefined references") != std::string::npos) {
        problems.push_back("LaTeX: there were undefined references");
    }
    if (log.find("Label(s) may have changed") != std::string::npos) {
        problems.push_back(
            "LaTeX: labels may have changed (the build needs one more pass)");
    }
    static const std::regex missing_char(
        R"(Missing character: There is no (.+?) in font)");
    for (std::sregex_iterator it(log.begin(), log.end(), missing_char), end; it != end;
         ++it) {
        problems.push_back("a character the font lacks was dropped: " + (*it)[1].str());
    }
    std::vector<std::string> unique;
    for (const auto& p : problems) {
        if (std::find(unique.begin(), unique.end(), p) == unique.end()) {
            unique.push_back(p);
        }
    }
    return unique;
}

// Every "??" in the text of the PDF, with the words around it.
std::vector<std::string> unresolved_marks(const std::string& text) {
    std::vector<std::string> found;
    for (auto at = text.find("??"); at != std::string::npos;
         at = text.find("??", at + 2)) {
        const auto from = at < 40 ? 0 : at - 40;
        std::string context = text.substr(from, 90);
        std::replace(context.begin(), context.end(), '\n', ' ');
        found.push_back("\"??\" in the PDF text: ..." + context + "...");
    }
    return found;
}

// The table numbers the PDF prints. The text's references ("Table 7.4") are numbered by
// the book filter, which counts captioned tables only, and LaTeX numbers the captions:
// so in each chapter the captions must run 1, 2, 3, ... with no gap (a gap is a table
// LaTeX counted that the filter did not, and every reference after it names the wrong
// table), and every reference must name a caption. One line per problem.
std::vector<std::string> table_number_problems(const std::string& pdf_text) {
    // Line breaks and runs of spaces as one space: "Table" may end a line.
    const std::string text = std::regex_replace(pdf_text, std::regex(R"(\s+)"), " ");
    std::vector<std::string> problems;
    std::map<int, int> last; // chapter -> its last caption's number
    std::set<std::pair<int, int>> captions;
    static const std::regex caption(R"(Table ([0-9]+)\.([0-9]+):)");
    for (std::sregex_iterator it(text.begin(), text.end(), caption), end; it != end;
         ++it) {
        const int chapter = std::stoi((*it)[1]), number = std::stoi((*it)[2]);
        if (number != last[chapter] + 1) {
            problems.push_back("table caption " + (*it)[1].str() + "." + (*it)[2].str() +
                               " follows " + std::to_string(chapter) + "." +
                               std::to_string(last[chapter]) +
                               ": LaTeX counted a table the references do not");
        }
        last[chapter] = number;
        captions.insert({chapter, number});
    }
    static const std::regex reference(R"(Table ([0-9]+)\.([0-9]+)(?![0-9:]))");
    for (std::sregex_iterator it(text.begin(), text.end(), reference), end; it != end;
         ++it) {
        if (!captions.count({std::stoi((*it)[1]), std::stoi((*it)[2])})) {
            problems.push_back("reference to Table " + (*it)[1].str() + "." +
                               (*it)[2].str() + ", which no caption has");
        }
    }
    return problems;
}

// The file of every \includegraphics in `tex`.
std::vector<std::string> figures_of(const std::string& tex) {
    static const std::regex include(R"(\\includegraphics(\[[^\]]*\])?\{([^}]+)\})");
    std::vector<std::string> files;
    for (std::sregex_iterator it(tex.begin(), tex.end(), include), end; it != end; ++it) {
        files.push_back((*it)[2]);
    }
    return files;
}

// True when the picture in `png` has at least two different pixel values.
bool has_content(const fs::path& png) {
    const auto image = exactpixels::read_png(png);
    const auto first = image.at(0, 0);
    for (int y = 0; y < image.height(); ++y) {
        for (int x = 0; x < image.width(); ++x) {
            if (image.at(x, y) != first) {
                return true;
            }
        }
    }
    return false;
}

// Runs pdflatex twice on `tex` in `folder`, without stopping at errors (as a broken book
// would be rendered), so that the log holds every complaint.
void run_pdflatex(const fs::path& folder, const std::string& tex) {
    std::ofstream(folder / "doc.tex") << tex;
    for (int pass = 0; pass < 2; ++pass) {
        run_command("cd " + quoted(folder) +
                    " && max_print_line=10000 pdflatex -interaction=nonstopmode doc.tex");
    }
}

} // namespace

TEST_CASE("the PDF check catches overfull listings and equations, missing figures and "
          "unresolved references") {
    const fs::path folder = fs::temp_directory_path() /
                            ("exactpixels-pdfcheck-" + std::to_string(::getpid()));
    fs::remove_all(folder);
    fs::create_directories(folder);
    const std::string long_code(150, 'x');
    // The book's own preamble additions, so the check is tested against what they log.
    const std::string header =
        std::string(EXACTPIXELS_SOURCE_DIR) + "/book/latex/header.tex";
    const std::string tex =
        "\\documentclass{article}\n"
        "\\usepackage{graphicx,longtable,array,xcolor}\n"
        "\\input{" +
        header +
        "}\n"
        "\\begin{document}\n"
        "See Section~\\ref{sec:nowhere}.\n"
        "\n"
        "\\begin{Verbatim}\n" +
        long_code +
        "\n"
        "\\end{Verbatim}\n"
        "\n"
        "\\begin{verbatim}\n" +
        long_code +
        "\n"
        "\\end{verbatim}\n"
        "\n"
        "Some text.\n"
        "\\[ a_1 + a_2 + a_3 + a_4 + a_5 + a_6 + a_7 + a_8 + a_9 + a_{10} "
        "+ a_{11} + a_{12} + a_{13} + a_{14} + a_{15} + a_{16} + a_{17} + "
        "a_{18} + a_{19} + a_{20} + a_{21} + a_{22} + a_{23} + a_{24} "
        "+ a_{25} + a_{26} + a_{27} + a_{28} + a_{29} + a_{30} \\]\n"
        "\n"
        "\\begin{longtable}[]{@{}p{2em}p{8em}@{}}\n"
        "subdivided-16 & two short words that may wrap \\\\\n"
        "\\end{longtable}\n"
        "\n"
        "\\includegraphics{ch99_missing.pdf}\n"
        "\\end{document}\n";
    run_pdflatex(folder, tex);
    const std::string log = read_text(folder / "doc.log");
    REQUIRE_MESSAGE(!log.empty(), "pdflatex did not run (texlive-latex-base missing?)");
    std::vector<std::string> notes;
    const auto problems = latex_log_problems(log, tex, notes);
    for (const auto& p : problems) {
        MESSAGE(p);
    }
    auto has = [&](const std::string& what) {
        return std::any_of(problems.begin(), problems.end(), [&](const std::string& p) {
            return p.find(what) != std::string::npos;
        });
    };
    CHECK(has("a listing line")); // the Verbatim (Pandoc's highlighted code)
    CHECK(std::any_of(problems.begin(), problems.end(), [](const std::string& p) {
        return p.rfind("a listing ", 0) == 0 && p.rfind("a listing line", 0) != 0;
    })); // the plain verbatim block: a real Overfull \hbox
    CHECK(has("an equation"));
    CHECK(has("a table cell")); // "subdivided-16" may not be split over two lines
    CHECK(std::count_if(problems.begin(), problems.end(), [](const std::string& p) {
              return p.find("a table cell") != std::string::npos;
          }) == 1); // the cell of short words wraps between them, as it may
    CHECK(has("file not found by LaTeX: ch99_missing.pdf"));
    CHECK(has("undefined Reference 'sec:nowhere'"));
    CHECK(has("there were undefined references"));
    const auto text = run_command("pdftotext " + quoted(folder / "doc.pdf") + " -");
    REQUIRE(text.exit_code == 0);
    CHECK(unresolved_marks(text.out).size() == 1);
    CHECK(figures_of(tex) == std::vector<std::string>{"ch99_missing.pdf"});
    fs::remove_all(folder);
}

TEST_CASE("the PDF check catches a table number the references do not have") {
    // As LaTeX printed chapter 7 when an uncaptioned longtable stepped the counter.
    const std::string gap = "Table 7.1: Colours\n... see Table 7.2 and (Table\n7.1).\n"
                            "Table 7.3: Speed\n";
    const auto problems = table_number_problems(gap);
    REQUIRE(problems.size() == 2);
    CHECK(problems[0].find("table caption 7.3 follows 7.1") != std::string::npos);
    CHECK(problems[1].find("reference to Table 7.2") != std::string::npos);
    // Consecutive captions in two chapters, references to them (one across a line
    // break): nothing to report.
    CHECK(table_number_problems("Table 2.1: a Table 2.2: b Table 7.1: c see Table 2.2, "
                                "Table\n7.1 and Table 2.1.")
              .empty());
}

TEST_CASE(
    "overfull prose is listed but does not fail; small overfull boxes are allowed") {
    const std::string tex =
        "line 1\n\\begin{Highlighting}[]\ncode\n\\end{Highlighting}\nprose\n";
    const std::string log =
        "Overfull \\hbox (4.9pt too wide) in paragraph at lines 2--4\n"
        "Overfull \\hbox (30.0pt too wide) in paragraph at lines 5--5\n"
        "Overfull \\hbox (5.1pt too wide) in paragraph at lines 2--4\n";
    std::vector<std::string> notes;
    const auto problems = latex_log_problems(log, tex, notes);
    REQUIRE(problems.size() == 1);
    CHECK(problems[0].find("a listing 5.1 pt") != std::string::npos);
    REQUIRE(notes.size() == 1);
    CHECK(notes[0].find("text 30.0 pt") != std::string::npos);
}

namespace {

/// The PDF of the edition in folder `book`: its LaTeX log, its figures and every page.
void check_pdf_edition(const fs::path& book) {
    const fs::path pdf = book / "exact-pixels.pdf";
    const fs::path latex = book / "latex";
    REQUIRE_MESSAGE(fs::exists(pdf), "no " << pdf.string()
                                           << ": build the book first (cmake --build "
                                              "--preset book)");
    const std::string log = read_text(latex / "exact-pixels.log");
    const std::string tex = read_text(latex / "exact-pixels.tex");
    REQUIRE(!log.empty());
    REQUIRE(!tex.empty());

    std::vector<std::string> notes;
    std::vector<std::string> problems = latex_log_problems(log, tex, notes);
    for (const auto& note : notes) {
        MESSAGE("note (not a failure): " << note);
    }

    // 90 columns of the listing font fit the text width (header.tex measures both).
    static const std::regex measure(
        R"(exactpixels-listing: 90 columns = ([0-9.]+)pt, text width = ([0-9.]+)pt)");
    std::smatch m;
    REQUIRE_MESSAGE(std::regex_search(log, m, measure),
                    "book/latex/header.tex should log the listing width");
    MESSAGE("90 listing columns: " << m[1] << " pt; text width: " << m[2] << " pt");
    CHECK(std::stod(m[1]) <= std::stod(m[2]));

    // Figures: found, included, and not blank.
    const fs::path scratch = fs::temp_directory_path() /
                             ("exactpixels-pdfpages-" + std::to_string(::getpid()));
    fs::remove_all(scratch);
    fs::create_directories(scratch);
    int figure_count = 0;
    for (const auto& figure : figures_of(tex)) {
        ++figure_count;
        const fs::path path =
            fs::path(figure).is_absolute() ? fs::path(figure) : latex / figure;
        if (!fs::exists(path) || fs::file_size(path) == 0) {
            problems.push_back("figure missing or empty: " + figure);
            continue;
        }
        if (log.find("<" + figure) == std::string::npos) {
            problems.push_back("figure not included by LaTeX (no '<" + figure +
                               "' in the log)");
        }
        fs::path png = path;
        if (path.extension() == ".pdf") {
            png = scratch / "figure.png";
            const auto r = run_command("pdftoppm -r 30 -png -singlefile " + quoted(path) +
                                       " " + quoted(scratch / "figure"));
            if (r.exit_code != 0) {
                problems.push_back("pdftoppm cannot render figure " + figure + ": " +
                                   r.err);
                continue;
            }
        }
        if (!has_content(png)) {
            problems.push_back("figure is blank (one colour): " + figure);
        }
    }

    // Every page to PNG; the count must match what pdfinfo says.
    const auto info = run_command("pdfinfo " + quoted(pdf));
    REQUIRE_MESSAGE(info.exit_code == 0,
                    "pdfinfo failed (install poppler-utils): " << info.err);
    std::smatch pages_match;
    REQUIRE(std::regex_search(info.out, pages_match, std::regex(R"(Pages:\s+([0-9]+))")));
    const int pages = std::stoi(pages_match[1]);
    const fs::path page_dir = book / "pages";
    fs::remove_all(page_dir);
    fs::create_directories(page_dir);
    const auto rendered = run_command("pdftoppm -r 40 -png " + quoted(pdf) + " " +
                                      quoted(page_dir / "page"));
    CHECK_MESSAGE(rendered.exit_code == 0, rendered.err);
    CHECK_MESSAGE(rendered.err.empty(), "pdftoppm complained: " << rendered.err);
    int png_count = 0;
    for (const auto& entry : fs::directory_iterator(page_dir)) {
        if (entry.path().extension() == ".png") {
            ++png_count;
            CHECK_MESSAGE(has_content(entry.path()), entry.path().string()
                                                         << " is blank");
        }
    }
    CHECK(png_count == pages);

    const auto text = run_command("pdftotext -enc UTF-8 " + quoted(pdf) + " -");
    REQUIRE(text.exit_code == 0);
    for (const auto& mark : unresolved_marks(text.out)) {
        problems.push_back(mark);
    }
    for (const auto& p : table_number_problems(text.out)) {
        problems.push_back(p);
    }

    MESSAGE(pages << " pages rendered to " << page_dir.string() << ", " << figure_count
                  << " figures checked");
    for (const auto& p : problems) {
        FAIL_CHECK(p);
    }
    CHECK(problems.empty());
    fs::remove_all(scratch);
}

} // namespace

TEST_CASE("every page of each edition of the PDF book prints without a fault") {
    for (const auto& edition : exactpixels::bookcheck::editions) {
        const std::string name = edition.folder; // doctest prints a char* as a pointer
        INFO("edition " << name);
        MESSAGE("edition " << name);
        check_pdf_edition(exactpixels::bookcheck::edition_folder(edition));
    }
}
