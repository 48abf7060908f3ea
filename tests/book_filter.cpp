// Tests of the book's Pandoc filter (book/filters/exactpixels.lua): listings are the
// compiled source minus marker lines, and every broken link between text and code fails
// the build with "chapters/NN-slug/chapter.md:LINE: error: ...".
#include "support/process.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using exactpixels::testing::run_command;

namespace {

// A throw-away source tree with one chapter, one source file and one test file.
struct FixtureBook {
    fs::path root;

    FixtureBook() {
        root = fs::temp_directory_path() /
               ("exactpixels-book-" + std::to_string(::getpid()));
        fs::remove_all(root);
        fs::create_directories(root / "chapters" / "07-demo");
        fs::create_directories(root / "src");
        fs::create_directories(root / "tests");
        fs::create_directories(root / "figures");
        fs::create_directories(root / "out" / "source");
        fs::create_directories(root / "book");
        write("book/metadata.yaml", "title: Demo\nkit-points-per-mark: 10\n");
        write("src/demo.hpp", "int before;\n"
                              "//> answer\n"
                              "    int answer() {\n"
                              "        //> exercise ch07-demo: return the answer\n"
                              "        return 42;\n"
                              "        //| return 0;\n"
                              "        //< exercise ch07-demo\n"
                              "    }\n"
                              "//< answer\n"
                              "int after;\n"
                              "//> twice-answer\n"
                              "    int twice_answer() {\n"
                              "        //> gives-away ch07-demo\n"
                              "        return 2 * 42;\n"
                              "        //| return 2 * answer();\n"
                              "        //< gives-away ch07-demo\n"
                              "    }\n"
                              "//< twice-answer\n");
        write("tests/ch07_demo.cpp", "TEST_CASE(\"the answer is 42\") {}\n"
                                     "TEST_CASE(\n"
                                     "    \"a name too long for one line\" * points) {}\n"
                                     "TEST_CASE(\"a name split by clang-format into \"\n"
                                     "          \"two string literals\") {}\n");
    }
    ~FixtureBook() { fs::remove_all(root); }

    void write(const std::string& relative, const std::string& text) const {
        std::ofstream(root / relative) << text;
    }

    // Renders chapters/07-demo/chapter.md with `markdown` as its text, to HTML.
    exactpixels::testing::CommandResult render(const std::string& markdown) const {
        write("chapters/07-demo/chapter.md", markdown);
        return run_filter("chapters/07-demo/chapter.md", "html", "EP_CHAPTERS=07-demo");
    }

    // Runs the filter on `file` (relative to the root) for `target` (html or latex), with
    // `env` added to the environment (e.g. "EP_CHAPTERS=07-demo" or "EP_PAGE=...").
    exactpixels::testing::CommandResult
    run_filter(const std::string& file, const std::string& target, const std::string& env,
               const std::string& all = "07-demo") const {
        const std::string vars = "EP_ROOT='" + root.string() + "' EP_FIGURES='" +
                                 (root / "figures").string() + "' EP_OUT='" +
                                 (root / "out").string() + "' EP_TARGET=" + target + " " +
                                 env + " EP_ALL_CHAPTERS='" + all + "' ";
        return run_command(vars + "pandoc --from=markdown --to=" +
                           (target == "html" ? "html5 --mathml" : "latex") +
                           " --lua-filter='" + std::string(EXACTPIXELS_SOURCE_DIR) +
                           "/book/filters/exactpixels.lua' '" + (root / file).string() +
                           "'");
    }
};

// Every chapter opens with what the reader will be able to do (checked by the filter).
const std::string title =
    "# Demo\n\n::: objectives\n- read the demo\n:::\n\nSome text.\n\n";

// The text of an HTML fragment with every tag removed (highlighting splits code into
// spans).
std::string without_tags(const std::string& html) {
    std::string text;
    bool in_tag = false;
    for (char c : html) {
        if (c == '<')
            in_tag = true;
        else if (c == '>')
            in_tag = false;
        else if (!in_tag)
            text += c;
    }
    return text;
}

} // namespace

