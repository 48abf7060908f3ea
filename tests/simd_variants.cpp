// Every vector instruction set this machine runs (fast/simd.hpp) gives the teaching
// path's pixels bit for bit: the exact mapper's u and v, the textured runs and the scene
// renderer's shipped scenes, each variant forced in turn. And EXACTPIXELS_SIMD refuses
// a value that names no variant, or one this CPU lacks, with exit 2 and one line.
#include "exactpixels/base/error.hpp"
#include "exactpixels/fast/exact_lanes.hpp"
#include "exactpixels/fast/simd.hpp"
#include "exactpixels/fast/textured_runs.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "exactpixels/texture/texture.hpp"
#include "exactpixels/texture/texture_mapper.hpp"
#include "support/printing.hpp"
#include "support/process.hpp"

#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

using namespace exactpixels;

namespace {

/// The variant chosen before a test, restored after it.
struct KeepChoice {
    SimdVariant before = chosen_simd();
    ~KeepChoice() { choose_simd(before); }
};

/// The bits of a double, so that -0 and 0, and every NaN, are told apart.
std::uint64_t bits(double x) {
    return std::bit_cast<std::uint64_t>(x);
}

/// A span of the exact mapper with random planes: depths from near 0 to far, slopes of
/// either sign, and hard cases (1/w falling to nearly 0 at the end of the span, u/w of
/// 2^24 texels, tiny steps).
LaneSpan random_span(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0);
    const int count = 1 + static_cast<int>(rng() % 150);
    const double one_w = 0x1p-8 + unit(rng) * 4.0;
    double done_w = sym(rng) * one_w / count;
    switch (rng() % 4) {
    case 0: // 1/w all but vanishes at the last pixel: w grows by a factor of 2^20
        done_w = -(one_w - one_w * 0x1p-20) / std::max(count - 1, 1);
        break;
    case 1:
        done_w = 0.0; // constant depth
        break;
    default:
        break;
    }
    const double scale = (rng() % 3 == 0) ? 0x1p24 : 300.0;
    return {sym(rng) * scale * one_w, sym(rng) * scale * one_w, one_w,
            sym(rng) * one_w * 3.0, sym(rng) * one_w * 0x1p-30, done_w, count};
}

/// Textured triangles in a width x height frame: random corners (slivers among them,
/// corners beyond the frame), a depth w in [0.5, 40] at each, texture coordinates up to
/// +-2000 texels.
std::vector<std::array<TexturedVertex, 3>> random_triangles(std::mt19937_64& rng, int n,
                                                            int width, int height) {
    std::uniform_real_distribution<double> x(-20.0, width + 20.0), y(-20.0, height + 20.0),
        w(0.5, 40.0), uv(-2000.0, 2000.0), near(-3.0, 3.0);
    std::vector<std::array<TexturedVertex, 3>> out;
    for (int k = 0; k < n; ++k) {
        std::array<TexturedVertex, 3> t{};
        for (auto& v : t) {
            v = {{x(rng), y(rng)}, w(rng), {uv(rng), uv(rng)}};
        }
        if (k % 5 == 0) { // a sliver: the third corner near the first
            t[2].position = t[0].position + Point2{near(rng), near(rng)};
        }
        out.push_back(t);
    }
    return out;
}

/// A texture with no two texels alike.
Texture numbered(int width, int height) {
    std::vector<Rgba8> texels;
    for (int j = 0; j < height; ++j) {
        for (int i = 0; i < width; ++i) {
            texels.push_back(rgba(static_cast<std::uint8_t>(i), static_cast<std::uint8_t>(j),
                                  static_cast<std::uint8_t>(i ^ j)));
        }
    }
    return Texture(width, height, std::move(texels));
}

} // namespace

TEST_CASE("EXACTPIXELS_SIMD names an available variant, or is refused") {
    const std::vector<SimdVariant> here = available_simd();
    REQUIRE(!here.empty());
    CHECK(here.front() == SimdVariant::portable);
    CHECK(simd_from_setting(nullptr) == here.back()); // unset: the widest
    CHECK(simd_from_setting("") == here.back());
    for (const SimdVariant v : here) {
        CHECK(simd_from_setting(std::string(simd_name(v)).c_str()) == v);
    }
    CHECK_THROWS_WITH_AS(simd_from_setting("avx1024"),
                         "EXACTPIXELS_SIMD=avx1024: unknown; one of sse2, avx2, avx512, "
                         "neon, portable",
                         Error);
    CHECK_THROWS_AS(simd_from_setting("AVX2"), Error); // spelled as documented only
#if defined(EXACTPIXELS_SIMD_X86)
    CHECK(simd_available(SimdVariant::sse2));
    CHECK_THROWS_WITH_AS(simd_from_setting("neon"),
                         "EXACTPIXELS_SIMD=neon: this CPU or build has no such instructions",
                         Error);
#elif defined(EXACTPIXELS_SIMD_ARM64)
    CHECK(simd_available(SimdVariant::neon));
    CHECK_THROWS_AS(simd_from_setting("avx2"), Error);
#endif
}

