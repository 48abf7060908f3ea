#include "exactpixels/raster/tiled_rasterizer.hpp"

#include "exactpixels/base/error.hpp"
#include "exactpixels/raster/block_masks.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"
#include "exactpixels/raster/gradients.hpp"
#include "exactpixels/raster/row_runs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstring>
#include <thread>
#include <vector>

namespace exactpixels {

DepthPlane depth_plane(const std::array<FixedPoint2, 3>& v,
                       const std::array<float, 3>& z) {
    PlaneSamples<double> s;
    for (std::size_t i = 0; i < 3; ++i) {
        const Point2 p = to_pixels(v[i]);
        s.x[i] = p.x;
        s.y[i] = p.y;
        s.c[i] = z[i];
    }
    const Gradient<double> g = closed_form_gradient(s);
    // z at the centre (0.5, 0.5) of pixel (0, 0), from vertex 0 along the plane.
    const double z0 = s.c[0] + (0.5 - s.x[0]) * g.dx + (0.5 - s.y[0]) * g.dy;
    return {static_cast<float>(z0), static_cast<float>(g.dx), static_cast<float>(g.dy)};
}

void fill_run(Rgba8* first, int count, Rgba8 colour) {
    std::array<Rgba8, 16> pattern;
    pattern.fill(colour);
    for (; count >= 16; count -= 16, first += 16) {
        std::memcpy(first, pattern.data(), sizeof pattern);
    }
    for (int i = 0; i < count; ++i) {
        first[i] = colour;
    }
}

namespace {

std::size_t index(const RenderTarget& t, int x, int y) {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(t.width) +
           static_cast<std::size_t>(x);
}

//> plot-pixel
/// Draws pixel (x, y) of `tri`: depth-tested (less) when the target has depth.
void plot(const RenderTarget& t, const FlatTriangle& tri, int x, int y) {
    const std::size_t i = index(t, x, y);
    if (t.depth != nullptr) {
        const float z = tri.depth.at(x, y);
        if (!(z < t.depth[i])) {
            return;
        }
        t.depth[i] = z;
    }
    t.colour[i] = tri.colour;
}
//< plot-pixel

/// Draws the run s of `tri`: one fill without depth, pixel by pixel with it.
void plot_run(const RenderTarget& t, const FlatTriangle& tri, Span s) {
    if (t.depth == nullptr) {
        fill_run(t.colour + index(t, s.x_begin, s.y), s.x_end - s.x_begin, tri.colour);
        return;
    }
    for (int x = s.x_begin; x < s.x_end; ++x) {
        plot(t, tri, x, s.y);
    }
}

Viewport viewport_of(const RenderTarget& t) {
    return {t.width, t.height};
}

void check_threads(int threads) {
    if (threads < 1 || threads > max_threads) {
        throw Error(
            fmt::format("thread count {} is outside 1 .. {}", threads, max_threads));
    }
}

void check_all(std::span<const FlatTriangle> triangles) {
    for (std::size_t n = 0; n < triangles.size(); ++n) {
        try {
            check_fixed_triangle(triangles[n].v);
        } catch (const Error& error) {
            throw Error(fmt::format("triangle {}: {}", n, error.what()));
        }
    }
}

/// True when r is small enough to walk pixel by pixel (small_box_pixels).
bool small(PixelRect r) {
    return r.empty() || (r.x_end - r.x_begin) * (r.y_end - r.y_begin) <= small_box_pixels;
}

/// Draws the pixels of r covered by `tri` (edges s) pixel by pixel.
void walk(const RenderTarget& t, const FlatTriangle& tri, const EdgeSetup<FixedEdge>& s,
          PixelRect r) {
    auto emit = [&](int x, int y) { plot(t, tri, x, y); };
    traverse_pixels(s, r, emit);
}

/// A triangle ready to draw: its edges and pixel bounds (setup done once, not per tile).
struct Prepared {
    EdgeSetup<FixedEdge> edges;
    PixelRect bounds;
};

} // namespace

void draw_reference(const RenderTarget& target, std::span<const FlatTriangle> triangles) {
    check_all(triangles);
    for (const FlatTriangle& tri : triangles) {
        edge_rasterize_pixels(tri.v, viewport_of(target),
                              [&](int x, int y) { plot(target, tri, x, y); });
    }
}

void draw_runs(const RenderTarget& target, const FlatTriangle& tri) {
    check_fixed_triangle(tri.v);
    const EdgeSetup<FixedEdge> s = setup_edges(tri.v);
    const PixelRect r = pixel_bounds(tri.v, viewport_of(target));
    if (s.empty || r.empty()) {
        return;
    }
    if (small(r)) {
        walk(target, tri, s, r);
        return;
    }
    traverse_runs_fast(s, r, [&](Span run) { plot_run(target, tri, run); });
}

void draw_masks(const RenderTarget& target, const FlatTriangle& tri) {
    check_fixed_triangle(tri.v);
    const EdgeSetup<FixedEdge> s = setup_edges(tri.v);
    const PixelRect r = pixel_bounds(tri.v, viewport_of(target));
    if (s.empty || r.empty()) {
        return;
    }
    if (small(r)) {
        walk(target, tri, s, r);
        return;
    }
    traverse_block_masks(s, r, [&](BlockMask m) {
        if (target.depth == nullptr) {
            fill_block_mask(target.colour, target.width, m, tri.colour);
        } else {
            for_each_pixel(m, [&](int x, int y) { plot(target, tri, x, y); });
        }
    });
}

//> draw-tiled
void draw_tiled(const RenderTarget& target, std::span<const FlatTriangle> triangles,
                int threads) {
    check_threads(threads);
    check_all(triangles);
    const int tiles_x = (target.width + tile_size - 1) / tile_size;
    const int tiles_y = (target.height + tile_size - 1) / tile_size;
    const auto tile_count = static_cast<std::size_t>(tiles_x * tiles_y);
    // Binning: every tile lists, in submission order, the triangles whose bounds meet
    // it, all in one array (a counting sort: count per tile, offsets, then fill).
    std::vector<Prepared> prepared(triangles.size());
    std::vector<std::uint32_t> first(tile_count + 1, 0); // tile k: [first[k], first[k+1])
    const auto for_each_tile = [&](const PixelRect& b, auto&& f) {
        for (int ty = b.y_begin / tile_size; ty * tile_size < b.y_end; ++ty) {
            for (int tx = b.x_begin / tile_size; tx * tile_size < b.x_end; ++tx) {
                f(static_cast<std::size_t>(ty * tiles_x + tx));
            }
        }
    };
    for (std::size_t n = 0; n < triangles.size(); ++n) {
        Prepared& p = prepared[n];
        p.edges = setup_edges(triangles[n].v);
        p.bounds = p.edges.empty ? PixelRect{}
                                 : pixel_bounds(triangles[n].v, viewport_of(target));
        for_each_tile(p.bounds, [&](std::size_t tile) { ++first[tile + 1]; });
    }
    for (std::size_t k = 0; k < tile_count; ++k) {
        first[k + 1] += first[k];
    }
    std::vector<std::uint32_t> bins(first[tile_count]);
    std::vector<std::uint32_t> end(first.begin(), first.end() - 1);
    for (std::size_t n = 0; n < triangles.size(); ++n) {
        for_each_tile(prepared[n].bounds, [&](std::size_t tile) {
            bins[end[tile]++] = static_cast<std::uint32_t>(n);
        });
    }
    // Drawing: a tile is one thread's; its triangles in order, each tested against the
    // whole tile first (@eq:edge-block): outside, nothing; inside, plain runs; else exact
    // runs.
    const auto draw_tile = [&](std::size_t tile) {
        const int tx = static_cast<int>(tile) % tiles_x;
        const int ty = static_cast<int>(tile) / tiles_x;
        for (std::uint32_t k = first[tile]; k < first[tile + 1]; ++k) {
            const FlatTriangle& tri = triangles[bins[k]];
            const Prepared& p = prepared[bins[k]];
            const PixelRect r{std::max(p.bounds.x_begin, tx * tile_size),
                              std::max(p.bounds.y_begin, ty * tile_size),
                              std::min(p.bounds.x_end, (tx + 1) * tile_size),
                              std::min(p.bounds.y_end, (ty + 1) * tile_size)};
            const auto run = [&](Span s) { plot_run(target, tri, s); };
            if (small(r)) {
                walk(target, tri, p.edges, r);
                continue;
            }
            switch (classify_block(p.edges, r)) {
            case BlockClass::outside:
                break;
            case BlockClass::inside:
                for (int y = r.y_begin; y < r.y_end; ++y) {
                    run(Span{y, r.x_begin, r.x_end});
                }
                break;
            case BlockClass::partial:
                traverse_runs_fast(p.edges, r, run);
                break;
            }
        }
    };
    std::atomic<std::size_t> next{0};
    const auto worker = [&] {
        for (std::size_t tile = next++; tile < tile_count; tile = next++) {
            draw_tile(tile);
        }
    };
    std::vector<std::jthread> pool;
    for (int k = 1; k < threads; ++k) {
        pool.emplace_back(worker);
    }
    worker(); // the calling thread is one of the `threads`
}
//< draw-tiled

} // namespace exactpixels
