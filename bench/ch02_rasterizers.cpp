// Chapter 2 benchmark: how fast the edge-function rasterizers draw triangles of a given
// area, in float and fixed point, pixel by pixel (1x1) and in 8x8 blocks, next to two
// references: a plain fill of the same number of pixels (the ceiling) and the naive
// rasterizer most tutorials teach (barycentrics recomputed per pixel, with divisions).
//
// Run:   bench_ch02_rasterizers [--benchmark_min_time=0.05] [--benchmark_out=f.csv
//                                --benchmark_out_format=csv]
// Names: table/VARIANT/AREA for the source's table (areas 3, 15, 80 px) and
//        sweep/VARIANT/AREA for the sweep (areas 2 .. 65536 px, powers of two), VARIANT
//        one of float_1x1, float_8x8, fixed_1x1, fixed_8x8, naive, plain_fill.
// Counters: tri_per_s (triangles, or filled rectangles, per second) and pix_per_s
// (pixels written per second), on one thread. figures/ch02_speed.cpp turns the CSV
// into the chapter's table and plot.
//
// Every variant draws the same 1024 triangles per area into a 1024 x 1024 array of
// 32-bit pixels, cycling through them: random shapes (no angle below about 25 degrees),
// random orientation and position, scaled to the exact area before snapping
// (triangle_sets.hpp, shared with chapter 10's benchmark). The
// fixed-point variants get the vertices already snapped (snapping belongs to vertex
// processing); the float and naive variants get them as float pixels.
#include "exactpixels/raster/edge_rasterizer.hpp"
#include "exactpixels/raster/naive_rasterizer.hpp"
#include "triangle_sets.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <vector>

using namespace exactpixels;

namespace {

constexpr int frame_side = 1024;
constexpr int triangle_count = 1024;

/// The target every variant writes: frame_side^2 pixels, row-major.
std::vector<std::uint32_t>& frame() {
    static std::vector<std::uint32_t> pixels(std::size_t{frame_side} * frame_side, 0);
    return pixels;
}

/// The benchmark's triangles of one area, in both forms (triangle_sets.hpp).
const bench::TriangleSet& triangles(int area) {
    static std::map<int, bench::TriangleSet> cache;
    auto [it, inserted] = cache.try_emplace(area);
    if (inserted) {
        it->second = bench::make_triangles(area, triangle_count, frame_side);
    }
    return it->second;
}

/// Reports triangles and pixels per second for `state`.
void report(benchmark::State& state, std::int64_t pixels) {
    using benchmark::Counter;
    state.counters["tri_per_s"] =
        Counter(static_cast<double>(state.iterations()), Counter::kIsRate);
    state.counters["pix_per_s"] = Counter(static_cast<double>(pixels), Counter::kIsRate);
}

/// One variant: draw(triangle index, emit) for the area state.range(0). The number of
/// pixels each triangle covers is counted once before timing, so that the timed loop
/// only writes pixels, like the plain fill.
template <class Draw> void run(benchmark::State& state, Draw draw) {
    std::vector<std::int64_t> covered(triangle_count, 0);
    for (std::size_t n = 0; n < covered.size(); ++n) {
        draw(n, [&](int, int) { ++covered[n]; });
    }
    std::uint32_t* pixels = frame().data();
    std::uint32_t colour = 0xff0000ffu;
    std::int64_t written = 0;
    std::size_t n = 0;
    for (auto _ : state) {
        // By value: a pixel store cannot then alias the colour, so it stays in a
        // register.
        draw(n, [pixels, c = colour](int x, int y) {
            pixels[static_cast<std::size_t>(y) * frame_side +
                   static_cast<std::size_t>(x)] = c;
        });
        written += covered[n];
        n = (n + 1) % triangle_count;
        ++colour;
        benchmark::ClobberMemory();
    }
    report(state, written);
}

void fixed_1x1(benchmark::State& state) {
    const auto& set = triangles(static_cast<int>(state.range(0))).fixed;
    run(state, [&](std::size_t n, auto&& emit) {
        edge_rasterize_pixels(set[n], Viewport{frame_side, frame_side}, emit);
    });
}

void fixed_8x8(benchmark::State& state) {
    const auto& set = triangles(static_cast<int>(state.range(0))).fixed;
    run(state, [&](std::size_t n, auto&& emit) {
        edge_rasterize_blocks(set[n], Viewport{frame_side, frame_side}, emit);
    });
}

void float_1x1(benchmark::State& state) {
    const auto& set = triangles(static_cast<int>(state.range(0))).floats;
    run(state, [&](std::size_t n, auto&& emit) {
        edge_rasterize_pixels(set[n], Viewport{frame_side, frame_side}, emit);
    });
}

void float_8x8(benchmark::State& state) {
    const auto& set = triangles(static_cast<int>(state.range(0))).floats;
    run(state, [&](std::size_t n, auto&& emit) {
        edge_rasterize_blocks(set[n], Viewport{frame_side, frame_side}, emit);
    });
}

void naive(benchmark::State& state) {
    const auto& set = triangles(static_cast<int>(state.range(0))).floats;
    run(state, [&](std::size_t n, auto&& emit) {
        naive_rasterize(set[n], Viewport{frame_side, frame_side}, emit);
    });
}

/// The ceiling: writing `area` pixels as a near-square rectangle, row by row, with no
/// coverage test at all, at the positions the triangles have.
void plain_fill(benchmark::State& state) {
    const auto area = static_cast<int>(state.range(0));
    const auto& set = triangles(area).fixed;
    const int width = static_cast<int>(std::ceil(std::sqrt(area)));
    std::uint32_t* pixels = frame().data();
    std::uint32_t colour = 0xff00ff00u;
    std::size_t n = 0;
    for (auto _ : state) {
        const int x0 = static_cast<int>(set[n][0].x >> 8) % (frame_side - width);
        const int y0 = static_cast<int>(set[n][0].y >> 8) % (frame_side - width);
        for (int left = area, y = y0; left > 0; left -= width, ++y) {
            std::uint32_t* row = pixels + static_cast<std::size_t>(y) * frame_side + x0;
            std::fill_n(row, std::min(left, width), colour);
        }
        n = (n + 1) % triangle_count;
        ++colour;
        benchmark::ClobberMemory();
    }
    report(state, static_cast<std::int64_t>(state.iterations()) * area);
}

void register_all() {
    const std::pair<const char*, void (*)(benchmark::State&)> variants[] = {
        {"float_1x1", float_1x1}, {"float_8x8", float_8x8}, {"fixed_1x1", fixed_1x1},
        {"fixed_8x8", fixed_8x8}, {"naive", naive},         {"plain_fill", plain_fill}};
    for (const auto& [name, function] : variants) {
        for (int area : {3, 15, 80}) {
            benchmark::RegisterBenchmark((std::string("table/") + name).c_str(), function)
                ->Arg(area);
        }
    }
    for (const auto& [name, function] : variants) {
        for (int area = 2; area <= 65536; area *= 2) {
            benchmark::RegisterBenchmark((std::string("sweep/") + name).c_str(), function)
                ->Arg(area);
        }
    }
}

} // namespace

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
        return 1;
    }
    register_all();
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
}
