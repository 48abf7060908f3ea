// The HTML book as a reader's browser shows it: every page of build/book/ (chapters,
// contents, appendices and the source pages of named tests) is opened in headless
// Chromium, and the check fails on a broken link or image, a console error, math that did
// not render, or a listing or equation wider than its box. The first screen of every
// top-level page is saved in build/book/screenshots/ for a person to look at. The same
// check runs on each edition (build/book-course/ and build/book-teacher/ too,
// bookcheck_editions.hpp), whose links must resolve inside its own folder.
//
// These tests need the built book, so they carry the CTest label `bookcheck` and run in
// the `book` workflow after the book is rendered (cmake --workflow --preset book), never
// in the `test` workflow.
#include "bookcheck_cdp.hpp"
#include "bookcheck_editions.hpp"

#include "support/text_file.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using exactpixels::bookcheck::Browser;
using exactpixels::bookcheck::Json;
using exactpixels::bookcheck::PageVisit;

namespace {

// The viewport of the screenshots and of the "wider than its box" check: a laptop screen.
constexpr int viewport_width = 1200;
constexpr int viewport_height = 900;

using exactpixels::testing::read_text;

std::string percent_decode(const std::string& text) {
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '%' && i + 2 < text.size()) {
            out += static_cast<char>(std::stoi(text.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += text[i];
        }
    }
    return out;
}

// What the check found in one book folder.
struct BookReport {
    std::vector<std::string> problems; // "page: what is wrong"
    int pages = 0;
    int links = 0;
    int external_links = 0; // http(s)/mailto links: not followed (no network)
    int images = 0;
    std::vector<fs::path> screenshots;
};

// The pages a reader reaches: every .html at the top of `book` and in book/source/.
// (The Doxygen API reference in book/api/ is Doxygen's own; links into it are checked.)
std::vector<fs::path> pages_of(const fs::path& book) {
    std::vector<fs::path> pages;
    for (const fs::path& folder : {book, book / "source"}) {
        if (!fs::is_directory(folder)) {
            continue;
        }
        for (const auto& entry : fs::directory_iterator(folder)) {
            if (entry.path().extension() == ".html") {
                pages.push_back(entry.path());
            }
        }
    }
    std::sort(pages.begin(), pages.end());
    return pages;
}

// Opens every page of `book` in Chromium and lists what a reader would find broken.
BookReport check_html_book(const fs::path& book, const fs::path& screenshots) {
    BookReport report;
    const std::string script =
        read_text(fs::path(EXACTPIXELS_SOURCE_DIR) / "book/checks/page_check.js");
    REQUIRE_MESSAGE(!script.empty(), "book/checks/page_check.js is missing");
    const fs::path root = fs::canonical(book);

    std::map<fs::path, std::set<std::string>> ids_of; // page -> its anchors
    std::vector<std::pair<fs::path, Json>> visits;
    {
        Browser browser(fs::temp_directory_path() /
                            ("exactpixels-chromium-" + std::to_string(::getpid())),
                        viewport_width, viewport_height);
        for (const auto& page : pages_of(root)) {
            const bool top_level = page.parent_path() == root;
            const fs::path shot =
                top_level ? screenshots / (page.stem().string() + ".png") : fs::path();
            const PageVisit visit = browser.open("file://" + page.string(), script, shot);
            const std::string name = fs::relative(page, root).string();
            ++report.pages;
            if (!visit.error.empty()) {
                report.problems.push_back(name + ": cannot open: " + visit.error);
                continue;
            }
            if (!shot.empty()) {
                report.screenshots.push_back(shot);
            }
            for (const auto& line : visit.console) {
                report.problems.push_back(name + ": " + line);
            }
            const Json& r = visit.result;
            for (const auto& image : r["images"].array) {
                ++report.images;
                if (!image["ok"].boolean) {
                    report.problems.push_back(name + ": broken image " +
                                              image["url"].str());
                }
            }
            for (const auto& text : r["rawTex"].array) {
                report.problems.push_back(name + ": math not rendered: " + text.str());
            }
            for (const auto& text : r["mathErrors"].array) {
                report.problems.push_back(name + ": " + text.str());
            }
            for (const auto& box : r["wide"].array) {
                report.problems.push_back(
                    name + ": " + box["what"].str() + " wider than its box (" +
                    std::to_string(static_cast<int>(box["scroll"].number)) + " px in " +
                    std::to_string(static_cast<int>(box["client"].number)) + " px at a " +
                    std::to_string(viewport_width) +
                    " px wide window): " + box["text"].str());
            }
            for (const auto& box : r["tall"].array) {
                report.problems.push_back(
                    name + ": equation taller than its box (" +
                    std::to_string(static_cast<int>(box["scroll"].number)) + " px in " +
                    std::to_string(static_cast<int>(box["client"].number)) +
                    " px): " + box["text"].str());
            }
            for (const auto& cell : r["wrapped"].array) {
                report.problems.push_back(
                    name + ": table cell wraps a single word over " +
                    std::to_string(static_cast<int>(cell["lines"].number)) +
                    " lines: " + cell["text"].str());
            }
            for (const auto& heading : r["unnumbered"].array) {
                report.problems.push_back(
                    name + ": unnumbered section heading in a chapter: " + heading.str());
            }
            for (const auto& line : r["fences"].array) {
                report.problems.push_back(
                    name +
                    ": fence text on the page (a ::: or ``` fence not read as one): " +
                    line.str());
            }
            auto& ids = ids_of[page];
            for (const auto& id : r["ids"].array) {
                ids.insert(id.str());
            }
            visits.emplace_back(page, r);
        }
    }

    // Links, once every page's anchors are known.
    for (const auto& [page, r] : visits) {
        const std::string name = fs::relative(page, root).string();
        for (const auto& link : r["links"].array) {
            const std::string& url = link["url"].str();
            ++report.links;
            if (url.rfind("file://", 0) != 0) {
                if (url.rfind("http", 0) == 0 || url.rfind("mailto:", 0) == 0) {
                    ++report.external_links;
                } else {
                    report.problems.push_back(name + ": link to " + url + " (" +
                                              link["text"].str() + ")");
                }
                continue;
            }
            const auto hash = url.find('#');
            fs::path target = percent_decode(
                url.substr(7, hash == std::string::npos ? std::string::npos : hash - 7));
            const std::string anchor =
                hash == std::string::npos ? "" : percent_decode(url.substr(hash + 1));
            if (fs::is_directory(target)) {
                target /= "index.html";
            }
            if (!fs::exists(target)) {
                report.problems.push_back(name + ": broken link to " + target.string() +
                                          " (\"" + link["text"].str() + "\")");
                continue;
            }
            if (anchor.empty()) {
                continue;
            }
            const fs::path key = fs::canonical(target);
            bool found = false;
            if (ids_of.count(key) != 0) {
                found = ids_of[key].count(anchor) != 0;
            } else {
                const std::string html = read_text(key);
                found = html.find("id=\"" + anchor + "\"") != std::string::npos ||
                        html.find("name=\"" + anchor + "\"") != std::string::npos;
            }
            if (!found) {
                report.problems.push_back(name + ": link to a missing anchor " +
                                          fs::relative(key, root).string() + "#" +
                                          anchor + " (\"" + link["text"].str() + "\")");
            }
        }
    }
    return report;
}

bool mentions(const std::vector<std::string>& problems, const std::string& page,
              const std::string& what) {
    return std::any_of(problems.begin(), problems.end(), [&](const std::string& p) {
        return p.rfind(page + ":", 0) == 0 && p.find(what) != std::string::npos;
    });
}

// A two-page book with one of every fault on its first page.
struct BrokenBook {
    fs::path root = fs::temp_directory_path() /
                    ("exactpixels-bookcheck-" + std::to_string(::getpid()));
    BrokenBook() {
        fs::remove_all(root);
        fs::create_directories(root);
        std::ofstream(root / "style.css")
            << "pre { width: 200px; overflow-x: auto; }\n"
               ".equation > p:first-child { height: 4px; overflow: auto; }\n"
               "td { width: 3em; }\n";
        std::ofstream(root / "broken.html")
            << "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\">"
               "<title>t</title><link rel=\"stylesheet\" href=\"style.css\"></head><body>"
               "<h1><span class=\"secnum\">1</span> A chapter</h1>"
               "<h2><span class=\"secnum\">1.1</span> Numbered</h2><h2>Exercises</h2>"
               "<p><a href=\"gone.html\">a missing page</a> "
               "<a href=\"fine.html#nowhere\">a missing anchor</a> "
               "<a href=\"fine.html#here\">a good anchor</a> "
               "<a href=\"#top\">a missing anchor here</a></p>"
               "<p><img src=\"gone.png\" alt=\"a missing image\"></p>"
               "<p>Left as TeX: $$x = \\frac{a}{b}$$</p>"
               "<p><span class=\"math inline\">\\(\\frac{a\\)</span></p>"
               "<p><math><merror><mtext>bad</mtext></merror></math></p>"
               "<pre>" +
                   std::string(120, 'x') +
                   "</pre>"
                   "<div class=\"equation\"><p><math display=\"block\"><mfrac><mi>a</mi>"
                   "<mi>b</mi></mfrac></math></p><p>(1)</p></div>"
                   "<table><tr><td>subdivided-16-fixed-rule</td><td>two "
                   "words</td></tr></table>"
                   // chapter 3's erratum box as it once reached the page
                   "<p>::: erratum\nThe source's listing is wrong.\n::: The parabola "
                   "<math><mi>u</mi></math> through</p>"
                   "<script>console.error('a console error')</script>"
                   "</body></html>\n";
        std::ofstream(root / "fine.html")
            << "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\">"
               "<title>t</title><link rel=\"stylesheet\" href=\"style.css\"></head><body>"
               "<h1><span class=\"secnum\">1</span> A chapter</h1>"
               "<h2><span class=\"secnum\">1.1</span> A section</h2>"
               "<table><tr><td>fixed</td><td>1.25</td></tr></table>"
               "<p id=\"here\">A fine page with <math><mi>x</mi></math> and "
               "<a href=\"broken.html\">a link</a>.</p><pre>short\n::: in a listing</pre>"
               "<p>Open a box with <code>::: erratum</code>,\n<code>:::</code> closes "
               "it.</p></body></html>\n";
    }
    ~BrokenBook() { fs::remove_all(root); }
};

} // namespace