TEST_CASE("a listing is the source region minus every marker and stub line") {
    FixtureBook book;
    const auto result =
        book.render(title + "```{.snippet file=\"src/demo.hpp\" name=\"answer\"}\n```\n");
    REQUIRE(result.exit_code == 0);
    const std::string text = without_tags(result.out);
    // Dedented by the region's common indent; exercise markers and the stub are gone.
    CHECK(text.find("int answer() {") != std::string::npos);
    CHECK(text.find("return 42;") != std::string::npos);
    CHECK(text.find("return 0;") == std::string::npos);
    CHECK(text.find("exercise") == std::string::npos);
    CHECK(text.find("before") == std::string::npos);
    CHECK(text.find("after") == std::string::npos);
    CHECK(text.find("Listing\u00a07.1:") != std::string::npos);
    CHECK(result.out.find("src/demo.hpp") != std::string::npos);
}

TEST_CASE(
    "the course edition shows an exercise region as its stub, named by its number") {
    FixtureBook book;
    book.write("chapters/07-demo/chapter.md",
               title + "```{.snippet file=\"src/demo.hpp\" name=\"answer\"}\n```\n\n"
                       "```{.snippet file=\"src/demo.hpp\" name=\"twice-answer\"}\n```\n\n"
                       "## Notes\n\n::: summary\n- the answer\n:::\n\n## Exercises\n\n"
                       "1. []{.exercise kind=derive marks=1 difficulty=easy "
                       "objectives=\"1\"} Think.\n"
                       "2. []{.exercise kind=implement marks=2 region=ch07-demo "
                       "difficulty=medium objectives=\"1\"} Write.\n");
    const auto course = book.run_filter("chapters/07-demo/chapter.md", "html",
                                        "EP_CHAPTERS=07-demo EP_COURSE=1");
    REQUIRE(course.exit_code == 0);
    const std::string text = without_tags(course.out);
    // The kit's view of the region: its stub between comments naming exercise 7.2; none
    // of the solution. The code around the region is kept.
    CHECK(text.find("int answer() {") != std::string::npos);
    CHECK(text.find("// Exercise 7.2 (ch07-demo): your code here.") != std::string::npos);
    CHECK(text.find("// Hint: return the answer") != std::string::npos);
    CHECK(text.find("return 0;") != std::string::npos);
    CHECK(text.find("// End of exercise 7.2 (ch07-demo).") != std::string::npos);
    CHECK(text.find("return 42;") == std::string::npos);
    // A gives-away block (code outside the region that states its answer) is its stub.
    CHECK(text.find("int twice_answer() {") != std::string::npos);
    CHECK(text.find("// (Left out here: it would answer exercise 7.2.)\n"
                    "    return 2 * answer();") != std::string::npos);
    CHECK(text.find("2 * 42") == std::string::npos);
    // The same chapter in the public book: the solution, no stub.
    const auto public_book =
        book.run_filter("chapters/07-demo/chapter.md", "html", "EP_CHAPTERS=07-demo");
    REQUIRE(public_book.exit_code == 0);
    CHECK(without_tags(public_book.out).find("return 42;") != std::string::npos);
    CHECK(without_tags(public_book.out).find("return 2 * 42;") != std::string::npos);
    CHECK(without_tags(public_book.out).find("answer();") == std::string::npos);
    CHECK(without_tags(public_book.out).find("Exercise 7.2") == std::string::npos);
    CHECK(without_tags(public_book.out).find("Left out") == std::string::npos);
}

TEST_CASE("a missing snippet region fails naming the chapter file, line and region") {
    FixtureBook book;
    const auto result = book.render(
        title + "```{.snippet file=\"src/demo.hpp\" name=\"no-such-region\"}\n```\n");
    CHECK(result.exit_code != 0);
    CHECK(result.err.find("chapters/07-demo/chapter.md:9: error:") != std::string::npos);
    CHECK(result.err.find("no-such-region") != std::string::npos);
}

TEST_CASE("a missing snippet file fails naming the file") {
    FixtureBook book;
    const auto result =
        book.render(title + "```{.snippet file=\"src/gone.hpp\" name=\"answer\"}\n```\n");
    CHECK(result.exit_code != 0);
    CHECK(result.err.find("chapters/07-demo/chapter.md:9: error:") != std::string::npos);
    CHECK(result.err.find("src/gone.hpp") != std::string::npos);
}