TEST_CASE("the command-line program refuses a bad EXACTPIXELS_SIMD with exit 2 and one line") {
    using testing::cli_path;
    using testing::run_command;
    const auto unknown = run_command("EXACTPIXELS_SIMD=avx9 " + cli_path() + " --version");
    CHECK(unknown.exit_code == 2);
    CHECK(unknown.out.empty());
    CHECK(unknown.err ==
          "exactpixels: EXACTPIXELS_SIMD=avx9: unknown; one of sse2, avx2, avx512, neon, "
          "portable\n");
    for (const SimdVariant v : {SimdVariant::sse2, SimdVariant::avx2, SimdVariant::avx512,
                                SimdVariant::neon, SimdVariant::portable}) {
        const std::string name(simd_name(v));
        INFO(name);
        const auto forced =
            run_command("EXACTPIXELS_SIMD=" + name + " " + cli_path() + " --version");
        if (simd_available(v)) {
            CHECK(forced.exit_code == 0);
        } else {
            CHECK(forced.exit_code == 2);
            CHECK(forced.err == "exactpixels: EXACTPIXELS_SIMD=" + name +
                                    ": this CPU or build has no such instructions\n");
        }
    }
}

TEST_CASE("every variant's exact mapper gives exact_at's bits") {
    std::mt19937_64 rng(34);
    for (const SimdVariant v : available_simd()) {
        INFO(std::string(simd_name(v)));
        long long compared = 0;
        for (int n = 0; n < 2000; ++n) {
            const LaneSpan s = random_span(rng);
            const PerspectiveSpan<double> plain{s.u_w,  s.v_w,    s.one_w, s.du_w,
                                                s.dv_w, s.done_w, s.count};
            const int k0 = static_cast<int>(rng() % static_cast<unsigned>(s.count));
            const int length = 1 + static_cast<int>(rng() % static_cast<unsigned>(s.count - k0));
            std::vector<double> u(static_cast<std::size_t>(length)), w(u.size());
            exact_uv_lanes(v, s, k0, length, u.data(), w.data());
            for (int i = 0; i < length; ++i) {
                const UV<double> expected = exact_at(plain, k0 + i);
                const auto at = static_cast<std::size_t>(i);
                if (bits(u[at]) != bits(expected.u) || bits(w[at]) != bits(expected.v)) {
                    FAIL_CHECK("span " << n << " pixel " << k0 + i << ": " << u[at] << ", "
                                       << w[at] << " against " << expected.u << ", "
                                       << expected.v);
                }
                ++compared;
            }
            // map_span_exact_lanes hands out the same pixels, in order, as
            // map_span_exact does.
            int next = 0;
            bool same = true;
            map_span_exact_lanes(v, plain, [&](int k, double pu, double pv) {
                const UV<double> e = exact_at(plain, k);
                same = same && k == next++ && bits(pu) == bits(e.u) && bits(pv) == bits(e.v);
            });
            CHECK((same && next == s.count));
        }
        CHECK(compared > 30000);
    }
}

TEST_CASE("every variant sets a run's span up with perspective_span's bits") {
    // The kernels set each run's span up themselves (textured_runs_lanes): the planes at
    // the run's first pixel centre, value + dx (x - x0) + dy (y - y0) in that order. Random
    // planes with values and slopes of every size make a reordered sum, or a centre off by
    // anything, round differently somewhere.
    std::mt19937_64 rng(3435);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), corner(-50.0, 1100.0);
    const auto plane = [&] {
        const double scale = std::ldexp(1.0, static_cast<int>(rng() % 60) - 30);
        return ScreenPlane{{corner(rng), corner(rng)},
                           unit(rng) * scale * 1000.0,
                           {unit(rng) * scale, unit(rng) * scale}};
    };
    for (const SimdVariant v : available_simd()) {
        INFO(std::string(simd_name(v)));
        int differing = 0;
        for (int n = 0; n < 20000; ++n) {
            const TexturePlanes planes{plane(), plane(), plane(), {}, {}};
            const int x = static_cast<int>(rng() % 1024), y = static_cast<int>(rng() % 1024);
            const Span run{y, x, x + 1 + static_cast<int>(rng() % 40)};
            const LaneSpan got =
                run_span_lanes(v, lane_planes(planes), {run.y, run.x_begin, run.x_end});
            const PerspectiveSpan<double> e = perspective_span(planes, run);
            differing += bits(got.u_w) != bits(e.u_w) || bits(got.v_w) != bits(e.v_w) ||
                         bits(got.one_w) != bits(e.one_w) || bits(got.du_w) != bits(e.du_w) ||
                         bits(got.dv_w) != bits(e.dv_w) || bits(got.done_w) != bits(e.done_w) ||
                         got.count != e.count;
        }
        CHECK(differing == 0);
    }
}

