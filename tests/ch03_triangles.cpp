// Chapter 3 tests: textures, and textured triangles drawn by every mapper through
// chapter 1's scanline rasterizer.
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/base/test_pattern.hpp"
#include "exactpixels/lab/perspective_scenes.hpp"
#include "exactpixels/raster/scanline.hpp"
#include "exactpixels/texture/perspective_error.hpp"
#include "exactpixels/texture/texture.hpp"
#include "exactpixels/texture/texture_mapper.hpp"
#include "support/printing.hpp"
#include "support/measured_facts.hpp"
#include "support/process.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

using namespace exactpixels;
using exactpixels::testing::record_fact;
namespace fs = std::filesystem;

namespace {
fs::path scratch_folder(const std::string& name) {
    auto folder = fs::temp_directory_path() /
                  ("exactpixels-ch03-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(folder);
    fs::create_directories(folder);
    return folder;
}

const MapperKind all_kinds[] = {MapperKind::exact, MapperKind::affine,
                                MapperKind::subdivided, MapperKind::quadratic,
                                MapperKind::quadratic_subdivided};
const Precision all_precisions[] = {Precision::float32, Precision::float64,
                                    Precision::fixed};
} // namespace

TEST_CASE("wrap_index repeats and clamps") {
    CHECK(wrap_index(-1, 5, Wrap::repeat) == 4);
    CHECK(wrap_index(5, 5, Wrap::repeat) == 0);
    CHECK(wrap_index(-6, 5, Wrap::repeat) == 4);
    CHECK(wrap_index(13, 5, Wrap::repeat) == 3);
    CHECK(wrap_index(-1, 5, Wrap::clamp) == 0);
    CHECK(wrap_index(7, 5, Wrap::clamp) == 4);
    CHECK(wrap_index(2, 5, Wrap::clamp) == 2);
}

TEST_CASE("nearest sampling picks texel floor(u), floor(v), unflipped") {
    const Texture f = f_texture(1); // 5 x 7 texels, texel (i, j) red where the F is
    for (int j = 0; j < 7; ++j) {
        for (int i = 0; i < 5; ++i) {
            const Rgba8 want = f_glyph_cell(i, j) ? pattern_red : pattern_blue;
            INFO("texel (" << i << ", " << j << ")");
            CHECK(sample_nearest(f, {i + 0.5, j + 0.5}, Wrap::clamp) == want); // centre
            CHECK(sample_nearest(f, {i + 0.0, j + 0.0}, Wrap::clamp) ==
                  want); // its corner
            CHECK(sample_nearest(f, {i + 0.999, j + 0.999}, Wrap::clamp) == want);
        }
    }
    // Texel (4, 1) is blue, (4, 0) red: u = 4.5 just above v = 1 is blue.
    CHECK(sample_nearest(f, {4.5, 1.0}, Wrap::clamp) == pattern_blue);
    CHECK(sample_nearest(f, {4.5, 0.999}, Wrap::clamp) == pattern_red);
    // Repeat: u = -0.5 is texel 4 of the row; clamp: texel 0.
    CHECK(sample_nearest(f, {-0.5, 3.5}, Wrap::repeat) == pattern_blue); // (4, 3)
    CHECK(sample_nearest(f, {-0.5, 3.5}, Wrap::clamp) == pattern_red);   // (0, 3)
}

TEST_CASE("the checkerboard alternates every `square` texels from texel (0, 0)") {
    const Rgba8 A = rgba(1, 1, 1), B = rgba(2, 2, 2);
    const Texture c = checkerboard_texture(6, 4, 2, A, B);
    const char* expected[] = {"AABBAA", "AABBAA", "BBAABB", "BBAABB"};
    for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 6; ++i) {
            CHECK(c.texel(i, j) == (expected[j][i] == 'A' ? A : B));
        }
    }
}

