// Chapter 4 tests, pixel for pixel: quads textured through chapter 3's mappers with the
// rounding chosen per triangle. 1:1 and magnified, pixel-aligned and offset by half a
// pixel (every sample a tie), the texture running forwards and mirrored; and the broken
// variant that always uses rule 1, with the texels it skips and doubles counted.
#include "exactpixels/base/test_pattern.hpp"
#include "exactpixels/texture/rounding.hpp"
#include "exactpixels/texture/texture.hpp"
#include "exactpixels/texture/texture_mapper.hpp"
#include "support/printing.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

using namespace exactpixels;

namespace {

/// A screen rectangle [x0, x1] x [y0, y1] textured with u running from u_left to
/// u_right and v from v_top to v_bottom, at one depth w: two triangles.
struct Quad {
    double x0, y0, x1, y1;
    double u_left, u_right, v_top, v_bottom;
};

std::array<std::array<TexturedVertex, 3>, 2> triangles(const Quad& q) {
    const TexturedVertex tl{{q.x0, q.y0}, 1.0, {q.u_left, q.v_top}};
    const TexturedVertex tr{{q.x1, q.y0}, 1.0, {q.u_right, q.v_top}};
    const TexturedVertex br{{q.x1, q.y1}, 1.0, {q.u_right, q.v_bottom}};
    const TexturedVertex bl{{q.x0, q.y1}, 1.0, {q.u_left, q.v_bottom}};
    return {{{tl, tr, br}, {tl, br, bl}}};
}

/// Whether a triangle's rounding is chosen by chapter 4 or left at rule 1 (the bug).
enum class Rounding { chosen, always_rule1 };

MapperSettings settings_for(MapperKind kind, Precision precision,
                            Wrap wrap = Wrap::clamp) {
    MapperSettings s;
    s.mapper.kind = kind;
    s.precision = precision;
    s.mapper.piece =
        4; // short pieces: the subdivided mappers really subdivide these quads
    s.wrap = wrap;
    return s;
}

MapperSettings with_rounding(MapperSettings s, const std::array<TexturedVertex, 3>& t,
                             Rounding rounding) {
    s.rounding = rounding == Rounding::chosen ? choose_rounding(t, s.mapper.kind)
                                              : TexelRounding{};
    return s;
}

constexpr int frame_width = 48, frame_height = 64; // room for 4x magnification

TexelMap map_quad(const Quad& q, const MapperSettings& s, Rounding rounding) {
    TexelMap map(frame_width, frame_height);
    for (const auto& t : triangles(q)) {
        map_textured_triangle(map, t, with_rounding(s, t, rounding));
    }
    return map;
}

Framebuffer draw_quad(const Quad& q, const Texture& texture, const MapperSettings& s,
                      Rounding rounding) {
    Framebuffer frame(frame_width, frame_height, rgba(0, 160, 0));
    for (const auto& t : triangles(q)) {
        draw_textured_triangle(frame, t, texture, with_rounding(s, t, rounding));
    }
    return frame;
}

struct Combo {
    MapperKind kind;
    Precision precision;
};

/// Every mapper of chapter 3 in every inner-loop arithmetic.
std::vector<Combo> every_mapper() {
    std::vector<Combo> all;
    for (MapperKind k : {MapperKind::exact, MapperKind::affine, MapperKind::subdivided,
                         MapperKind::quadratic, MapperKind::quadratic_subdivided}) {
        for (Precision p : {Precision::float32, Precision::float64, Precision::fixed}) {
            all.push_back({k, p});
        }
    }
    return all;
}

std::string name(Combo c) {
    const char* kinds[] = {"exact", "affine", "subdivided", "quadratic",
                           "quadratic_subdivided"};
    const char* precisions[] = {"float32", "float64", "fixed"};
    return std::string(kinds[int(c.kind)]) + "/" + precisions[int(c.precision)];
}

/// The covered pixels must be exactly [px0, px0 + cols) x [py0, py0 + rows), and pixel
/// (px0 + a, py0 + b) must show texel (want_i(a), want_j(b)). Returns the number of
/// pixels that break this, and describes the first few.
int mismatches(const TexelMap& map, int px0, int py0, int cols, int rows,
               const std::function<int(int)>& want_i,
               const std::function<int(int)>& want_j, std::string& report) {
    REQUIRE(px0 + cols <= map.width); // the whole quad must be inside the frame
    REQUIRE(py0 + rows <= map.height);
    std::ostringstream out;
    int bad = 0;
    for (int y = 0; y < map.height; ++y) {
        for (int x = 0; x < map.width; ++x) {
            const std::size_t at =
                std::size_t(y) * std::size_t(map.width) + std::size_t(x);
            const int a = x - px0, b = y - py0;
            const bool inside = a >= 0 && a < cols && b >= 0 && b < rows;
            bool wrong = map.covered[at] != inside;
            if (!wrong && inside) {
                wrong = map.i[at] != want_i(a) || map.j[at] != want_j(b);
            }
            if (wrong && ++bad <= 4) {
                out << " pixel (" << x << ", " << y << "): "
                    << (map.covered[at] ? "texel (" + std::to_string(map.i[at]) + ", " +
                                              std::to_string(map.j[at]) + ")"
                                        : std::string("not covered"))
                    << (inside ? ", want (" + std::to_string(want_i(a)) + ", " +
                                     std::to_string(want_j(b)) + ")"
                               : std::string(", want not covered"))
                    << ";";
            }
        }
    }
    report = out.str();
    return bad;
}

/// How often each texel of a width x height texture shows, after clamping the indices.
std::vector<int> texel_histogram(const TexelMap& map, int width, int height) {
    std::vector<int> count(std::size_t(width) * std::size_t(height), 0);
    for (std::size_t at = 0; at < map.covered.size(); ++at) {
        if (map.covered[at]) {
            const int i = wrap_index(map.i[at], width, Wrap::clamp);
            const int j = wrap_index(map.j[at], height, Wrap::clamp);
            ++count[std::size_t(j) * std::size_t(width) + std::size_t(i)];
        }
    }
    return count;
}

/// Texels never shown, texels shown more than once, and the extra showings.
struct Census {
    int skipped = 0, doubled = 0, extra = 0;
};

Census census(const std::vector<int>& histogram) {
    Census c;
    for (int n : histogram) {
        c.skipped += n == 0;
        c.doubled += n > 1;
        c.extra += n > 1 ? n - 1 : 0;
    }
    return c;
}

// The texture of the image tests: the book's F, 10 x 14 texels (cell 2).
constexpr int W = 10, H = 14;
// Where the quads go: the pixel-aligned ones start at (3, 2).
constexpr int X0 = 3, Y0 = 2;

/// A 1:1 quad of the W x H texture with its corner at (X0 + offset, Y0 + offset),
/// mirrored in u and/or v.
Quad one_to_one(double offset, bool mirror_u, bool mirror_v, int scale = 1) {
    const double x0 = X0 + offset, y0 = Y0 + offset;
    return {x0,
            y0,
            x0 + scale * W,
            y0 + scale * H,
            mirror_u ? double(W) : 0.0,
            mirror_u ? 0.0 : double(W),
            mirror_v ? double(H) : 0.0,
            mirror_v ? 0.0 : double(H)};
}

std::function<int(int)> forwards(int scale = 1) {
    return [scale](int a) { return a / scale; };
}
std::function<int(int)> backwards(int size, int scale = 1) {
    return [size, scale](int a) { return size - 1 - a / scale; };
}

} // namespace

