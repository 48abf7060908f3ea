// The HTML book's live figures (web/, book/filters/live.lua) in a real browser: every
// page with a live figure of each edition (build/book/, build/book-teacher/,
// build/book-course/) is opened from file:// in headless Chromium (no flags), every
// figure must report data-live="ready" within a second of its script's start, and each
// is then driven as a reader would, with a mouse drag (press, moves with the button
// held, release) and with the arrow keys on a focused handle. After each move the
// figure's state (its data-state JSON and the state line under it) must equal what the
// native library gives for the same inputs here, computed by this test: the covered
// pixels and ties of the triangle, the centres on the edge, the rule and the texels, the
// 8 x 8 blocks' verdicts, each pixel's level of detail (to 1e-14: the C libraries may
// round sin, cos, hypot and log2 differently in the last bit), and the scene's image,
// report and per-triangle decisions (web/live_scenes.hpp holds the two figures' inputs
// that are more than numbers). The positions are checked too (the drag must have moved
// the handle to where the test put the mouse), so a figure that shows a stale answer,
// or one computed by anything but the library, fails. Any console error or uncaught
// exception fails; in print media and without JavaScript the live figures are hidden
// and the static figures shown. With EXACTPIXELS_BOOK_URL set (a web server serving
// build/book/, URL ending in /) the same checks run on the served public book.
//
// Label `interactive` (and `bookcheck`: it needs the built book, so it runs in the book
// workflow after `cmake --build --preset book`). Each figure as loaded is saved in
// its edition's screenshots/live-NAME.png (build/book/screenshots/ for the public book).
#include "bookcheck_cdp.hpp"

#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/raster/edge_function.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"
#include "exactpixels/raster/gradients.hpp"
#include "exactpixels/raster/scanline.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "exactpixels/texture/level_of_detail.hpp"
#include "exactpixels/texture/rounding.hpp"
#include "exactpixels/texture/span_mappers.hpp"

#include "../web/live_scenes.hpp"

#include "support/text_file.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdlib>
#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using namespace exactpixels;
using exactpixels::bookcheck::Browser;
using exactpixels::bookcheck::Json;

namespace {

const fs::path book = fs::path(EXACTPIXELS_BINARY_DIR) / "book";

// The editions' folders: the public book, and with `all` the teacher's and the course
// edition (the book workflow builds all three; each has the live figures).
std::vector<fs::path> editions(bool all) {
    std::vector<fs::path> out{book};
    if (all) {
        out.push_back(fs::path(EXACTPIXELS_BINARY_DIR) / "book-teacher");
        out.push_back(fs::path(EXACTPIXELS_BINARY_DIR) / "book-course");
    }
    return out;
}
constexpr double cell = 40; // web/live.js: SVG units per book pixel

using Pixels = std::vector<std::pair<int, int>>;

Pixels pixels_of(const Json& list) {
    Pixels out;
    for (const Json& p : list.array) {
        out.emplace_back(static_cast<int>(p.array.at(0).number),
                         static_cast<int>(p.array.at(1).number));
    }
    std::sort(out.begin(), out.end());
    return out;
}

// What the native library says about the fill-rule figure's triangle: the pixels
// edge_rasterize_pixels covers in the 8 x 7 grid, and the centres on the closed
// triangle's edges that it keeps (won) and gives away (lost).
struct Coverage {
    Pixels pixels;
    int won = 0;
    int lost = 0;
};

Coverage native_coverage(const std::array<Point2, 3>& p) {
    const std::array<FixedPoint2, 3> v = {snap_to_subpixel(p[0]), snap_to_subpixel(p[1]),
                                          snap_to_subpixel(p[2])};
    Coverage c;
    edge_rasterize_pixels(v, Viewport{8, 7}, [&](int x, int y) { c.pixels.emplace_back(x, y); });
    std::sort(c.pixels.begin(), c.pixels.end());
    const std::int64_t area2 = edge_function(v[0], v[1], v[2]);
    if (area2 == 0) {
        return c;
    }
    for (int y = 0; y < 7; ++y) {
        for (int x = 0; x < 8; ++x) {
            // The closed triangle and its edges, from the signed edge functions alone.
            const FixedPoint2 q = fixed_pixel_centre(x, y);
            bool inside = true, on = false;
            for (int i = 0; i < 3; ++i) {
                const std::int64_t e = edge_function(v[(i + 1) % 3], v[(i + 2) % 3], q);
                const std::int64_t oriented = area2 > 0 ? e : -e;
                inside = inside && oriented >= 0;
                on = on || e == 0;
            }
            if (inside && on) {
                const bool kept =
                    std::binary_search(c.pixels.begin(), c.pixels.end(), std::pair{x, y});
                (kept ? c.won : c.lost) += 1;
            }
        }
    }
    return c;
}

// The centres of the 12 x 8 grid on the segment from a to b (whole pixels): in doubled
// coordinates the centre (2x + 1, 2y + 1) is on the line when the cross product is 0,
// and between the ends when its projection is.
Pixels native_edge_centres(std::array<int, 2> a, std::array<int, 2> b) {
    Pixels out;
    const long dx = 2 * (b[0] - a[0]), dy = 2 * (b[1] - a[1]);
    for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 12; ++x) {
            const long px = 2 * x + 1 - 2 * a[0], py = 2 * y + 1 - 2 * a[1];
            const long along = px * dx + py * dy;
            if ((dx != 0 || dy != 0) && px * dy - py * dx == 0 && along >= 0 &&
                along <= dx * dx + dy * dy) {
                out.emplace_back(x, y);
            }
        }
    }
    return out;
}