TEST_CASE("textures load from PNG; missing, corrupt or empty ones fail naming the path") {
    const auto folder = scratch_folder("load");
    write_png(folder / "f.png", draw_f_pattern(3));
    CHECK(load_texture(folder / "f.png").texels() == f_texture(3).texels());

    const fs::path missing = folder / "missing.png";
    CHECK_THROWS_WITH_AS(load_texture(missing),
                         doctest::Contains(missing.string().c_str()), Error);
    const fs::path corrupt = folder / "corrupt.png";
    std::ofstream(corrupt) << "not a png at all";
    CHECK_THROWS_WITH_AS(load_texture(corrupt),
                         doctest::Contains(corrupt.string().c_str()), Error);
    // A PNG signature and an IHDR chunk claiming 0 x 0 pixels.
    const fs::path empty = folder / "empty.png";
    {
        std::ofstream out(empty, std::ios::binary);
        const unsigned char bytes[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0,
                                       0,    0,   13,  'I', 'H',  'D',  'R',  0,    0,
                                       0,    0,   0,   0,   0,    0,    8,    6,    0,
                                       0,    0,   0,   0,   0,    0};
        out.write(reinterpret_cast<const char*>(bytes), sizeof bytes);
    }
    CHECK_THROWS_WITH_AS(load_texture(empty), doctest::Contains(empty.string().c_str()),
                         Error);
    CHECK_THROWS_AS(Texture(0, 0, {}), Error);
    CHECK_THROWS_AS(Texture(2, 2, std::vector<Rgba8>(3)), Error);
    fs::remove_all(folder);
}

TEST_CASE("a screen-aligned F is drawn unflipped by every mapper") {
    // Two triangles covering pixels [10, 20) x [4, 18), u = (x - 10) / 2, v = (y - 4) /
    // 2: the 5 x 7 F scaled by 2, every pixel centre inside one texel (u, v on
    // half-texels).
    const Texture f = f_texture(1);
    for (const MapperKind kind : all_kinds) {
        for (const Precision precision : all_precisions) {
            Framebuffer frame(30, 22, rgba(0, 0, 0));
            const auto vertex = [](double x, double y) {
                return TexturedVertex{{x, y}, 2.0, {(x - 10.0) / 2.0, (y - 4.0) / 2.0}};
            };
            const MapperSettings settings{{kind, 4}, precision, {}, Wrap::clamp};
            draw_textured_triangle(frame, {vertex(10, 4), vertex(20, 4), vertex(20, 18)},
                                   f, settings);
            draw_textured_triangle(frame, {vertex(10, 4), vertex(20, 18), vertex(10, 18)},
                                   f, settings);
            CAPTURE(int(kind));
            CAPTURE(int(precision));
            for (int y = 0; y < 22; ++y) {
                for (int x = 0; x < 30; ++x) {
                    const bool inside = x >= 10 && x < 20 && y >= 4 && y < 18;
                    const Rgba8 want = !inside ? rgba(0, 0, 0)
                                       : f_glyph_cell((x - 10) / 2, (y - 4) / 2)
                                           ? pattern_red
                                           : pattern_blue;
                    REQUIRE(frame.at(x, y) == want);
                }
            }
        }
    }
}

TEST_CASE("every mapper covers exactly the scanline rasterizer's pixels") {
    const PerspectiveScene scene = wall_scene(96, 72);
    for (const MapperKind kind : all_kinds) {
        TexelMap map(96, 72);
        map_scene(map, scene, MapperSettings{.mapper = {kind}});
        std::vector<bool> covered(96 * 72, false);
        for (const auto& t : scene.triangles) {
            const std::array<FixedPoint2, 3> v{snap_to_subpixel(t[0].position),
                                               snap_to_subpixel(t[1].position),
                                               snap_to_subpixel(t[2].position)};
            scanline_spans(v, Viewport{96, 72}, [&](Span s) {
                for (int x = s.x_begin; x < s.x_end; ++x) {
                    covered[static_cast<std::size_t>(s.y * 96 + x)] = true;
                }
            });
        }
        CHECK(map.covered == covered);
    }
}