TEST_CASE("a hand-typed code block is refused, a pseudo-code block is allowed") {
    FixtureBook book;
    CHECK(book.render(title + "```cpp\nint x;\n```\n").exit_code != 0);
    CHECK(book.render(title + "```\nint x;\n```\n").exit_code != 0);
    CHECK(book.render(title + "```{.pseudocode}\nfor each pixel\n```\n").exit_code == 0);
}

TEST_CASE("equations are numbered per chapter and references resolve") {
    FixtureBook book;
    const auto result = book.render(title + "$$ a = b $$ {#eq:first}\n\n"
                                            "$$ c = d $$ {#eq:second}\n\n"
                                            "See @eq:second and @sec:part.\n\n"
                                            "## Part {#sec:part}\n");
    REQUIRE(result.exit_code == 0);
    CHECK(result.out.find("(7.1)") != std::string::npos);
    CHECK(result.out.find("href=\"#eq:second\"") != std::string::npos);
    CHECK(result.out.find(">(7.2)</a>") != std::string::npos);
    CHECK(result.out.find(">Section\u00a07.1</a>") != std::string::npos);
}

TEST_CASE("an unknown reference fails naming the line") {
    FixtureBook book;
    const auto result = book.render(title + "See @eq:nowhere.\n");
    CHECK(result.exit_code != 0);
    CHECK(result.err.find("chapters/07-demo/chapter.md:9: error:") != std::string::npos);
    CHECK(result.err.find("eq:nowhere") != std::string::npos);
}

TEST_CASE("a named test must exist in the named file") {
    FixtureBook book;
    const auto good =
        book.render(title + "[the answer is 42]{.test file=\"tests/ch07_demo.cpp\"}\n");
    REQUIRE(good.exit_code == 0);
    CHECK(good.out.find("ch07_demo.cpp.html#src-1") != std::string::npos);
    const auto bad =
        book.render(title + "[the answer is 41]{.test file=\"tests/ch07_demo.cpp\"}\n");
    CHECK(bad.exit_code != 0);
    CHECK(bad.err.find("the answer is 41") != std::string::npos);
    // clang-format may move a long name to the line after "TEST_CASE(".
    const auto wrapped = book.render(
        title + "[a name too long for one line]{.test file=\"tests/ch07_demo.cpp\"}\n");
    CHECK(wrapped.exit_code == 0);
    CHECK(wrapped.out.find("ch07_demo.cpp.html#src-2") != std::string::npos);
    // or split it into adjacent string literals, which C++ joins.
    const auto split =
        book.render(title + "[a name split by clang-format into two string "
                            "literals]{.test file=\"tests/ch07_demo.cpp\"}\n");
    CHECK(split.exit_code == 0);
    CHECK(split.out.find("ch07_demo.cpp.html#src-4") != std::string::npos);
}

TEST_CASE("in LaTeX a named test is set in the lighter \\eptest face, in HTML a link") {
    FixtureBook book;
    book.write("chapters/07-demo/chapter.md",
               title +
                   "So [the answer is 42]{.test file=\"tests/ch07_demo.cpp\"} holds.\n");
    const auto latex =
        book.run_filter("chapters/07-demo/chapter.md", "latex", "EP_CHAPTERS=07-demo");
    REQUIRE(latex.exit_code == 0);
    CHECK(latex.out.find("\\eptest{the answer is 42}") != std::string::npos);
    CHECK(latex.out.find("\\texttt{the") == std::string::npos);
    CHECK(latex.out.find("\\textbf{the") == std::string::npos);
}

