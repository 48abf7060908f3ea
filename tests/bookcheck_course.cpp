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
/// tests/, and every line of a gives-away block (`//> gives-away ID` to
/// `//< gives-away ID`: code outside the region that states its answer, such as
/// chapter 10's run_end, which divides out the same crossing), except a line whose code (comments aside) the source also holds outside every
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
            } else if (t.rfind("//> gives-away ", 0) == 0) {
                exercise = trimmed(t.substr(15));
            } else if (t.rfind("//< exercise ", 0) == 0 ||
                       t.rfind("//< gives-away ", 0) == 0) {
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

/// The text of every HTML page of `book` (its top level, its source pages and its API
/// reference), as a reader sees it, white space collapsed, one page a line.
std::string book_text(const fs::path& book) {
    std::string text;
    for (const auto& entry : fs::recursive_directory_iterator(book)) {
        if (entry.path().extension() == ".html") {
            text += collapsed(html_text(read_text(entry.path()))) + "\n";
        }
    }
    return text;
}

/// The solution lines that appear in some HTML page of `book`.
std::vector<SolutionLine> printed_solutions(const fs::path& book) {
    const std::string text = book_text(book);
    std::vector<SolutionLine> printed;
    for (const auto& line : solution_lines()) {
        if (text.find(line.code) != std::string::npos) {
            printed.push_back(line);
        }
    }
    return printed;
}

/// A page's text with no white space at all and U+2212 (MathML's minus) as '-': an
/// expression compares equal however it is spaced, in code, in prose or in maths (whose
/// MathML carries its TeX as an annotation, so a formula is found by its TeX too).
std::string squeezed(const std::string& text) {
    static const std::string minus = "\u2212";
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text.compare(i, minus.size(), minus) == 0) {
            out += '-';
            i += minus.size() - 1;
        } else if (text[i] != ' ' && text[i] != '\n' && text[i] != '\t' &&
                   text[i] != '\r') {
            out += text[i];
        }
    }
    return out;
}

/// What would give an exercise's answer away outside its region: the decisive expression
/// of its solution as the text, the maths (its TeX) or a comment of a listing stated it,
/// written here without white space. The course edition states the idea instead
/// (`.not-in-course` / `.course-only`, book/AUTHORING.md); the public book keeps them all,
/// which the second test below requires, so that no entry here is a string that never
/// occurs.
struct GiveAway {
    const char* exercise;
    const char* text;
};
const GiveAway give_aways[] = {
    {"ch02-edge-bias", "dy<0||(dy==0&&dx>0)"},
    {"ch02-edge-bias", "aleftedgerunsup"},
    {"ch02-edge-bias", "aleftedgegoesupthescreen"},
    {"ch02-barycentric", R"(\lambda_i(p)&=\frac{E_i(p)}{2A})"},
    {"ch02-barycentric", "lambda_i=E_i/(E_0+E_1+E_2)"},
    {"ch02-barycentric", "-(y_{i+2}-y_{i+1})/2A"},
    {"ch04-modifier", "D/2-1"},
    {"ch04-modifier", R"(\tfrac12-1/D)"},
    {"ch04-modifier", "oneunit(1/D)smaller"},
    {"ch05-texel-error", "std::max(std::abs(u-u_ref),std::abs(v-v_ref))"},
    {"ch05-texel-error", R"(e_k=\max\left()"},
    {"ch05-texel-error", "largerofthetwocoordinateerrors"},
    {"ch05-texel-error", "Thelargerofthetwo:below1/2"},
    {"ch08-bilinear", "C=U-D/2"},
    {"ch08-bilinear", "f_u=C-iD"},
    {"ch08-bilinear", "Cu-i*D"},
    {"ch08-derivatives", R"(\frac{p_xq-p\,q_x}{q^2})"},
    {"ch08-derivatives", "numerator_x(u)*inv_q2"},
    {"ch08-derivatives", "numeratoroverq^2"},
    {"ch08-derivatives", "dividedbyq2q^2"},
    {"ch08-derivatives", "|N_x|/q^2"},
    {"ch10-run-of-row", "ceil_div(-w[i],step)"},
    {"ch10-run-of-row", "floor_div(w[i],-step)+1"},
    {"ch10-run-of-row", R"(k\ge\left\lceil\dfrac{-w}{s_x}\right\rceil)"},
    {"ch10-run-of-row", R"(k=\lceil-w/s\rceil)"},
    {"ch10-run-of-row", R"(\lfloorw/s\rfloor+1)"},
    {"ch10-run-of-row", "k>=ceil(-w/step)"},
    // run_end (chapter 10) divides out the same crossing, once per triangle.
    {"ch10-run-of-row", "end.k=ceil_div(-w,end.s)"},
    {"ch10-run-of-row", "end.k=floor_div(w,end.s)+1"},
};