TEST_CASE("with constant w every mapper picks the exact texels, pixel for pixel") {
    // u = a x + b y + c with dyadic a, b, c, vertices on 1/4 px and w a power of two:
    // every quantity every mapper forms is a short dyadic number, so all arithmetic is
    // exact and the texel must be floor(u) at the pixel centre, ties (u an integer)
    // included.
    struct Case {
        std::array<Point2, 3> p;
        double a, b, c, w;
    };
    const Case cases[] = {
        {{{{1.25, 2.5}, {60.0, 7.75}, {20.5, 45.0}}}, 0.75, -0.5, 3.0, 1.0},
        {{{{50.0, 1.0}, {3.0, 30.25}, {58.5, 40.0}}}, -1.25, 0.375, 100.0, 4.0},
        {{{{0.0, 0.0}, {63.0, 0.0}, {0.0, 47.0}}}, 2.0, 1.0, 0.0, 0.5},
    };
    for (const Case& c : cases) {
        std::array<TexturedVertex, 3> tri{};
        for (std::size_t k = 0; k < 3; ++k) {
            const Point2 p = c.p[k];
            tri[k] = {
                p, c.w, {c.a * p.x + c.b * p.y + c.c, c.b * p.x - c.a * p.y + 80.0}};
        }
        for (const MapperKind kind : all_kinds) {
            for (const Precision precision : all_precisions) {
                for (const TexelRounding rounding :
                     {TexelRounding{}, TexelRounding{(1 << 15) - 1, (1 << 15) - 1}}) {
                    TexelMap map(64, 48);
                    map_textured_triangle(map, tri,
                                          {{kind, 8}, precision, rounding, Wrap::repeat});
                    int pixels = 0;
                    for (int y = 0; y < 48; ++y) {
                        for (int x = 0; x < 64; ++x) {
                            const std::size_t at = static_cast<std::size_t>(y * 64 + x);
                            if (!map.covered[at]) {
                                continue;
                            }
                            ++pixels;
                            const double u = c.a * (x + 0.5) + c.b * (y + 0.5) + c.c;
                            const double v = c.b * (x + 0.5) - c.a * (y + 0.5) + 80.0;
                            CAPTURE(int(kind));
                            CAPTURE(int(precision));
                            REQUIRE(map.i[at] ==
                                    real_texel_index(u, rounding.u_modifier));
                            REQUIRE(map.j[at] ==
                                    real_texel_index(v, rounding.v_modifier));
                        }
                    }
                    CHECK(pixels > 300);
                }
            }
        }
    }
}

TEST_CASE("exact float picks exact double's texel everywhere but at counted near-ties") {
    // Where float and double pick different texels, the double u (or v) must lie within
    // the largest measured float error of a texel boundary: a near-tie, not a mistake.
    for (const auto& named : {std::pair{std::string("floor"), floor_scene(320, 240)},
                              std::pair{std::string("wall"), wall_scene(320, 240)}}) {
        const std::string& name = named.first;
        const auto& scene = named.second;
        TexelMap d(320, 240), f(320, 240);
        map_scene(d, scene, {.precision = Precision::float64});
        map_scene(f, scene, {.precision = Precision::float32});
        REQUIRE(d.covered == f.covered);
        double largest = 0.0;
        int pixels = 0;
        for (std::size_t at = 0; at < d.covered.size(); ++at) {
            if (d.covered[at]) {
                ++pixels;
                largest = std::max(
                    {largest, std::abs(f.u[at] - d.u[at]), std::abs(f.v[at] - d.v[at])});
            }
        }
        const auto near_tie = [&](double u) {
            return std::abs(u - std::round(u)) <= largest;
        };
        int differ = 0, near_ties = 0;
        for (std::size_t at = 0; at < d.covered.size(); ++at) {
            if (!d.covered[at]) {
                continue;
            }
            const bool tie = near_tie(d.u[at]) || near_tie(d.v[at]);
            near_ties += tie;
            if (d.i[at] != f.i[at] || d.j[at] != f.j[at]) {
                ++differ;
                CHECK(tie);
            }
        }
        CHECK(largest <
              2e-3); // float loses no more than a few thousandths of a texel here
        CHECK(differ <= near_ties);
        record_fact("ch03_float_error_" + name, largest);
        record_fact("ch03_near_ties_" + name, near_ties);
        record_fact("ch03_float_differs_" + name, differ);
        MESSAGE(name << ": " << pixels << " pixels, float error up to " << largest
                     << " texels, " << near_ties << " near-ties, " << differ
                     << " pixels where float and double differ");
    }
}

