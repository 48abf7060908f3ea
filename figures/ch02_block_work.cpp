// Figure data for chapter 2's Exercise 6: the work of the block traversal against the
// pixel walk, for blocks of 4, 8 and 16 px, counted instead of timed. The pixel walk
// tests every pixel of the bounding box (three edge tests each); the block traversal
// classifies each block that meets the box (classify_block: two corners per edge, six
// edge tests), fills the inside blocks with no test and walks the partial ones pixel by
// pixel; a box within one block is walked directly, as traverse_blocks does. For
// triangle areas of 8 to 32768 px (200 random triangles each, no slivers, snapped to the
// 1/256 px grid in a 1024 x 1024 viewport) it writes ch02_block_work.txt into the folder
// argv[1]: for each block size B and area A the ratio of the block traversal's edge tests
// to the pixel walk's, ratio_B_A, and for each B the smallest area at which it saves at
// least a tenth of the tests (ratio below 0.9), crossover_B (0 if none).
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/base/split_mix.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"
#include "support/figure_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

namespace {

using namespace exactpixels;

constexpr int viewport = 1024;

/// A random triangle of about `area` px, no angle thinner than a tenth of its box.
std::array<FixedPoint2, 3> random_triangle(SplitMix& random, double area) {
    for (;;) {
        std::array<Point2, 3> p{};
        for (Point2& q : p) {
            q = {random.uniform(), random.uniform()};
        }
        const double a = 0.5 * std::abs((p[1].x - p[0].x) * (p[2].y - p[0].y) -
                                        (p[1].y - p[0].y) * (p[2].x - p[0].x));
        if (a < 0.1) {
            continue; // a sliver: its box is mostly empty, a different question
        }
        const double scale = std::sqrt(area / a);
        const double ox = random.uniform(0.0, viewport - 2.0 * scale);
        const double oy = random.uniform(0.0, viewport - 2.0 * scale);
        std::array<FixedPoint2, 3> v{};
        for (std::size_t i = 0; i < 3; ++i) {
            v[i] = snap_in_range({ox + scale * p[i].x, oy + scale * p[i].y});
        }
        return v;
    }
}

/// Edge tests of the block traversal with blocks of `size` px over the box r.
long long block_tests(const EdgeSetup<FixedEdge>& s, PixelRect r, int size) {
    const auto area = [](PixelRect b) {
        return static_cast<long long>(b.x_end - b.x_begin) * (b.y_end - b.y_begin);
    };
    if (r.x_end - r.x_begin <= size && r.y_end - r.y_begin <= size) {
        return 3 * area(r);
    }
    long long tests = 0;
    for (int by = r.y_begin - r.y_begin % size; by < r.y_end; by += size) {
        for (int bx = r.x_begin - r.x_begin % size; bx < r.x_end; bx += size) {
            const PixelRect b{std::max(bx, r.x_begin), std::max(by, r.y_begin),
                              std::min(bx + size, r.x_end), std::min(by + size, r.y_end)};
            tests += 6;
            if (classify_block(s, b) == BlockClass::partial) {
                tests += 3 * area(b);
            }
        }
    }
    return tests;
}

} // namespace

int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    std::string facts = "# chapter 2, Exercise 6: block traversal's edge tests over the "
                        "pixel walk's, by block size and triangle area\n";
    try {
        for (const int size : {4, 8, 16}) {
            SplitMix random{2};
            int crossover = 0;
            for (const int area : {8, 32, 128, 512, 2048, 8192, 32768}) {
                long long walk = 0, blocks = 0;
                for (int t = 0; t < 200; ++t) {
                    const std::array<FixedPoint2, 3> v = random_triangle(random, area);
                    const EdgeSetup<FixedEdge> s = setup_edges(v);
                    const PixelRect r = pixel_bounds(v, Viewport{viewport, viewport});
                    walk += 3 * static_cast<long long>(r.x_end - r.x_begin) *
                            (r.y_end - r.y_begin);
                    blocks += block_tests(s, r, size);
                }
                const double ratio =
                    static_cast<double>(blocks) / static_cast<double>(walk);
                if (crossover == 0 && ratio < 0.9) {
                    crossover = area;
                }
                facts += fmt::format("ratio_{}_{} {:.4f}\n", size, area, ratio);
            }
            facts += fmt::format("crossover_{} {}\n", size, crossover);
        }
        write_figure_file(folder / "ch02_block_work.txt", facts);
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch02_block_work: %s\n", error.what());
        return 1;
    }
}