// The ch04 figure by the library, natively: the rule from the numerator at centre 4, and
// each centre's texel by that rule and by rule 1.
constexpr int no_texel = 9999;

struct TexelRow {
    int rule = 0;
    std::vector<int> texels, rule1;
};

TexelRow native_texels(double dc_dx, double dc_dy, double dq_dx) {
    const ProjectedCoordinate<double> at_4{4.0, 1.0, {dc_dx, dc_dy}, {dq_dx, 0.0}};
    const RoundingRule rule = choose_rule(at_4);
    TexelRow row;
    row.rule = rule == RoundingRule::ties_up ? 1 : 2;
    for (int a = 0; a < 8; ++a) {
        const double q = 1.0 + dq_dx * (a - 4), p = 4.0 + dc_dx * (a - 4);
        if (!(q > 0)) { // behind the eye: no u (the figure shows "-", its state null)
            row.texels.push_back(no_texel);
            row.rule1.push_back(no_texel);
            continue;
        }
        const std::int64_t c = snap_to_subpixel(p / q - 0.5);
        row.texels.push_back(static_cast<int>(round_with_modifier(c, rounding_modifier(rule, 8), 8)));
        row.rule1.push_back(static_cast<int>(
            round_with_modifier(c, rounding_modifier(RoundingRule::ties_up, 8), 8)));
    }
    return row;
}

// The ch03 figure by the library, natively: each mapper's largest |u - exact u| and its
// pixels on another texel, on the span of 64 pixels, 64 texels, depth 1 to r.
struct SpanErrors {
    std::array<double, 4> worst{};
    std::array<int, 4> differing{};
};

SpanErrors native_span(double r) {
    const int count = 64;
    const double n = count - 1;
    const PerspectiveSpan<double> s{0.0, 0.0, 1.0, (64.0 / r) / n, 0.0, (1 / r - 1.0) / n,
                                    count};
    std::array<std::vector<double>, 4> u;
    for (auto& m : u) {
        m.resize(count);
    }
    const auto into = [&](int m) { return [&u, m](int k, double v, double) { u[m][k] = v; }; };
    map_span_exact(s, into(0));
    map_span_affine(AffineSpan<double>{0.0, 0.0, 64.0 / n, 0.0, count}, into(1));
    map_span_quadratic(s, into(2));
    map_span_subdivided(s, 16, into(3));
    SpanErrors e;
    for (int m = 0; m < 4; ++m) {
        for (int k = 0; k < count; ++k) {
            e.worst[m] = std::max(e.worst[m], std::abs(u[m][k] - u[0][k]));
            e.differing[m] += std::floor(u[m][k]) != std::floor(u[0][k]) ? 1 : 0;
        }
    }
    return e;
}

std::vector<int> ints_of(const Json& list) {
    std::vector<int> out;
    for (const Json& v : list.array) {
        out.push_back(v.type == Json::Type::null ? no_texel : static_cast<int>(v.number));
    }
    return out;
}

// One open page with live figures, and the reader's moves on it.
class Page {
public:
    explicit Page(Browser& browser) : browser_(browser) {}

    Json state(const std::string& figure) {
        return bookcheck::parse_json(browser_
            .evaluate("document.getElementById('live-" + figure + "').dataset.state")
            .str());
    }

    std::string line(const std::string& figure) {
        return browser_
            .evaluate("document.querySelector('#live-" + figure + " .live-state').textContent")
            .str();
    }

    // The screen position of handle `index` of the figure, and screen pixels per
    // SVG unit, after scrolling it into view.
    struct Spot {
        double x, y, scale;
    };
    Spot handle(const std::string& figure, int index) {
        const Json r = browser_.evaluate(
            "(() => { const h = document.querySelectorAll('#live-" + figure +
            " .live-handle')[" + std::to_string(index) +
            "]; h.scrollIntoView({block: 'center'}); const b = h.getBoundingClientRect();"
            " return {x: b.left + b.width / 2, y: b.top + b.height / 2,"
            " scale: h.getScreenCTM().a}; })()");
        return {r["x"].number, r["y"].number, r["scale"].number};
    }