TEST_CASE("every variant's textured runs draw the teaching path's texels") {
    KeepChoice keep;
    std::mt19937_64 rng(3434);
    constexpr int width = 160, height = 120;
    const auto tris = random_triangles(rng, 400, width, height);
    const Texture texture = numbered(64, 32);
    Framebuffer teaching(width, height, rgba(0, 0, 0, 0));
    for (const auto& t : tris) {
        draw_textured_triangle(teaching, t, texture, MapperSettings{});
    }
    long long drawn = 0;
    for (const Rgba8 p : teaching.pixels()) {
        drawn += p.a != 0;
    }
    CHECK(drawn > width * height / 2); // not vacuous
    for (const SimdVariant v : available_simd()) {
        INFO(std::string(simd_name(v)));
        std::vector<Rgba8> pixels(width * height, rgba(0, 0, 0, 0));
        draw_textured_runs({pixels.data(), nullptr, width, height}, tris, texture,
                           Wrap::repeat, v);
        CHECK((pixels == teaching.pixels()));
        // The overload without a variant takes the chosen one.
        choose_simd(v);
        std::vector<Rgba8> chosen(width * height, rgba(0, 0, 0, 0));
        draw_textured_runs({chosen.data(), nullptr, width, height}, tris, texture,
                           Wrap::repeat);
        CHECK((chosen == teaching.pixels()));
    }
}

TEST_CASE("every variant's textured runs floor exact integers and negative coordinates") {
    // Spans of constant depth (1/w = 1, so u = u/w exactly) whose u and v step by a
    // quarter texel through zero: exact integers, -0.25 and -1 land in every lane
    // position, in runs from 1 pixel (shorter than any register) to 49. A floor that
    // rounds an exact integer down by one (ceil - 1), truncates towards zero or rounds
    // to nearest picks another texel of the numbered texture, which has no two alike.
    const Texture texture = numbered(64, 32);
    const LaneTexels tex = lane_texels(texture);
    std::vector<LaneSpan> spans;
    for (int start = 0; start < 8; ++start) {
        for (int count = 1; count <= 49; ++count) {
            const double u0 = -6.0 + 0.25 * start, v0 = 3.0 - 0.25 * start;
            spans.push_back({u0, v0, 1.0, 0.25, -0.25, 0.0, count});
        }
    }
    // One ulp either side of integers, and the zeros and the smallest doubles.
    for (const double x : {-1025.0, -64.0, -3.0, -1.0, 0.0, 1.0, 31.0, 4096.0}) {
        for (const double y : {std::nextafter(x, -1e9), x, std::nextafter(x, 1e9)}) {
            for (int count = 1; count <= 17; ++count) {
                spans.push_back({y, -y, 1.0, 0.0, 0.0, 0.0, count});
            }
        }
    }
    for (const double y : {-0.0, 0x1p-1074, -0x1p-1074}) {
        spans.push_back({y, y, 1.0, 0.0, 0.0, 0.0, 9});
    }
    for (const SimdVariant v : available_simd()) {
        INFO(std::string(simd_name(v)));
        long long compared = 0;
        for (const LaneSpan& s : spans) {
            const PerspectiveSpan<double> plain{s.u_w,  s.v_w,    s.one_w, s.du_w,
                                                s.dv_w, s.done_w, s.count};
            std::vector<Rgba8> row(static_cast<std::size_t>(s.count) + 1, rgba(0, 0, 0, 0));
            textured_run_lanes(v, row.data(), s, tex);
            for (int k = 0; k < s.count; ++k) {
                const UV<double> uv = exact_at(plain, k);
                const auto i = static_cast<int>(std::floor(uv.u)),
                           j = static_cast<int>(std::floor(uv.v));
                const Rgba8 expected = texture.texels()[static_cast<std::size_t>(
                    (j & 31) * 64 + (i & 63))];
                if (!(row[static_cast<std::size_t>(k)] == expected)) {
                    FAIL_CHECK("u " << uv.u << ", v " << uv.v << ", pixel " << k << " of "
                                    << s.count);
                }
                ++compared;
            }
            CHECK(row.back() == rgba(0, 0, 0, 0)); // nothing written past the run
        }
        CHECK(compared > 10000);
    }
}

TEST_CASE("every variant draws every shipped scene as the teaching path does") {
    KeepChoice keep;
    int scenes = 0;
    long long exact_pixels = 0;
    for (const std::filesystem::path& path : shipped_scenes()) {
        INFO(path.filename().string());
        Scene scene = load_scene(path);
        // As shipped, and with the exact mapper in double everywhere (the mapper the
        // lanes serve; auto chooses it only on some spans).
        Scene exact = scene;
        exact.options.mapper = MapperChoice{false, Mapper{MapperKind::exact}};
        exact.options.precision = Precision::float64;
        for (const Scene* s : {&scene, &exact}) {
            const RenderResult plain = render_scene(*s, nullptr, teaching_path);
            exact_pixels += plain.report.mappers[static_cast<std::size_t>(MapperKind::exact)].pixels;
            for (const SimdVariant v : available_simd()) {
                INFO(std::string(simd_name(v)));
                choose_simd(v);
                FastPaths lanes_only = teaching_path;
                lanes_only.exact_lanes = true;
                CHECK((render_scene(*s, nullptr, lanes_only).image == plain.image));
                CHECK((render_scene(*s, nullptr, FastPaths{}).image == plain.image));
            }
        }
        ++scenes;
    }
    CHECK(scenes >= 7);
    CHECK(exact_pixels > 100000); // the exact mapper ran on many pixels
}