TEST_CASE("in LaTeX a table's columns are sized from its words, never split inside one") {
    FixtureBook book;
    // Pandoc would give the seven columns of this long pipe table one seventh each, and
    // break "subdivided-16" in the first.
    const std::string wide =
        "| mapper | ns/px | × affine | worst (texels) | mean (texels) | differing | "
        "front "
        "|\n|:--|--:|--:|--:|--:|--:|:-:|\n"
        "| subdivided-16 fixed +rule | 6.90 | 1.42 | 0.000123 | 0 | 50.00 % | yes |\n"
        "| affine | 4.87 | 1.00 | 0 | 0 | 50.00 % |  |\n\n: A wide table.\n\n"
        "| a | b |\n|---|---|\n| x | y |\n\n: A narrow table.\n";
    book.write("chapters/07-demo/chapter.md", title + wide);
    const auto latex =
        book.run_filter("chapters/07-demo/chapter.md", "latex", "EP_CHAPTERS=07-demo");
    REQUIRE(latex.exit_code == 0);
    // The narrow table: natural widths, nothing wraps.
    CHECK(latex.out.find("\\begin{longtable}[]{@{}ll@{}}") != std::string::npos);
    // The wide one: fractions of the line, the name column the widest and wide enough
    // for its longest row (26 characters of about 4.6 pt in 439 pt less 6 gaps of 12).
    std::vector<double> widths;
    const std::string key = "\\real{";
    for (auto at = latex.out.find(key); at != std::string::npos;
         at = latex.out.find(key, at + 1)) {
        widths.push_back(std::stod(latex.out.substr(at + key.size())));
    }
    REQUIRE(widths.size() == 7);
    CHECK(std::max_element(widths.begin(), widths.end()) == widths.begin());
    CHECK(widths[0] * (439 - 6 * 12) >= 26 * 4.6);
    double sum = 0;
    for (const double w : widths) {
        CHECK(w > 0);
        sum += w;
    }
    CHECK(sum <= 1.0001);
}

TEST_CASE("a figure the build did not make fails the book") {
    FixtureBook book;
    const auto missing = book.render(title + "![A figure.](ch07_none.png){#fig:none}\n");
    CHECK(missing.exit_code != 0);
    CHECK(missing.err.find("ch07_none.png") != std::string::npos);
    book.write("figures/ch07_made.png", "png");
    const auto made = book.render(title + "![A figure.](ch07_made.png){#fig:made}\n");
    CHECK(made.exit_code == 0);
    CHECK(made.out.find("Figure\u00a07.1:") != std::string::npos);
}

TEST_CASE("an index term is plain text in HTML and an \\index entry in LaTeX") {
    FixtureBook book;
    const std::string text =
        title + "The [Top-left fill rule]{.index} decides, and so does "
                "[the affine one]{.index term=\"texture mapping!affine\"}.\n";
    const auto html = book.render(text);
    REQUIRE(html.exit_code == 0);
    CHECK(html.out.find("The Top-left fill rule decides") != std::string::npos);
    CHECK(html.out.find("index") == std::string::npos);
    book.write("chapters/07-demo/chapter.md", text);
    const auto latex =
        book.run_filter("chapters/07-demo/chapter.md", "latex", "EP_CHAPTERS=07-demo");
    REQUIRE(latex.exit_code == 0);
    // Sorted by a plain lower-case key, shown as written; "!" makes a sub-entry.
    CHECK(latex.out.find(
              "Top-left fill rule\\index{topleft fill rule@Top-left fill rule}") !=
          std::string::npos);
    CHECK(latex.out.find("\\index{texture mapping@texture mapping!affine@affine}") !=
          std::string::npos);
}

TEST_CASE("the contents page lists every chapter and numbered section with links") {
    FixtureBook book;
    book.write("chapters/07-demo/chapter.md", title +
                                                  "## Part {#sec:part}\n\nText.\n\n"
                                                  "### Detail\n\nText.\n\n"
                                                  "## Exercises {.unnumbered}\n\nDo.\n");
    book.write("contents.md", "# Contents\n\n::: contents\n:::\n\nSee @sec:part.\n");
    const auto result = book.run_filter(
        "contents.md", "html", "EP_PAGE='" + (book.root / "contents.md").string() + "'");
    REQUIRE(result.exit_code == 0);
    std::string text = without_tags(result.out);
    std::replace(text.begin(), text.end(), '\n', ' ');
    CHECK(result.out.find("href=\"07-demo.html\"") != std::string::npos);
    CHECK(text.find("7 Demo") != std::string::npos);
    CHECK(result.out.find("href=\"07-demo.html#sec:part\"") != std::string::npos);
    CHECK(text.find("7.1 Part") != std::string::npos);
    // Level 3 and unnumbered headings stay out of the contents.
    CHECK(text.find("Detail") == std::string::npos);
    CHECK(text.find("Exercises") == std::string::npos);
    // A reference from a page that is not a chapter goes to the chapter's page.
    CHECK(result.out.find(
              "href=\"07-demo.html#sec:part\" class=\"ref\">Section\u00a07.1</a>") !=
          std::string::npos);
}