    void mouse(const std::string& type, double x, double y, int buttons) {
        browser_.command("Input.dispatchMouseEvent",
                         R"({"type":")" + type + R"(","x":)" + std::to_string(x) +
                             R"(,"y":)" + std::to_string(y) +
                             R"(,"button":"left","clickCount":1,"buttons":)" +
                             std::to_string(buttons) + "}");
    }

    // Presses on the handle, moves in four steps by (dx, dy) screen pixels with the
    // button held, releases; then waits for a frame.
    void drag(const std::string& figure, int index, double dx_units, double dy_units) {
        const Spot s = handle(figure, index);
        mouse("mousePressed", s.x, s.y, 1);
        for (int i = 1; i <= 4; ++i) {
            mouse("mouseMoved", s.x + dx_units * s.scale * i / 4, s.y + dy_units * s.scale * i / 4, 1);
        }
        mouse("mouseReleased", s.x + dx_units * s.scale, s.y + dy_units * s.scale, 0);
        frame();
    }

    void key(const std::string& figure, int index, const std::string& name, int code,
             int times = 1) {
        browser_.evaluate("document.querySelectorAll('#live-" + figure + " .live-handle')[" +
                          std::to_string(index) + "].focus()");
        for (int i = 0; i < times; ++i) {
            for (const char* type : {"rawKeyDown", "keyUp"}) {
                browser_.command("Input.dispatchKeyEvent",
                                 std::string(R"({"type":")") + type + R"(","key":")" + name +
                                     R"(","code":")" + name +
                                     R"(","windowsVirtualKeyCode":)" + std::to_string(code) +
                                     "}");
            }
        }
        frame();
    }

    void frame() {
        browser_.evaluate("new Promise(r => requestAnimationFrame(() => r(true)))");
    }

private:
    Browser& browser_;
};

// Waits (up to 5 s) until every live figure of the page is ready; returns what it saw.
const char* wait_ready = R"js(new Promise((resolve) => {
  const start = performance.now();
  const poll = () => {
    const all = [...document.querySelectorAll('figure[data-live]')];
    const ready = all.filter((f) => f.dataset.live === 'ready').length;
    if ((all.length > 0 && ready === all.length) || performance.now() - start > 5000) {
      resolve({ figures: all.map((f) => f.dataset.figure), ready,
                readyMs: window.exactpixelsLiveReadyMs ?? -1,
                startMs: window.exactpixelsLiveStartMs ?? -1 });
    } else {
      setTimeout(poll, 10);
    }
  };
  poll();
}))js";

// The triangle a figure shows is exactly where the test's moves put it.
void check_vertices(const Json& state, const std::array<Point2, 3>& expected) {
    for (int i = 0; i < 3; ++i) {
        CHECK(state["vertices"].array.at(i).array.at(0).number == expected[i].x);
        CHECK(state["vertices"].array.at(i).array.at(1).number == expected[i].y);
    }
}

void check_fill_rule(Browser& browser, Page& page) {
    const std::string f = "ch02-fill-rule";
    const auto check = [&](std::array<Point2, 3> expected, const char* what) {
        INFO(what);
        const Json s = page.state(f);
        check_vertices(s, expected);
        const Coverage native = native_coverage(expected);
        CHECK(pixels_of(s["pixels"]) == native.pixels);
        CHECK(static_cast<std::size_t>(s["covered"].number) == native.pixels.size());
        CHECK(static_cast<int>(s["tiesWon"].number) == native.won);
        CHECK(static_cast<int>(s["tiesLost"].number) == native.lost);
        const std::string line = page.line(f);
        CHECK_MESSAGE(line.find(std::to_string(native.pixels.size()) + " pixels covered") !=
                          std::string::npos,
                      line);
        return native;
    };
    // As loaded: the chapter's triangle, 15 pixels, with centres on the diagonal kept
    // and centres on the right side given away.
    const Coverage first = check({Point2{0.5, 0.5}, {5.5, 0.5}, {5.5, 5.5}}, "as loaded");
    CHECK(first.pixels.size() == 15);
    CHECK(first.won > 0);
    CHECK(first.lost > 0);
    // v0 dragged by (+1, +1/2) px.
    page.drag(f, 0, 1.0 * cell, 0.5 * cell);
    check({Point2{1.5, 1.0}, {5.5, 0.5}, {5.5, 5.5}}, "v0 dragged by (1, 1/2)");
    // v1 moved down by 1/8 px with the keyboard, twice.
    page.key(f, 1, "ArrowDown", 40, 2);
    check({Point2{1.5, 1.0}, {5.5, 0.75}, {5.5, 5.5}}, "v1 down by 2/8 with the keys");
    (void)browser;
}