TEST_CASE("the scenes' affine mapper errs by its end errors plus the exact-ends error") {
    // The affine mapper the scenes run takes u at a span's first pixel and its step from
    // the plane of u through the triangle's corners (affine_span), so it is not exact at
    // the span's ends. Along the span it is still a straight line, and the exact u is
    // u0 + dU s(t) (@eq:exact-fraction), so its error at t = k / n is
    //   (1 - t) d0 + t d1 + dU e(t) (@eq:affine-plane-error)
    // with d0, d1 its errors at the first and last pixel, dU the exact extent and e the
    // exact-ends error of @eq:affine-error at the span's own depth ratio r; at most
    // max(|d0|, |d1|) + |dU| (sqrt r - 1) / (sqrt r + 1) (@eq:affine-plane-bound).
    // Checked at every pixel of every span of both scenes, against the exact u of the
    // exact mapper in double (a divide and a few products: a few units in the last place
    // of u, far below the tolerance), to 1e-9 texel, which also covers the affine
    // mapper's own stepping. Spans whose error exceeds the exact-ends bound alone are
    // counted: they are why the end terms are there.
    constexpr double tolerance = 1e-9;
    for (const auto& named : {std::pair{std::string("floor"), floor_scene(320, 240)},
                              std::pair{std::string("wall"), wall_scene(320, 240)}}) {
        const std::string& name = named.first;
        const auto& scene = named.second;
        int spans = 0, beyond_exact_ends = 0;
        double worst_excess = 0; // the largest error beyond the exact-ends bound
        double closest = 0;      // the largest share of its bound a span reaches
        for (const auto& v : scene.triangles) {
            std::array<FixedPoint2, 3> snapped{};
            std::array<Point2, 3> p{};
            for (std::size_t k = 0; k < 3; ++k) {
                snapped[k] = snap_to_subpixel(v[k].position);
                p[k] = to_pixels(snapped[k]);
            }
            const TexturePlanes planes = texture_planes(p, v);
            scanline_spans(snapped, Viewport{320, 240}, [&](Span s) {
                const int count = s.x_end - s.x_begin;
                if (count < 2) {
                    return;
                }
                const PerspectiveSpan<double> exact = perspective_span(planes, s);
                std::vector<double> affine;
                map_span_affine(affine_span(planes, s),
                                [&](int, double u, double) { affine.push_back(u); });
                const int n = count - 1;
                const double u0 = exact_at(exact, 0).u, u1 = exact_at(exact, n).u;
                const double d0 = affine[0] - u0, d1 = affine[std::size_t(n)] - u1;
                const double r = (exact.one_w) / (exact.one_w + n * exact.done_w);
                double worst = 0;
                for (int k = 0; k <= n; ++k) {
                    const double t = static_cast<double>(k) / n;
                    const double e = t - t / (r - (r - 1) * t); // @eq:affine-error
                    const double error = affine[std::size_t(k)] - exact_at(exact, k).u;
                    INFO(name << ", row " << s.y << ", pixel " << k << " of " << count);
                    REQUIRE(std::abs(error - ((1 - t) * d0 + t * d1 + (u1 - u0) * e)) <=
                            tolerance);
                    worst = std::max(worst, std::abs(error));
                }
                const double ends = std::max(std::abs(d0), std::abs(d1));
                const double inside = std::abs(u1 - u0) * affine_error_bound(r);
                CHECK(worst <= ends + inside + tolerance);
                closest = std::max(closest, worst / (ends + inside));
                ++spans;
                if (worst > inside + tolerance) {
                    ++beyond_exact_ends;
                    worst_excess = std::max(worst_excess, worst - inside);
                }
            });
        }
        MESSAGE(name << ": " << beyond_exact_ends << " of " << spans
                     << " spans beyond the exact-ends bound, by up to " << worst_excess
                     << " texels; the closest span reaches " << closest
                     << " of its bound");
        CHECK(spans > 100);
        CHECK(beyond_exact_ends > 0);
        record_fact("ch03_affine_spans_" + name, spans);
        record_fact("ch03_affine_spans_beyond_" + name, beyond_exact_ends);
        record_fact("ch03_affine_excess_" + name, worst_excess);
        record_fact("ch03_affine_bound_reached_" + name, closest);
    }
}