TEST_CASE("a chapter's summary stands before its exercises, a box in HTML and LaTeX") {
    FixtureBook book;
    const std::string summary = "::: summary\n- what was derived\n:::\n\n";
    const std::string body = "## Part\n\nText.\n\n";
    const std::string exercises = "## Exercises\n\nDo.\n";
    // HTML: a div the stylesheet heads "In short"; LaTeX: the epsummary environment.
    const auto html = book.render(title + body + summary + exercises);
    REQUIRE(html.exit_code == 0);
    CHECK(html.out.find("<div class=\"summary\">") != std::string::npos);
    book.write("chapters/07-demo/chapter.md", title + body + summary + exercises);
    const auto latex =
        book.run_filter("chapters/07-demo/chapter.md", "latex", "EP_CHAPTERS=07-demo");
    REQUIRE(latex.exit_code == 0);
    const auto begin = latex.out.find("\\begin{epsummary}");
    const auto item = latex.out.find("what was derived");
    const auto end = latex.out.find("\\end{epsummary}");
    CHECK(begin < item);
    CHECK(item < end);
    CHECK(end < latex.out.find("Exercises"));
    // Missing, misplaced or doubled, it fails naming the chapter file and line.
    const auto missing = book.render(title + body + exercises);
    CHECK(missing.exit_code != 0);
    CHECK(missing.err.find("chapters/07-demo/chapter.md:13: error:") !=
          std::string::npos);
    CHECK(missing.err.find("::: summary") != std::string::npos);
    const auto early = book.render(title + summary + body + exercises);
    CHECK(early.exit_code != 0);
    CHECK(early.err.find("directly before") != std::string::npos);
    CHECK(book.render(title + body + summary + summary + exercises).exit_code != 0);
    CHECK(book.render(title + body + exercises + summary).exit_code != 0);
    CHECK(book.render(title + body + summary).exit_code != 0);
    // A chapter without exercises (a fixture, a draft) needs none.
    CHECK(book.render(title + body).exit_code == 0);
}

TEST_CASE(
    "fence text that would reach the page fails naming its lines, in both editions") {
    FixtureBook book;
    const auto has = [](const std::string& text, const std::string& what) {
        return text.find(what) != std::string::npos;
    };
    // Chapter 3's erratum box as it was: its closing fence shared a line with the next
    // paragraph, so Pandoc read no box and the page showed "::: erratum ... ::: The".
    const auto broken = book.render(title + "::: erratum\n"               // line 9
                                            "The source is wrong here.\n" // line 10
                                            "::: The parabola $u$ through\n"
                                            "three points.\n");
    CHECK(broken.exit_code != 0);
    CHECK(has(broken.err, "chapters/07-demo/chapter.md:9: error: fence text reaches the "
                          "page: '::: erratum The source"));
    CHECK(has(broken.err, "chapters/07-demo/chapter.md:11: error: fence text reaches the "
                          "page: '::: The parabola'"));
    // Closed on a line of its own, the same box is a box and no fence shows.
    const auto fixed =
        book.render(title + "::: erratum\nThe source is wrong here.\n:::\n\n"
                            "The parabola $u$ through\nthree points.\n");
    REQUIRE(fixed.exit_code == 0);
    CHECK(has(fixed.out, "class=\"erratum\""));
    CHECK_FALSE(has(fixed.out, ":::"));
    // A code fence left in a line of text, and a broken fence inside a solution (which
    // the student book drops, the teacher's edition shows): both fail.
    const auto stray = book.render(title + "A stray ```{.text} fence.\n");
    CHECK(stray.exit_code != 0);
    CHECK(
        has(stray.err, "chapter.md:9: error: fence text reaches the page: '```{.text}"));
    const auto in_solution =
        book.render(title + "## Exercises\n\n"
                            "1. []{.exercise kind=derive marks=1 difficulty=easy "
                            "objectives=\"1\"} Do.\n\n"
                            "   ::: solution\n"
                            "   Done.\n"
                            "   ::: Then more.\n");
    CHECK(in_solution.exit_code != 0);
    CHECK(has(in_solution.err,
              "chapter.md:15: error: fence text reaches the page: '::: Then"));
    // Fences in code are code, not fence text.
    const auto code = book.render(title + "Open one with `::: solution`.\n\n"
                                          "```{.text}\n::: shown as typed\n```\n");
    CHECK(code.exit_code == 0);
}