void check_scanline(Page& page) {
    const std::string f = "ch01-scanline";
    const auto check = [&](std::array<Point2, 3> v, const char* what) {
        INFO(what);
        const Json s = page.state(f);
        check_vertices(s, v);
        // The spans chapter 1's rasterizer walks, and both gradients, exactly.
        std::vector<std::vector<int>> spans;
        int covered = 0;
        scanline_spans(v, Viewport{12, 9}, [&](Span sp) {
            spans.push_back({sp.y, sp.x_begin, sp.x_end});
            covered += sp.x_end - sp.x_begin;
        });
        std::vector<std::vector<int>> shown;
        for (const Json& sp : s["spans"].array) {
            shown.push_back(ints_of(sp));
        }
        CHECK(shown == spans);
        CHECK(static_cast<int>(s["covered"].number) == covered);
        const std::array<double, 3> c = {0.0, 1.0, 0.5};
        const Gradient<double> closed = closed_form_gradient<double>(v, c);
        const Gradient<double> split = split_edge_gradient<double>(v, c);
        CHECK(s["closedForm"].array.at(0).number == closed.dx);
        CHECK(s["closedForm"].array.at(1).number == closed.dy);
        CHECK(s["splitEdge"].array.at(0).number == split.dx);
        CHECK(s["splitEdge"].array.at(1).number == split.dy);
        const std::string line = page.line(f);
        CHECK_MESSAGE(line.find(std::to_string(spans.size()) + " spans, " +
                                std::to_string(covered) + " pixels covered") !=
                          std::string::npos,
                      line);
    };
    check({Point2{4.25, 0.625}, {11.25, 3.875}, {1.375, 8.25}}, "as loaded");
    page.drag(f, 0, 1.0 * cell, 0.5 * cell);
    check({Point2{5.25, 1.125}, {11.25, 3.875}, {1.375, 8.25}}, "v0 dragged by (1, 1/2)");
    page.key(f, 2, "ArrowLeft", 37, 3);
    check({Point2{5.25, 1.125}, {11.25, 3.875}, {1.0, 8.25}}, "v2 left by 3/8 with the keys");
}

void check_edge_centres(Page& page) {
    const std::string f = "ch00-edge-centres";
    const auto check = [&](std::array<int, 2> a, std::array<int, 2> b, const char* what) {
        INFO(what);
        const Json s = page.state(f);
        CHECK(ints_of(s["a"]) == std::vector<int>{a[0], a[1]});
        CHECK(ints_of(s["b"]) == std::vector<int>{b[0], b[1]});
        const Pixels native = native_edge_centres(a, b);
        CHECK(pixels_of(s["centres"]) == native);
        // The exponents of the largest powers of two dividing dx and dy (-1 for 0).
        const auto twos = [](int d) {
            return d == 0 ? -1 : std::countr_zero(static_cast<unsigned>(d < 0 ? -d : d));
        };
        CHECK(ints_of(s["twos"]) == std::vector<int>{twos(b[0] - a[0]), twos(b[1] - a[1])});
        const std::string line = page.line(f);
        CHECK_MESSAGE(line.find("through " + std::to_string(native.size()) + " pixel centre") !=
                          std::string::npos,
                      line);
        return native.size();
    };
    CHECK(check({1, 1}, {5, 7}, "as loaded") == 0u); // dx = 4, dy = 6
    page.drag(f, 1, 0, -2 * cell);                  // b to (5, 5): dx = dy = 4
    CHECK(check({1, 1}, {5, 5}, "b dragged up 2 px") == 4u);
    page.key(f, 0, "ArrowLeft", 37);                // a to (0, 1): dx = 5, dy = 4
    CHECK(check({0, 1}, {5, 5}, "a left 1 px with the keys") == 0u);
}

