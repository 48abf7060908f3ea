#include "exactpixels/tiled_rasterizer.hpp"

#include "exactpixels/block_masks.hpp"
#include "exactpixels/edge_rasterizer.hpp"
#include "exactpixels/error.hpp"
#include "exactpixels/gradients.hpp"
#include "exactpixels/row_runs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
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
        std::fill_n(t.colour + index(t, s.x_begin, s.y), s.x_end - s.x_begin, tri.colour);
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
    if (!s.empty) {
        traverse_runs_fast(s, pixel_bounds(tri.v, viewport_of(target)),
                           [&](Span run) { plot_run(target, tri, run); });
    }
}

void draw_masks(const RenderTarget& target, const FlatTriangle& tri) {
    check_fixed_triangle(tri.v);
    const EdgeSetup<FixedEdge> s = setup_edges(tri.v);
    if (s.empty) {
        return;
    }
    traverse_block_masks(s, pixel_bounds(tri.v, viewport_of(target)), [&](BlockMask m) {
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
    // Binning: each tile lists, in submission order, the triangles whose bounds meet it.
    std::vector<Prepared> prepared(triangles.size());
    std::vector<std::vector<std::uint32_t>> bins(static_cast<std::size_t>(tiles_x) *
                                                 static_cast<std::size_t>(tiles_y));
    for (std::size_t n = 0; n < triangles.size(); ++n) {
        Prepared& p = prepared[n];
        p.edges = setup_edges(triangles[n].v);
        p.bounds = pixel_bounds(triangles[n].v, viewport_of(target));
        if (p.edges.empty || p.bounds.empty()) {
            continue;
        }
        for (int ty = p.bounds.y_begin / tile_size; ty * tile_size < p.bounds.y_end;
             ++ty) {
            for (int tx = p.bounds.x_begin / tile_size; tx * tile_size < p.bounds.x_end;
                 ++tx) {
                bins[static_cast<std::size_t>(ty * tiles_x + tx)].push_back(
                    static_cast<std::uint32_t>(n));
            }
        }
    }
    // Drawing: a tile is one thread's; its triangles in order, each tested against the
    // whole tile first (eq. 2.9): outside, nothing; inside, plain runs; else exact runs.
    const auto draw_tile = [&](int tile) {
        const int tx = tile % tiles_x, ty = tile / tiles_x;
        for (const std::uint32_t n : bins[static_cast<std::size_t>(tile)]) {
            const Prepared& p = prepared[n];
            const PixelRect r{std::max(p.bounds.x_begin, tx * tile_size),
                              std::max(p.bounds.y_begin, ty * tile_size),
                              std::min(p.bounds.x_end, (tx + 1) * tile_size),
                              std::min(p.bounds.y_end, (ty + 1) * tile_size)};
            if (r.empty()) {
                continue;
            }
            const auto run = [&](Span s) { plot_run(target, triangles[n], s); };
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
    const int tile_count = tiles_x * tiles_y;
    std::atomic<int> next{0};
    const auto worker = [&] {
        for (int tile = next++; tile < tile_count; tile = next++) {
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