TEST_CASE("a pixel-aligned 1:1 quad shows every texel exactly once, in every mapper") {
    // Pixel centres sit at u = a + 1/2: no tie anywhere, both rules agree.
    for (const Combo c : every_mapper()) {
        for (const Rounding r : {Rounding::chosen, Rounding::always_rule1}) {
            std::string report;
            const TexelMap map = map_quad(one_to_one(0.0, false, false),
                                          settings_for(c.kind, c.precision), r);
            INFO(name(c) << (r == Rounding::chosen ? " chosen" : " rule 1") << report);
            CHECK(mismatches(map, X0, Y0, W, H, forwards(), forwards(), report) == 0);
            CHECK(census(texel_histogram(map, W, H)).skipped == 0);
        }
    }
}

TEST_CASE("a half-pixel-offset quad samples only ties and shows every texel once") {
    // Corner at (3.5, 2.5): the top-left rule covers centres 3.5 .. 12.5, and the centre
    // of pixel (3 + a, 2 + b) maps to (u, v) = (a, b) exactly: an integer in both.
    for (const Combo c : every_mapper()) {
        std::string report;
        const TexelMap map =
            map_quad(one_to_one(0.5, false, false), settings_for(c.kind, c.precision),
                     Rounding::chosen);
        INFO(name(c) << report);
        CHECK(mismatches(map, X0, Y0, W, H, forwards(), forwards(), report) == 0);
        int ties = 0;
        for (std::size_t at = 0; at < map.covered.size(); ++at) {
            ties += map.covered[at] && map.u[at] == std::floor(map.u[at]) &&
                    map.v[at] == std::floor(map.v[at]);
        }
        CHECK(ties == W * H); // every single sample is a tie in u and in v
    }
}