void check_texel_rule(Page& page) {
    const std::string f = "ch04-texel-rule";
    const auto check = [&](double dc_dx, double dc_dy, double dq_dx, const char* what) {
        INFO(what);
        const Json s = page.state(f);
        CHECK(s["dcdx"].number == dc_dx);
        CHECK(s["dcdy"].number == dc_dy);
        CHECK(s["dqdx"].number == dq_dx);
        const TexelRow native = native_texels(dc_dx, dc_dy, dq_dx);
        CHECK(static_cast<int>(s["rule"].number) == native.rule);
        CHECK(ints_of(s["texels"]) == native.texels);
        CHECK(ints_of(s["rule1"]) == native.rule1);
        const std::string line = page.line(f);
        CHECK_MESSAGE(line.find("so rule " + std::to_string(native.rule)) != std::string::npos,
                      line);
        return native;
    };
    // As loaded: the texture mirrored (dc/dx = -1), affine: rule 2, every texel of the
    // 8 once; rule 1 alone would sample texel 8, outside the texture, and never 0.
    const TexelRow mirrored = check(-1, 0, 0, "as loaded");
    CHECK(mirrored.rule == 2);
    CHECK(mirrored.texels == std::vector<int>{7, 6, 5, 4, 3, 2, 1, 0});
    CHECK(mirrored.rule1 == std::vector<int>{8, 7, 6, 5, 4, 3, 2, 1});
    // Turned with the keys to dc/dx = +1/2 (six steps of 1/4): rule 1.
    page.key(f, 0, "ArrowRight", 39, 6);
    CHECK(check(0.5, 0, 0, "turned to dc/dx = 1/2").rule == 1);
    // The depth slider dragged to d(1/w)/dx = 1/4 (one unit of the slider is 8 px of
    // the figure): BC - AD = 1/2 - 4/4 < 0 though dc/dx > 0, so rule 2.
    page.drag(f, 1, 0.25 * 8 * cell, 0);
    const TexelRow tilted = check(0.5, 0, 0.25, "depth slope 1/4");
    CHECK(tilted.rule == 2);
    CHECK(tilted.texels.front() == no_texel); // 1/w = 0 at the first centre
}

void check_span_mappers(Page& page) {
    const std::string f = "ch03-span-mappers";
    const auto check = [&](double r, const char* what) {
        INFO(what);
        const Json s = page.state(f);
        CHECK(s["ratio"].number == r);
        const SpanErrors native = native_span(r);
        for (int m = 0; m < 4; ++m) {
            CHECK(s["worst"].array.at(m).number == native.worst[m]);
            CHECK(static_cast<int>(s["differing"].array.at(m).number) == native.differing[m]);
        }
        const std::string line = page.line(f);
        CHECK_MESSAGE(line.find(fmt::format("affine {:.3f} ({} pixels", native.worst[1],
                                            native.differing[1])) != std::string::npos,
                      line);
        return native;
    };
    // As loaded: the chapter's span, r = 4; the affine mapper strays by texels there.
    CHECK(check(4, "as loaded").worst[1] > 1);
    page.drag(f, 0, 4 * 16, 0); // 16 SVG units per unit of r
    check(8, "dragged to r = 8");
    page.key(f, 0, "ArrowLeft", 37, 2);
    check(7.5, "two steps of 1/4 down with the keys");
}


// The ch02 blocks figure by the library, natively: the pixels of the 32 x 24 grid the
// pixel walk covers (edge_rasterize_pixels, not the block walk the figure runs), and
// classify_block's verdict on each 8 x 8 block cut to the bounding box (1 rejected,
// 2 accepted, 3 partial; 4 for a box within one block, walked without a verdict).
struct BlockWalk {
    Pixels pixels;
    std::vector<int> blocks;
};

BlockWalk native_blocks(const std::array<Point2, 3>& p) {
    const std::array<FixedPoint2, 3> v = {snap_to_subpixel(p[0]), snap_to_subpixel(p[1]),
                                          snap_to_subpixel(p[2])};
    BlockWalk w;
    edge_rasterize_pixels(v, Viewport{32, 24}, [&](int x, int y) { w.pixels.emplace_back(x, y); });
    std::sort(w.pixels.begin(), w.pixels.end());
    const EdgeSetup<FixedEdge> s = setup_edges(v);
    const PixelRect box = pixel_bounds(v, Viewport{32, 24});
    const bool one = box.x_end - box.x_begin <= 8 && box.y_end - box.y_begin <= 8;
    for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 4; ++i) {
            const PixelRect b{std::max(8 * i, box.x_begin), std::max(8 * j, box.y_begin),
                              std::min(8 * i + 8, box.x_end), std::min(8 * j + 8, box.y_end)};
            w.blocks.push_back(s.empty || b.empty() ? 0
                               : one                ? 4
                               : classify_block(s, b) == BlockClass::outside ? 1
                               : classify_block(s, b) == BlockClass::inside  ? 2
                                                                             : 3);
        }
    }
    return w;
}