TEST_CASE("a page that is not a chapter reports errors with its own file name") {
    FixtureBook book;
    book.write("page.md", "# A page\n\nSee @sec:nowhere.\n");
    const auto result = book.run_filter(
        "page.md", "html", "EP_PAGE='" + (book.root / "page.md").string() + "'");
    CHECK(result.exit_code != 0);
    CHECK(result.err.find("page.md:3: error:") != std::string::npos);
    CHECK(result.err.find("sec:nowhere") != std::string::npos);
    book.write("page.md", "# A page\n\n::: note\nText.\n::: More text.\n");
    const auto fence = book.run_filter(
        "page.md", "html", "EP_PAGE='" + (book.root / "page.md").string() + "'");
    CHECK(fence.exit_code != 0);
    CHECK(fence.err.find("page.md:5: error: fence text reaches the page: '::: More "
                         "text.'") != std::string::npos);
}

TEST_CASE("headings without an explicit label may repeat from chapter to chapter") {
    FixtureBook book;
    fs::create_directories(book.root / "chapters" / "08-more");
    book.write("chapters/08-more/chapter.md", "# More\n\n## Exercises\n\nDo.\n");
    book.write("chapters/07-demo/chapter.md",
               title + "::: summary\n- it is a demo\n:::\n\n## Exercises\n\nDo.\n");
    const auto result = book.run_filter("chapters/07-demo/chapter.md", "html",
                                        "EP_CHAPTERS=07-demo", "07-demo 08-more");
    CHECK(result.exit_code == 0);
    CHECK(result.err.find("defined twice") == std::string::npos);
}

TEST_CASE("plain parentheses in HTML math do not stretch; \\left and \\right do") {
    FixtureBook book;
    const auto plain = book.render(title + "A point $(x_k, y_k)$.\n");
    REQUIRE(plain.exit_code == 0);
    CHECK(plain.out.find("<math") != std::string::npos);
    CHECK(plain.out.find("stretchy=\"false\" form=\"prefix\">(") != std::string::npos);
    CHECK(plain.out.find("stretchy=\"true\"") == std::string::npos);
    const auto fenced = book.render(title + "A point $\\left(\\frac{a}{b}\\right)$.\n");
    REQUIRE(fenced.exit_code == 0);
    CHECK(fenced.out.find("stretchy=\"true\"") != std::string::npos);
}

TEST_CASE("a claim the data contradicts fails naming the chapter line and the claim") {
    FixtureBook book;
    const std::string claim =
        title + "Text.\n\nEvery variant [beats the naive rasterizer at 3 px]{.claim "
                "data=\"ch07_facts.txt\" check=\"float8x8_over_naive_3px > 1\"}.\n";
    // The data agrees: the text is shown as written, with no trace of the markup.
    book.write("figures/ch07_facts.txt", "# speed over naive, 3 px\n"
                                         "float8x8_over_naive_3px 1.24\n");
    const auto agreed = book.render(claim);
    REQUIRE(agreed.exit_code == 0);
    CHECK(agreed.out.find("beats the naive rasterizer at 3 px") != std::string::npos);
    CHECK(agreed.out.find("claim") == std::string::npos);
    // The same claim on altered data fails the book, naming line 7 and quoting it.
    book.write("figures/ch07_facts.txt", "float8x8_over_naive_3px 0.81\n");
    const auto contradicted = book.render(claim);
    CHECK(contradicted.exit_code != 0);
    CHECK(contradicted.err.find(
              "chapters/07-demo/chapter.md:11: error: claim contradicted") !=
          std::string::npos);
    CHECK(contradicted.err.find("beats the naive rasterizer at 3 px") !=
          std::string::npos);
    CHECK(contradicted.err.find("0.81") != std::string::npos);
    // Facts can be compared with each other, and several conditions must all hold.
    book.write("figures/ch07_facts.txt", "fixed 3.0\ndouble 2.5\n");
    CHECK(book.render(title + "[fixed is slower]{.claim data=\"ch07_facts.txt\" "
                              "check=\"fixed > double; fixed < 4\"}\n")
              .exit_code == 0);
    CHECK(book.render(title + "[fixed is faster]{.claim data=\"ch07_facts.txt\" "
                              "check=\"fixed > double; fixed < double\"}\n")
              .exit_code != 0);
}