TEST_CASE("mirrored mappings give exactly the mirrored images with the chosen rule" *
          doctest::description("points: 4; exercise: ch04-choose-rule")) {
    for (const double offset : {0.0, 0.5}) {
        for (const bool mu : {false, true}) {
            for (const bool mv : {false, true}) {
                for (const Combo c : every_mapper()) {
                    std::string report;
                    const TexelMap map =
                        map_quad(one_to_one(offset, mu, mv),
                                 settings_for(c.kind, c.precision), Rounding::chosen);
                    INFO(name(c) << ", offset " << offset << ", mirrored u " << mu
                                 << ", mirrored v " << mv << report);
                    CHECK(mismatches(map, X0, Y0, W, H, mu ? backwards(W) : forwards(),
                                     mv ? backwards(H) : forwards(), report) == 0);
                }
            }
        }
    }
}

TEST_CASE("rule 1 alone skips and doubles texels on mirrored tie quads" *
          doctest::description("points: 2; exercise: ch04-choose-rule")) {
    // Offset quad, u running backwards: the centre of column a maps to u = W - a, a tie.
    // Rule 1 takes floor(u) = W - a: column 0 asks for texel W, beyond the texture
    // (clamped to W - 1, which so shows twice), and texel 0 never shows. The same in v.
    // Per texture: mirrored u skips H texels (column 0) and doubles H; mirrored v skips
    // W and doubles W; both skip W + H - 1 and double W + H - 3 texels, shown W + H - 1
    // extra times (texel (W-1, H-1) four times).
    struct Case {
        bool mu, mv;
        Census want;
    };
    const Case cases[] = {{true, false, {H, H, H}},
                          {false, true, {W, W, W}},
                          {true, true, {W + H - 1, W + H - 3, W + H - 1}}};
    for (const Case& k : cases) {
        for (const Combo c : every_mapper()) {
            const auto s = settings_for(c.kind, c.precision);
            const TexelMap broken =
                map_quad(one_to_one(0.5, k.mu, k.mv), s, Rounding::always_rule1);
            const TexelMap fixed =
                map_quad(one_to_one(0.5, k.mu, k.mv), s, Rounding::chosen);
            const Census bad = census(texel_histogram(broken, W, H));
            const Census good = census(texel_histogram(fixed, W, H));
            INFO(name(c) << ", mirrored u " << k.mu << ", mirrored v " << k.mv);
            CHECK(bad.skipped == k.want.skipped);
            CHECK(bad.doubled == k.want.doubled);
            CHECK(bad.extra == k.want.extra);
            CHECK(good.skipped == 0);
            CHECK(good.doubled == 0);
            // The broken map asks for texel index W (or H) itself, one past the end.
            int past_end = 0;
            for (std::size_t at = 0; at < broken.covered.size(); ++at) {
                past_end +=
                    broken.covered[at] && (broken.i[at] == W || broken.j[at] == H);
            }
            CHECK(past_end == (k.mu ? H : 0) + (k.mv ? W : 0) - (k.mu && k.mv ? 1 : 0));
        }
    }
}

TEST_CASE("without ties the rule makes no difference, mirrored or not") {
    for (const bool mu : {false, true}) {
        for (const bool mv : {false, true}) {
            const auto s = settings_for(MapperKind::exact, Precision::fixed);
            const TexelMap a = map_quad(one_to_one(0.0, mu, mv), s, Rounding::chosen);
            const TexelMap b =
                map_quad(one_to_one(0.0, mu, mv), s, Rounding::always_rule1);
            CHECK(a.i == b.i);
            CHECK(a.j == b.j);
        }
    }
}