void check_blocks(Page& page) {
    const std::string f = "ch02-blocks";
    const auto check = [&](std::array<Point2, 3> v, const char* what) {
        INFO(what);
        const Json s = page.state(f);
        check_vertices(s, v);
        const BlockWalk native = native_blocks(v);
        CHECK(pixels_of(s["pixels"]) == native.pixels);
        CHECK(ints_of(s["blocks"]) == native.blocks);
        const std::string line = page.line(f);
        CHECK_MESSAGE(line.find(std::to_string(native.pixels.size()) + " pixels covered") !=
                          std::string::npos,
                      line);
        return native;
    };
    // As loaded: blocks of all three verdicts.
    const BlockWalk first = check({Point2{3.5, 2.25}, {29.25, 7.5}, {9.75, 21.5}}, "as loaded");
    for (int verdict : {1, 2, 3}) {
        CHECK(std::count(first.blocks.begin(), first.blocks.end(), verdict) > 0);
    }
    // v2 dragged by (2, -1) px: 20 SVG units per pixel in this figure.
    page.drag(f, 2, 2 * 20.0, -1 * 20.0);
    check({Point2{3.5, 2.25}, {29.25, 7.5}, {11.75, 20.5}}, "v2 dragged by (2, -1)");
    page.key(f, 0, "ArrowRight", 39, 3);
    check({Point2{3.875, 2.25}, {29.25, 7.5}, {11.75, 20.5}}, "v0 right by 3/8 with the keys");
}

// The ch08 figure by the library, natively: the level at every covered pixel centre of
// the tilted floor, and at the image centre beside the closed form.
void check_level(Page& page) {
    const std::string f = "ch08-level";
    const auto check = [&](double tilt, double distance, const char* what) {
        INFO(what);
        const Json s = page.state(f);
        CHECK(s["tilt"].number == tilt);
        CHECK(s["distance"].number == distance);
        const auto floor = live::tilted_floor(tilt, distance);
        const int W = live::floor_width, H = live::floor_height;
        std::vector<double> levels(static_cast<std::size_t>(W * H), 0.0);
        std::vector<bool> covered(levels.size(), false);
        int count = 0;
        for (const auto& t : floor) {
            const std::array<FixedPoint2, 3> v = {snap_to_subpixel(t[0].position),
                                                  snap_to_subpixel(t[1].position),
                                                  snap_to_subpixel(t[2].position)};
            edge_rasterize_pixels(v, Viewport{W, H}, [&](int x, int y) {
                const auto i = static_cast<std::size_t>(y * W + x);
                covered[i] = true;
                levels[i] = isotropic_level(derivatives_at(t, Point2{x + 0.5, y + 0.5}));
                ++count;
            });
        }
        CHECK(static_cast<int>(s["covered"].number) == count);
        const auto& shown = s["levels"].array;
        REQUIRE(shown.size() == levels.size());
        int differ = 0, inexact = 0;
        double worst = 0;
        for (std::size_t i = 0; i < levels.size(); ++i) {
            const bool on = shown[i].type != Json::Type::null;
            differ += on != covered[i] ? 1 : 0;
            if (on && covered[i] && shown[i].number != levels[i]) {
                ++inexact;
                worst = std::max(worst, std::abs(shown[i].number - levels[i]));
            }
        }
        // Coverage exactly; the levels to 1e-14. The module's C library (WASI's, from
        // musl) and glibc may round sin, cos, hypot and log2 differently in the last
        // bit (chapter 0 bounds such differences); seen: up to 2^-51 on levels of
        // about 2, at a few dozen of the pixels.
        CHECK(differ == 0);
        CHECK_MESSAGE(worst <= 1e-14, inexact << " levels differ, by up to " << worst);
        // The level at the centre is the closed form of @sec:level (its test allows 12
        // digits; so does this).
        const Pinhole lens = live::floor_lens();
        const double centre = isotropic_level(derivatives_at(floor[0], lens.centre));
        CHECK(std::abs(s["centre"].number - centre) <= 1e-14);
        const double closed = std::log2(live::floor_texels_per_unit * distance /
                                        (lens.focal * std::cos(tilt * std::acos(-1.0) / 180)));
        CHECK(std::abs(s["closedForm"].number - closed) <= 1e-12 * std::abs(closed) + 1e-12);
        CHECK(std::abs(centre - closed) <= 1e-12 * std::abs(closed) + 1e-12);
        const std::string line = page.line(f);
        CHECK_MESSAGE(line.find(std::to_string(count) + " pixels of floor") != std::string::npos,
                      line);
        return levels;
    };
    check(60, 6, "as loaded");
    // The tilt slider (2.5 SVG units per degree) dragged from 60 to 30 degrees.
    page.drag(f, 0, -30 * 2.5, 0);
    check(30, 6, "tilted back to 30 degrees");
    // The distance slider, two steps of 1/2 up with the keys, then the tilt to 80.
    page.key(f, 1, "ArrowRight", 39, 2);
    check(30, 7, "distance 7 with the keys");
    page.key(f, 0, "ArrowRight", 39, 12);
    check(80, 7, "tilt 80 with the keys (the slider stops there)");
}