TEST_CASE("disagreement with the exact mapper falls as the approximation improves") {
    const PerspectiveScene scene = wall_scene(320, 240);
    TexelMap exact(320, 240);
    map_scene(exact, scene, {});
    const auto differ = [&](MapperKind kind, int span) {
        TexelMap m(320, 240);
        map_scene(m, scene, {.mapper = {kind, span}});
        int count = 0;
        for (std::size_t at = 0; at < m.covered.size(); ++at) {
            count += m.covered[at] && (m.i[at] != exact.i[at] || m.j[at] != exact.j[at]);
        }
        return count;
    };
    const int affine = differ(MapperKind::affine, 16);
    int previous = affine;
    for (const int n : {32, 16, 8, 4}) {
        const int sub = differ(MapperKind::subdivided, n);
        CHECK(sub < previous);
        previous = sub;
        CHECK(differ(MapperKind::quadratic_subdivided, n) <= sub);
        MESSAGE("N = " << n << ": subdivided differs at " << sub
                       << " pixels, quadratic at "
                       << differ(MapperKind::quadratic_subdivided, n));
    }
    const int quadratic = differ(MapperKind::quadratic, 16);
    CHECK(quadratic < affine);
    MESSAGE("affine differs at " << affine << " pixels, quadratic (whole spans) at "
                                 << quadratic);
}

TEST_CASE("bad triangles and settings fail naming the value, and draw nothing") {
    const Texture t = checkerboard_texture(8, 8, 2);
    Framebuffer frame(16, 16, rgba(9, 9, 9));
    const Framebuffer before = frame;
    const std::array<TexturedVertex, 3> good{{{{0.0, 0.0}, 1.0, {0.0, 0.0}},
                                              {{16.0, 0.0}, 2.0, {8.0, 0.0}},
                                              {{0.0, 16.0}, 1.0, {0.0, 8.0}}}};
    auto zero_w = good;
    zero_w[1].w = 0.0;
    CHECK_THROWS_WITH_AS(draw_textured_triangle(frame, zero_w, t, {}),
                         doctest::Contains("w = 0"), Error);
    auto nan_position = good;
    nan_position[2].position.y = std::nan("");
    CHECK_THROWS_WITH_AS(draw_textured_triangle(frame, nan_position, t, {}),
                         doctest::Contains("nan"), Error);
    auto huge_uv = good;
    huge_uv[0].uv.x = 20000.0;
    CHECK_THROWS_WITH_AS(
        draw_textured_triangle(frame, huge_uv, t, {.precision = Precision::fixed}),
        doctest::Contains("20000"), Error);
    CHECK_THROWS_WITH_AS(
        draw_textured_triangle(frame, good, t, {.mapper = {MapperKind::exact, 1}}),
        doctest::Contains("piece = 1"), Error);
    CHECK(frame == before); // nothing drawn by any failed call
    draw_textured_triangle(frame, good, t, {});
    CHECK(frame != before); // and the good triangle does draw
}

TEST_CASE("ch03-example: a missing texture fails naming it and writes no figure") {
    const std::string example = std::string(EXACTPIXELS_BINARY_DIR) + "/bin/ch03-example";
    REQUIRE_MESSAGE(fs::exists(example), "build the target ch03-example first");
    const auto folder = scratch_folder("example");
    const fs::path missing = folder / "no-such-texture.png";
    const auto failed = testing::run_command(testing::program_command(example) + " '" +
                                             folder.string() + "' '" + missing.string() +
                                             "'");
    CHECK(failed.exit_code != 0);
    CHECK(failed.err.find(missing.string()) != std::string::npos);
    CHECK(fs::is_empty(folder));
    fs::remove_all(folder);
}