TEST_CASE("a claim on missing data or an unknown name fails the book") {
    FixtureBook book;
    const auto missing = book.render(
        title + "[a claim]{.claim data=\"ch07_gone.txt\" check=\"speed > 1\"}\n");
    CHECK(missing.exit_code != 0);
    CHECK(missing.err.find("ch07_gone.txt") != std::string::npos);
    book.write("figures/ch07_facts.txt", "speed 2\n");
    const auto unknown = book.render(
        title + "[a claim]{.claim data=\"ch07_facts.txt\" check=\"sped > 1\"}\n");
    CHECK(unknown.exit_code != 0);
    CHECK(unknown.err.find("chapters/07-demo/chapter.md:9: error:") != std::string::npos);
    CHECK(unknown.err.find("sped") != std::string::npos);
}

TEST_CASE("a fact span shows the measured value, formatted") {
    FixtureBook book;
    book.write("figures/ch07_facts.txt", "share 0.1834\n");
    const auto result = book.render(
        title + "It is []{.fact data=\"ch07_facts.txt\" name=\"share\" format=\"%.2f\"} "
                "of it.\n");
    REQUIRE(result.exit_code == 0);
    CHECK(result.out.find("It is 0.18 of it.") != std::string::npos);
    CHECK(book.render(title + "[]{.fact data=\"ch07_facts.txt\" name=\"nope\"}\n")
              .exit_code != 0);
}

TEST_CASE("a claim can be checked against a committed Markdown table") {
    FixtureBook book;
    fs::create_directories(book.root / "chapters" / "07-demo");
    book.write("chapters/07-demo/results.md", "Measured 2026-11-21.\n\n"
                                              "| run | instructions per pixel |\n"
                                              "|:--|--:|\n"
                                              "| floor/exact_fixed | 139.9 |\n"
                                              "| floor/exact_double | 124.8 |\n");
    const std::string claim =
        title +
        "[exact fixed costs more work]{.claim data=\"chapters/07-demo/results.md\" "
        "check=\"floor/exact_fixed > floor/exact_double\"}\n";
    CHECK(book.render(claim).exit_code == 0);
    book.write("chapters/07-demo/results.md", "| run | instructions per pixel |\n"
                                              "|:--|--:|\n"
                                              "| floor/exact_fixed | 119.9 |\n"
                                              "| floor/exact_double | 124.8 |\n");
    const auto contradicted = book.render(claim);
    CHECK(contradicted.exit_code != 0);
    CHECK(contradicted.err.find(
              "chapters/07-demo/chapter.md:9: error: claim contradicted") !=
          std::string::npos);
    CHECK(contradicted.err.find("exact fixed costs more work") != std::string::npos);
}

TEST_CASE(
    "a bibliography key is left for citeproc; a generated caption's reference resolves") {
    FixtureBook book;
    const auto cited = book.render(title + "Edge functions [@pineda1988].\n");
    REQUIRE(cited.exit_code == 0);
    CHECK(cited.out.find("data-cites=\"pineda1988\"") != std::string::npos);
    book.write("figures/ch07_table.md",
               "| a |\n|---|\n| 1 |\n\n: See @eq:first. {#tbl:t}\n");
    const auto generated =
        book.render(title + "$$ a = b $$ {#eq:first}\n\n"
                            "```{.generated file=\"ch07_table.md\"}\n```\n");
    REQUIRE(generated.exit_code == 0);
    CHECK(generated.out.find("href=\"#eq:first\"") != std::string::npos);
}