// The ch07 figure by the library, natively: the scene rendered by render_scene from the
// same camera, its image and report, and the per-triangle decisions adding up to it.
void check_scene(Page& page) {
    const std::string f = "ch07-scene";
    const auto check = [&](double x, double z, const char* what) {
        INFO(what);
        const Json s = page.state(f);
        CHECK(s["camera"].array.at(0).number == x);
        CHECK(s["camera"].array.at(1).number == z);
        const Scene scene = live::live_scene(x, z);
        const RenderResult native = render_scene(scene);
        std::vector<int> image;
        for (int y = 0; y < scene.height; ++y) {
            for (int i = 0; i < scene.width; ++i) {
                const Rgba8 p = native.image.at(i, y);
                image.push_back(p.r << 16 | p.g << 8 | p.b);
            }
        }
        CHECK(ints_of(s["image"]) == image);
        const RenderReport& r = native.report;
        std::size_t triangles = 0;
        for (const SceneMesh& mesh : scene.meshes) {
            triangles += mesh.triangles.size();
        }
        CHECK(static_cast<std::size_t>(s["triangles"].number) == triangles);
        CHECK(static_cast<long long>(s["geometry"].number) == r.geometry.triangles);
        CHECK(static_cast<long long>(s["rejected"].number) == r.rejected.triangles);
        CHECK(static_cast<long long>(s["clipped"].number) == r.clipping.triangles);
        CHECK(static_cast<long long>(s["culled"].number) == r.culling.triangles);
        CHECK(static_cast<long long>(s["drawn"].number) == r.raster.triangles);
        CHECK(static_cast<long long>(s["covered"].number) == r.raster.pixels);
        CHECK(s["depthOn"].boolean == r.depth_on);
        CHECK(static_cast<long long>(s["tested"].number) == r.depth.pixels);
        CHECK(static_cast<long long>(s["hidden"].number) == r.hidden.pixels);
        CHECK(s["reason"].str() == r.depth_reason);
        // Each triangle's decision, summed, is the whole render's count: the geometry
        // stage decides every triangle on its own.
        const std::vector<int> flags = ints_of(s["flags"]), culled = ints_of(s["culledPieces"]),
                               pieces = ints_of(s["pieces"]), pixels = ints_of(s["pixels"]);
        REQUIRE(flags.size() == triangles);
        long long rejected = 0, clipped = 0, culled_sum = 0, drawn = 0, covered = 0;
        for (std::size_t k = 0; k < triangles; ++k) {
            rejected += flags[k] % 2;
            clipped += flags[k] / 2 % 2;
            culled_sum += culled[k];
            drawn += pieces[k];
            covered += pixels[k];
        }
        CHECK(rejected == r.rejected.triangles);
        CHECK(clipped == r.clipping.triangles);
        CHECK(culled_sum == r.culling.triangles);
        CHECK(drawn == r.raster.triangles);
        CHECK(covered == r.raster.pixels);
        const std::string line = page.line(f);
        const bool says = line.find(fmt::format("{} rejected", r.rejected.triangles)) !=
                              std::string::npos &&
                          line.find(fmt::format("{} hidden", r.hidden.pixels)) != std::string::npos;
        CHECK_MESSAGE(says, line);
        return r;
    };
    // As loaded: something of every kind happens, and the depth stage hides pixels.
    const RenderReport first = check(4, -5, "as loaded");
    CHECK(first.rejected.triangles > 0);
    CHECK(first.clipping.triangles > 0);
    CHECK(first.culling.triangles > 0);
    CHECK(first.hidden.pixels > 0);
    // The camera dragged 2 units left and 1 back on the plan (16 SVG units per unit; the
    // plan's y points towards -z).
    page.drag(f, 0, -2 * 16.0, 1 * 16.0);
    check(2, -6, "camera dragged to (2, -6)");
    // Four steps of 1/4 up the plan (towards +z) with the keys.
    page.key(f, 0, "ArrowUp", 38, 4);
    check(2, -5, "camera moved to (2, -5) with the keys");
}

} // namespace

TEST_CASE("the live figures' module is the library, under 1 MB") {
    const fs::path wasm = fs::path(EXACTPIXELS_BINARY_DIR) / "web/exactpixels-live.wasm";
    REQUIRE_MESSAGE(fs::exists(wasm), "build the book first: cmake --build --preset book");
    MESSAGE("exactpixels-live.wasm: " << fs::file_size(wasm) << " bytes");
    CHECK(fs::file_size(wasm) < 1000000);
    for (const fs::path& folder : editions(true)) {
        INFO(folder);
        CHECK(fs::exists(folder / "live/exactpixels-live.js"));
        CHECK(fs::exists(folder / "live/live.js"));
    }
}