/// The answers of the variant exercises: exercises set in place of ones whose answer a
/// chapter must print to teach (book/teaching.md, "Three editions"). Their point is that
/// no chapter prints them, in any edition: each decisive expression (TeX or code, without
/// white space) may appear on no page of the public book or the course edition outside
/// the API reference (which prints the public library whole), and must appear in the
/// teacher's edition, whose solutions derive them, so that the search is shown to see
/// them.
const GiveAway variant_answers[] = {
    {"ch01-gradient-3d",
     R"(\Delta_2\,(\mathbfe_3\times\mathbfn)+\Delta_3\,(\mathbfn\times\mathbfe_2))"},
    {"ch01-gradient-3d", "along2=cross(e3,n),along3=cross(n,e2)"},
    {"ch01-prestep-up", R"(j=\lfloory-\tfrac12\rfloor)"},
    {"ch01-prestep-up", "std::floor(y_from-0.5)"},
    {"ch02-block-area", R"(\max\!\left(-\tfrac12s_x,(n_x-\tfrac12)\,s_x\right))"},
    {"ch02-block-area", "right=(b.x_end-b.x_begin)*e.step_x()-half_x"},
    {"ch03-pixel-of-u", R"(t=\frac{u\,q_0-p_0}{p_t-u\,q_t})"},
    {"ch03-pixel-of-u", "(u*s.one_w-s.u_w)/(s.du_w-u*s.done_w)"},
    {"ch03-quarter-point", R"(16\Delta\,w_0/(w_0+3w_2))"},
    {"ch03-quarter-point", R"(a=\frac{4\Delta-k}{3n^2})"},
    {"ch03-quarter-point", "T(16)*du*w0/(w0+T(3)*w2)"},
};

/// The expressions of `list` found on the HTML pages of `book` (all of them, or with
/// `top_level_only` its chapters and other pages without its API reference), each as
/// `EXERCISE: "TEXT" on PAGE`.
template <std::size_t N>
std::vector<std::string> found_in(const fs::path& book, const GiveAway (&list)[N],
                                  bool top_level_only = false) {
    std::vector<std::string> found;
    for (auto it = fs::recursive_directory_iterator(book);
         it != fs::recursive_directory_iterator(); ++it) {
        if (it->path().extension() != ".html" || (top_level_only && it.depth() > 0)) {
            continue;
        }
        const std::string text = squeezed(html_text(read_text(it->path())));
        for (const auto& g : list) {
            if (text.find(g.text) != std::string::npos) {
                found.push_back(std::string(g.exercise) + ": \"" + g.text + "\" on " +
                                fs::relative(it->path(), book).string());
            }
        }
    }
    return found;
}

/// The entries of `list` that `found` (from found_in) never names.
template <std::size_t N>
std::vector<std::string> never_found(const std::vector<std::string>& found,
                                     const GiveAway (&list)[N]) {
    std::vector<std::string> missing;
    for (const auto& g : list) {
        const std::string prefix = std::string(g.exercise) + ": \"" + g.text + "\"";
        if (std::none_of(found.begin(), found.end(),
                         [&](const std::string& f) { return f.rfind(prefix, 0) == 0; })) {
            missing.push_back(prefix);
        }
    }
    return missing;
}

} // namespace

TEST_CASE("the course edition prints no solution line of any exercise region") {
    const fs::path course = fs::path(EXACTPIXELS_BINARY_DIR) / "book-course";
    REQUIRE_MESSAGE(fs::exists(course / "index.html"),
                    "build the course edition first: cmake --build build --target "
                    "book-course");
    // Its API reference is searched with its pages: without it the search would pass
    // for want of pages to search.
    REQUIRE(fs::exists(course / "api/index.html"));
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

TEST_CASE("the search reads the API reference: the public book's prints solution lines") {
    // The API reference's source pages print each header whole in the public book; the
    // search must see them there, run_end's division included (a gives-away block of
    // ch10-run-of-row, which the course edition's API reference once printed).
    const fs::path api = fs::path(EXACTPIXELS_BINARY_DIR) / "book" / "api";
    REQUIRE(fs::exists(api / "index.html"));
    const auto printed = printed_solutions(api);
    std::set<std::string> exercises;
    for (const auto& line : printed) {
        exercises.insert(line.exercise);
    }
    MESSAGE(printed.size() << " solution lines of " << exercises.size()
                           << " exercises are printed in the public book's API reference");
    CHECK(exercises.size() >= 10);
    CHECK(std::any_of(printed.begin(), printed.end(), [](const SolutionLine& line) {
        return line.exercise == "ch10-run-of-row" &&
               line.code == "end.k = ceil_div(-w, end.s);";
    }));
}

TEST_CASE("no text of the course edition gives an exercise's answer away") {
    const fs::path course = fs::path(EXACTPIXELS_BINARY_DIR) / "book-course";
    REQUIRE(fs::exists(course / "index.html"));
    for (const auto& found : found_in(course, give_aways)) {
        FAIL_CHECK("the course edition gives the answer away: " << found);
    }
}

TEST_CASE("the public book states every answer the course edition keeps back") {
    const fs::path public_book = fs::path(EXACTPIXELS_BINARY_DIR) / "book";
    REQUIRE(fs::exists(public_book / "index.html"));
    for (const auto& missing :
         never_found(found_in(public_book, give_aways), give_aways)) {
        FAIL_CHECK("never in the public book: " << missing);
    }
}

TEST_CASE("no page of the public book or the course edition prints a variant's answer") {
    for (const char* edition : {"book", "book-course"}) {
        const fs::path book = fs::path(EXACTPIXELS_BINARY_DIR) / edition;
        REQUIRE(fs::exists(book / "index.html"));
        for (const auto& found : found_in(book, variant_answers, true)) {
            FAIL_CHECK("build/" << std::string(edition)
                                << " prints a variant exercise's answer: " << found);
        }
    }
}

TEST_CASE("the teacher's edition derives every variant's answer") {
    const fs::path teacher = fs::path(EXACTPIXELS_BINARY_DIR) / "book-teacher";
    REQUIRE(fs::exists(teacher / "index.html"));
    const auto found = found_in(teacher, variant_answers, true);
    for (const auto& missing : never_found(found, variant_answers)) {
        FAIL_CHECK("never in the teacher's edition: " << missing);
    }
}