TEST_CASE(
    "committed tables name rows by scene and column; checks may scale and add facts") {
    FixtureBook book;
    book.write("chapters/07-demo/run.md", "Measured 2026-11-21 on x86_64.\n\n"
                                          ": Scene \"floor\" (35624 pixel writes).\n\n"
                                          "| mapper | ns/px | × affine | front |\n"
                                          "|:--|--:|--:|:-:|\n"
                                          "| affine fixed | 5.77 | 1.00 |  |\n"
                                          "| exact double | 13.12 | 2.27 | yes |\n");
    const auto render = [&](const std::string& check) {
        return book.render(
            title + "[a claim]{.claim data=\"chapters/07-demo/run.md\" check=\"" + check +
            "\"} and []{.fact data=\"chapters/07-demo/run.md\" "
            "name=\"floor/exact_double#3\" format=\"%.2f\"} times.\n");
    };
    const auto good = render("floor/exact_double#2 <= 2.5*floor/affine_fixed#2; "
                             "floor/exact_double#2+floor/affine_fixed#2 > 18");
    REQUIRE(good.exit_code == 0);
    CHECK(good.out.find("a claim and 2.27 times.") != std::string::npos);
    const auto bad = render("floor/exact_double#2 <= 2*floor/affine_fixed#2");
    CHECK(bad.exit_code != 0);
    CHECK(bad.err.find("claim contradicted by chapters/07-demo/run.md") !=
          std::string::npos);
}

TEST_CASE("an exercise's tag names its difficulty, the objectives it checks and, for a "
          "kit's exercise, its points there; a tag without them fails") {
    FixtureBook book;
    const std::string two_objectives =
        "# Demo\n\n::: objectives\n- read the demo\n- write the demo\n:::\n\nText.\n\n"
        "::: summary\n- the demo\n:::\n\n## Exercises\n\n";
    const auto good = book.render(
        two_objectives + "1. []{.exercise kind=derive marks=1 difficulty=easy "
                         "objectives=\"2\"} Think.\n"
                         "2. []{.exercise kind=implement marks=2 region=ch07-demo "
                         "difficulty=hard objectives=\"1,2\"} Write.\n");
    INFO(good.err);
    REQUIRE(good.exit_code == 0);
    // Pandoc wraps its output lines: one space for every run of white space.
    std::string text;
    for (const char c : without_tags(good.out)) {
        const bool space = c == ' ' || c == '\n';
        if (!space || text.empty() || text.back() != ' ') {
            text += space ? ' ' : c;
        }
    }
    CHECK(text.find("[derive, 1 mark, easy; objective 2]") != std::string::npos);
    // Ten points a mark, from book/metadata.yaml: make-kit check holds the kit to it.
    CHECK(
        text.find("[implement, 2 marks, hard; 20 points in the kit; objectives 1, 2]") !=
        std::string::npos);
    // The objectives are numbered, as the tags name them.
    CHECK(good.out.find("<ol") != std::string::npos);

    const auto no_difficulty =
        book.render(two_objectives +
                    "1. []{.exercise kind=derive marks=1 objectives=\"1\"} Think.\n");
    CHECK(no_difficulty.exit_code != 0);
    CHECK(no_difficulty.err.find("exercise 1: difficulty must be easy, medium or hard, "
                                 "not 'nil'") != std::string::npos);
    const auto no_objectives = book.render(
        two_objectives + "1. []{.exercise kind=derive marks=1 difficulty=easy} Think.\n");
    CHECK(no_objectives.exit_code != 0);
    CHECK(no_objectives.err.find("exercise 1: objectives=\"\" must list") !=
          std::string::npos);
    const auto unknown = book.render(
        two_objectives + "1. []{.exercise kind=derive marks=1 difficulty=easy "
                         "objectives=\"1,3\"} Think.\n");
    CHECK(unknown.exit_code != 0);
    CHECK(unknown.err.find("(1 to 2) of the chapter's objectives") != std::string::npos);
}