// Every live figure of one edition's folder (build/book/, build/book-teacher/ or
// build/book-course/), each driven and checked as the top of the file says.
void check_edition(Browser& browser, const fs::path& folder, const char* server) {
    REQUIRE_MESSAGE(fs::exists(folder / "index.html"),
                    "build the book first: cmake --workflow --preset book (" << folder << ")");
    INFO(folder.filename().string());
    Page page(browser);
    std::vector<std::string> seen;
    for (const auto& entry : fs::directory_iterator(folder)) {
        const fs::path path = entry.path();
        if (path.extension() != ".html" ||
            testing::read_text(path).find("data-live=") == std::string::npos) {
            continue;
        }
        INFO(path.filename().string());
        const std::string url = server ? std::string(server) + path.filename().string()
                                       : "file://" + fs::canonical(path).string();
        const auto visit = browser.open(url, wait_ready);
        REQUIRE_MESSAGE(visit.error.empty(), url << ": " << visit.error);
        const Json& r = visit.result;
        REQUIRE(!r["figures"].array.empty());
        MESSAGE(path.filename().string() << ": live figures ready " << r["readyMs"].number
                                          << " ms after the page's start (their script began at "
                                          << r["startMs"].number << " ms)");
        if (static_cast<std::size_t>(r["ready"].number) != r["figures"].array.size()) {
            FAIL_CHECK(r["ready"].number << " of " << r["figures"].array.size()
                                         << " live figures ready after 5 s");
            for (const auto& line : visit.console) {
                FAIL_CHECK(line);
            }
            continue;
        }
        // Interactive within a second: the figures' own time, from their script's start
        // (after the page's text is parsed) to every figure drawn and ready.
        CHECK(r["readyMs"].number - r["startMs"].number < 1000);
        for (const Json& name : r["figures"].array) {
            seen.push_back(name.str());
            // As loaded, for a person to look at beside the page's other screenshots.
            browser.screenshot("#live-" + name.str(),
                               folder / "screenshots" / ("live-" + name.str() + ".png"));
            if (name.str() == "ch01-scanline") {
                check_scanline(page);
            } else if (name.str() == "ch02-fill-rule") {
                check_fill_rule(browser, page);
            } else if (name.str() == "ch00-edge-centres") {
                check_edge_centres(page);
            } else if (name.str() == "ch03-span-mappers") {
                check_span_mappers(page);
            } else if (name.str() == "ch04-texel-rule") {
                check_texel_rule(page);
            } else if (name.str() == "ch02-blocks") {
                check_blocks(page);
            } else if (name.str() == "ch07-scene") {
                check_scene(page);
            } else if (name.str() == "ch08-level") {
                check_level(page);
            } else {
                FAIL("no check for the live figure " << name.str());
            }
        }
        for (const auto& line : browser.console()) {
            if (server && line.find("/favicon.ico") != std::string::npos) {
                continue; // the browser asks a server for one; the book has none
            }
            FAIL_CHECK(line);
        }
        // On paper the static figures stand and the live ones are not printed.
        browser.command("Emulation.setEmulatedMedia", R"({"media":"print"})");
        const Json printed = browser.evaluate(
            "[...document.querySelectorAll('figure[data-live]')].every("
            "(f) => getComputedStyle(f).display === 'none') && "
            "[...document.querySelectorAll('figure img')].every("
            "(i) => getComputedStyle(i.closest('figure')).display !== 'none')");
        CHECK(printed.boolean);
        browser.command("Emulation.setEmulatedMedia", R"({"media":""})");
        // Without JavaScript the live figures stay hidden and the static ones stand.
        browser.command("Emulation.setScriptExecutionDisabled", R"({"value":true})");
        const auto plain = browser.open(
            url, "({hidden: [...document.querySelectorAll('figure[data-live]')].every("
                 "(f) => f.dataset.live === 'loading' && getComputedStyle(f).display === "
                 "'none'), images: document.querySelectorAll('figure img').length})");
        browser.command("Emulation.setScriptExecutionDisabled", R"({"value":false})");
        CHECK(plain.result["hidden"].boolean);
        CHECK(plain.result["images"].number > 0);
    }
    std::sort(seen.begin(), seen.end());
    CHECK(seen == std::vector<std::string>{"ch00-edge-centres", "ch01-scanline", "ch02-blocks",
                                           "ch02-fill-rule", "ch03-span-mappers",
                                           "ch04-texel-rule", "ch07-scene", "ch08-level"});
}

TEST_CASE("every live figure loads from file://, and a drag or a key gives the library's answer") {
    Browser browser(fs::temp_directory_path() /
                        ("exactpixels-chromium-live-" + std::to_string(::getpid())),
                    1200, 900);
    // From file://, every edition; or the public book from the web server at
    // $EXACTPIXELS_BOOK_URL when it is set (e.g. http://127.0.0.1:8000/ serving
    // build/book/).
    const char* server = std::getenv("EXACTPIXELS_BOOK_URL");
    for (const fs::path& folder : editions(server == nullptr)) {
        check_edition(browser, folder, server);
    }
}