TEST_CASE("the browser check catches each fault a reader would see") {
    BrokenBook book;
    const BookReport report = check_html_book(book.root, book.root / "screenshots");
    for (const auto& p : report.problems) {
        MESSAGE(p);
    }
    CHECK(report.pages == 2);
    CHECK(mentions(report.problems, "broken.html", "broken link to"));
    CHECK(mentions(report.problems, "broken.html", "gone.html"));
    CHECK(mentions(report.problems, "broken.html", "missing anchor fine.html#nowhere"));
    CHECK(mentions(report.problems, "broken.html", "missing anchor broken.html#top"));
    CHECK_FALSE(mentions(report.problems, "broken.html", "#here"));
    CHECK(mentions(report.problems, "broken.html", "broken image"));
    CHECK(mentions(report.problems, "broken.html", "console.error: a console error"));
    CHECK(mentions(report.problems, "broken.html", "math not rendered: Left as TeX"));
    CHECK(mentions(report.problems, "broken.html", "unrendered math"));
    CHECK(mentions(report.problems, "broken.html", "<merror>"));
    CHECK(mentions(report.problems, "broken.html", "listing wider than its box"));
    CHECK(mentions(report.problems, "broken.html", "equation taller than its box"));
    CHECK(mentions(report.problems, "broken.html", "table cell wraps a single word"));
    CHECK(mentions(report.problems, "broken.html", "lines: subdivided-16-fixed-rule"));
    CHECK_FALSE(mentions(report.problems, "broken.html", "two words"));
    CHECK(mentions(report.problems, "broken.html",
                   "unnumbered section heading in a chapter: Exercises"));
    CHECK_FALSE(mentions(report.problems, "broken.html", "chapter: 1.1"));
    CHECK(mentions(report.problems, "broken.html", "fence text on the page"));
    CHECK(mentions(report.problems, "broken.html", "::: erratum"));
    CHECK(mentions(report.problems, "broken.html", "::: The parabola"));
    // The clean page has no problem, and both first screens were saved.
    CHECK_FALSE(
        std::any_of(report.problems.begin(), report.problems.end(),
                    [](const std::string& p) { return p.rfind("fine.html", 0) == 0; }));
    CHECK(report.screenshots.size() == 2);
    for (const auto& shot : report.screenshots) {
        CHECK(fs::file_size(shot) > 1000);
    }
}

// Every edition: the public book, the course edition and the teacher's edition. Each
// links only within its own folder (its API reference included), so a link that
// resolves in one edition and not in another fails here.
TEST_CASE("every page of each edition of the HTML book reads without a fault in a browser") {
    for (const auto& edition : exactpixels::bookcheck::editions) {
        const fs::path book = exactpixels::bookcheck::edition_folder(edition);
        const std::string name = edition.folder; // doctest prints a char* as a pointer
        INFO("edition " << name);
        if (!fs::exists(book / "index.html")) {
            FAIL_CHECK("no " << (book / "index.html").string()
                             << ": build the editions first (cmake --build --preset book)");
            continue;
        }
        const BookReport report = check_html_book(book, book / "screenshots");
        MESSAGE(name << ": checked " << report.pages << " pages, "
                               << report.links << " links (" << report.external_links
                               << " external, not followed), " << report.images
                               << " images; first screens in "
                               << (book / "screenshots").string());
        for (const auto& p : report.problems) {
            FAIL_CHECK(name << "/" << p);
        }
        CHECK(report.problems.empty());
        CHECK(report.pages >= 2);
        CHECK(!report.screenshots.empty());
    }
}
