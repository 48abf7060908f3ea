// Every vector instruction set this machine runs (fast/simd.hpp) depth-tests chapter
// 10's covered runs as the teaching path's plot does, bit for bit
// (fast/depth_lanes_kernel.hpp): the kernel on random runs of every length, and the
// runs and the tiled renderer drawing whole sets, each variant forced in turn.
#include "exactpixels/fast/depth_lanes_kernel.hpp"
#include "exactpixels/fast/simd.hpp"
#include "exactpixels/fast/tiled_rasterizer.hpp"
#include "support/printing.hpp"

#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
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

/// The depths of a row as bits, so that -0 and 0 and every NaN are told apart.
std::vector<std::uint32_t> bits_of(const std::vector<float>& depths) {
    std::vector<std::uint32_t> out;
    for (const float z : depths) {
        out.push_back(std::bit_cast<std::uint32_t>(z));
    }
    return out;
}

std::vector<std::uint32_t> words_of(const std::vector<Rgba8>& colours) {
    std::vector<std::uint32_t> out;
    for (const Rgba8 c : colours) {
        out.push_back(std::bit_cast<std::uint32_t>(c));
    }
    return out;
}

constexpr int row_width = 96; ///< pixels per test row: room for guards on both sides

} // namespace

TEST_CASE("every variant's depth kernel tests runs with plot's bits") {
    std::mt19937_64 rng(34);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), sym(-1.0f, 1.0f);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (const SimdVariant v : available_simd()) {
        INFO("variant " << std::string(simd_name(v)));
        const DepthRunFn depth_run = depth_run_kernel(v);
        for (int trial = 0; trial < 4000; ++trial) {
            const int x_begin = 1 + static_cast<int>(rng() % 20);
            const int x_end = x_begin + static_cast<int>(rng() % 72); // 0 to 71 pixels
            const int y = static_cast<int>(rng() % 2000) - 500;
            DepthPlane plane{unit(rng), sym(rng) * 0.01f, sym(rng) * 0.01f};
            if (trial % 97 == 0) {
                plane.dzdx = nan; // every z NaN: nothing is nearer
            }
            const Rgba8 colour = rgba(static_cast<std::uint8_t>(trial), 7, 9);
            // Stored depths: random, exactly the pixel's z (a tie: not drawn), NaN.
            std::vector<float> depth(row_width);
            std::vector<Rgba8> pixels(row_width);
            for (int x = 0; x < row_width; ++x) {
                const std::uint64_t pick = rng() % 8;
                depth[static_cast<std::size_t>(x)] = pick == 0   ? plane.at(x, y)
                                                     : pick == 1 ? nan
                                                                 : unit(rng);
                pixels[static_cast<std::size_t>(x)] =
                    rgba(static_cast<std::uint8_t>(x), 1, 2);
            }
            std::vector<float> want_depth = depth;
            std::vector<Rgba8> want = pixels;
            for (int x = x_begin; x < x_end; ++x) { // plot, pixel by pixel
                const auto i = static_cast<std::size_t>(x);
                const float z = plane.at(x, y);
                if (z < want_depth[i]) {
                    want_depth[i] = z;
                    want[i] = colour;
                }
            }
            depth_run({plane.z0, plane.dzdx, plane.dzdy, colour}, y, x_begin, x_end,
                      depth.data(), pixels.data());
            CHECK(bits_of(depth) == bits_of(want_depth));
            CHECK(words_of(pixels) == words_of(want));
        }
    }
}

TEST_CASE(
    "every variant's runs and tiled renderer draw a set as the teaching path does") {
    KeepChoice keep;
    std::mt19937_64 rng(341);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    constexpr int side = 200;
    std::vector<FlatTriangle> set;
    for (int n = 0; n < 300; ++n) {
        std::array<FixedPoint2, 3> v{};
        const double cx = unit(rng) * side, cy = unit(rng) * side;
        const double size = n % 3 == 0 ? 60.0 : 14.0; // big runs and 80-px triangles
        for (auto& p : v) {
            p = snap_to_subpixel(
                Point2{cx + (unit(rng) - 0.5) * size, cy + (unit(rng) - 0.5) * size});
        }
        set.push_back(
            {v, depth_plane(v, {unit(rng), unit(rng), unit(rng)}),
             rgba(static_cast<std::uint8_t>(n), static_cast<std::uint8_t>(n >> 8), 1)});
    }
    for (const bool with_depth : {false, true}) {
        const auto draw = [&](auto&& how) {
            std::vector<Rgba8> colour(side * side, rgba(0, 0, 0));
            std::vector<float> depth(colour.size(), 1.0f);
            how(RenderTarget{colour.data(), with_depth ? depth.data() : nullptr, side,
                             side});
            return words_of(colour);
        };
        const auto want = draw([&](const RenderTarget& t) { draw_reference(t, set); });
        for (const SimdVariant v : available_simd()) {
            INFO("variant " << std::string(simd_name(v)) << ", depth " << with_depth);
            choose_simd(v);
            CHECK(draw([&](const RenderTarget& t) {
                      for (const FlatTriangle& tri : set) {
                          draw_runs(t, tri);
                      }
                  }) == want);
            CHECK(draw([&](const RenderTarget& t) { TiledRenderer(1).draw(t, set); }) ==
                  want);
        }
    }
}