TEST_CASE("the F mirrored with the rule is the mirrored F; with rule 1 it is not" *
          doctest::description("points: 2; exercise: ch04-choose-rule")) {
    // The images themselves, drawn with the book's F, as a reader would see them. With
    // Wrap::repeat rule 1 shows every texel once but puts the wrapped one on the wrong
    // side: one whole column (or row) of the image is wrong.
    const Texture f = f_texture(2);
    REQUIRE(f.width() == W);
    REQUIRE(f.height() == H);
    for (const Wrap wrap : {Wrap::clamp, Wrap::repeat}) {
        for (const bool mu : {false, true}) {
            for (const bool mv : {false, true}) {
                Framebuffer want(frame_width, frame_height, rgba(0, 160, 0));
                for (int b = 0; b < H; ++b) {
                    for (int a = 0; a < W; ++a) {
                        want.at(X0 + a, Y0 + b) =
                            f.texel(mu ? W - 1 - a : a, mv ? H - 1 - b : b);
                    }
                }
                for (const Combo c : every_mapper()) {
                    const auto s = settings_for(c.kind, c.precision, wrap);
                    const Quad q = one_to_one(0.5, mu, mv);
                    INFO(name(c) << ", repeat " << (wrap == Wrap::repeat)
                                 << ", mirrored u " << mu << ", mirrored v " << mv);
                    CHECK(draw_quad(q, f, s, Rounding::chosen) == want);
                    const Framebuffer broken = draw_quad(q, f, s, Rounding::always_rule1);
                    int wrong = 0;
                    for (std::size_t k = 0; k < want.pixels().size(); ++k) {
                        wrong += broken.pixels()[k] != want.pixels()[k];
                    }
                    CHECK((wrong == 0) == (!mu && !mv)); // only the mirrored ones break
                }
            }
        }
    }
}

TEST_CASE("integer magnification k = 2, 3, 4: every texel covers exactly k x k pixels" *
          doctest::description("points: 2; exercise: ch04-choose-rule")) {
    // Pixel-aligned: the centre of pixel a maps to u = (a + 1/2) / k, never an integer,
    // so texel floor(u) = a / k (integer division) with either rule. Offset by half a
    // pixel, u = a / k: a tie at every k-th column. Those ties are exact only when 1/k
    // is exact in binary (k = 2, 4); with k = 3 the mappers' u is a rounding of a / 3 and
    // lands on either side of the tie, so the offset case is left to k = 2 and 4.
    for (const int k : {2, 3, 4}) {
        for (const double offset : {0.0, 0.5}) {
            if (offset != 0.0 && k == 3) {
                continue;
            }
            for (const bool mu : {false, true}) {
                for (const bool mv : {false, true}) {
                    for (const Combo c : every_mapper()) {
                        std::string report;
                        const TexelMap map =
                            map_quad(one_to_one(offset, mu, mv, k),
                                     settings_for(c.kind, c.precision), Rounding::chosen);
                        INFO(name(c)
                             << ", k = " << k << ", offset " << offset << ", mirrored u "
                             << mu << ", mirrored v " << mv << report);
                        CHECK(mismatches(map, X0, Y0, k * W, k * H,
                                         mu ? backwards(W, k) : forwards(k),
                                         mv ? backwards(H, k) : forwards(k),
                                         report) == 0);
                        const std::vector<int> histogram = texel_histogram(map, W, H);
                        CHECK(std::count(histogram.begin(), histogram.end(), k * k) ==
                              W * H);
                    }
                }
            }
        }
    }
}

TEST_CASE("every mapper draws the constant-depth quads into identical images") {
    const Texture f = f_texture(2);
    for (const double offset : {0.0, 0.5}) {
        for (const int k : {1, 2, 4}) {
            for (const bool mu : {false, true}) {
                for (const bool mv : {false, true}) {
                    const Quad q = one_to_one(offset, mu, mv, k);
                    const Framebuffer reference = draw_quad(
                        q, f, settings_for(MapperKind::exact, Precision::float64),
                        Rounding::chosen);
                    for (const Combo c : every_mapper()) {
                        INFO(name(c) << ", k = " << k << ", offset " << offset
                                     << ", mirrored u " << mu << ", mirrored v " << mv);
                        CHECK(draw_quad(q, f, settings_for(c.kind, c.precision),
                                        Rounding::chosen) == reference);
                    }
                }
            }
        }
    }
}
