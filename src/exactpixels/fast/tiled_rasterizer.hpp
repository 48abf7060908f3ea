// tiled_rasterizer.hpp: many flat triangles drawn into RGBA8 (with an optional 32-bit
// depth test) through 64 x 64 tiles, by any number of threads, with the same picture
// as drawing them one after another pixel by pixel.
//
// Usage:
//   std::vector<FlatTriangle> tris = {{v, depth_plane(v, {0.5f, 0.2f, 0.9f}), red}, ...};
//   RenderTarget target{fb_pixels, depth_or_null, width, height};
//   draw_tiled(target, tris, 2);            // two threads, started for this call
//   TiledRenderer renderer(2);              // two threads kept from call to call
//   renderer.draw(target, tris);            // every frame: the same pixels again
//   draw_reference(target, tris);           // the teaching path: the same pixels
//
// Vertices are snapped (1/256 px, within +-max_fixed_coordinate). A pixel is drawn when
// its centre is covered (top-left rule) and, with a depth buffer, when its depth is
// less than the stored one (then both are written). Depth is a float plane evaluated
// at every pixel by DepthPlane::at, in the same operations on every path, so every path
// writes the same bits. Triangles are drawn in submission order within every pixel:
// each tile belongs to one thread, which draws its triangles in order.
#pragma once

#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/base/framebuffer.hpp"
#include "exactpixels/fast/worker_pool.hpp"
#include "exactpixels/raster/edge_function.hpp"

#include <array>
#include <memory>
#include <span>

namespace exactpixels {

/// Depth over a triangle: z(x, y) = (z0 + y dzdy) + x dzdx at pixel (x, y), in float.
struct DepthPlane {
    float z0 = 0;   ///< z at the centre of pixel (0, 0)
    float dzdx = 0; ///< change of z per pixel to the right
    float dzdy = 0; ///< change of z per pixel down
    /// z at pixel (x, y): the one formula every path uses (same rounding everywhere).
    float at(int x, int y) const {
        return (z0 + static_cast<float>(y) * dzdy) + static_cast<float>(x) * dzdx;
    }
};

/// The depth plane through z[i] at vertex v[i] (closed form, @eq:closed-form, in double,
/// then rounded to float). Zero area: the constant z[0].
DepthPlane depth_plane(const std::array<FixedPoint2, 3>& v,
                       const std::array<float, 3>& z);

/// A triangle of one colour: snapped vertices, its depth plane and its colour.
struct FlatTriangle {
    std::array<FixedPoint2, 3> v; ///< vertices in 1/256 px
    DepthPlane depth;             ///< ignored when the target has no depth buffer
    Rgba8 colour;                 ///< written to every pixel drawn
};

/// Where triangles are drawn: row-major RGBA8 pixels and, optionally, float depth.
struct RenderTarget {
    Rgba8* colour = nullptr; ///< width * height pixels, rows top to bottom
    float* depth = nullptr;  ///< width * height depths, or nullptr: no depth test
    int width = 0;           ///< pixels per row
    int height = 0;          ///< rows
};

/// Writes `colour` into count pixels from `first` on and nowhere else: with SSE2, four
/// pixels per 16-byte store, the last store overlapping the one before when count is
/// not a multiple of four; runs shorter than four, and without SSE2, pixel by pixel.
void fill_run(Rgba8* first, int count, Rgba8 colour);

/// Bounding boxes of at most this many pixels are walked pixel by pixel by the fast
/// paths: the per-row or per-block setup would cost more than it saves.
inline constexpr int small_box_pixels = 64;

/// The side of a tile in pixels: a multiple of the 8 x 8 block. (The most threads a
/// tiled renderer accepts is max_threads, worker_pool.hpp.)
inline constexpr int tile_size = 64;

/// The teaching path: every triangle in order, pixel by pixel (traverse_pixels),
/// depth-tested when the target has depth. Throws Error for an out-of-range vertex
/// before drawing anything.
void draw_reference(const RenderTarget& target, std::span<const FlatTriangle> triangles);

/// One triangle, the same pixels as draw_reference, in covered runs (row_runs.hpp):
/// a run without depth is one fill_run, one with depth goes to the depth kernel of
/// chosen_simd()'s instruction set (depth_lanes_kernel.hpp).
void draw_runs(const RenderTarget& target, const FlatTriangle& triangle);

/// One triangle, the same pixels as draw_reference, in 8 x 8 masks (block_masks.hpp):
/// whole rows of a mask without depth are 8 stores at once.
void draw_masks(const RenderTarget& target, const FlatTriangle& triangle);

/// The tiled renderer with its threads (a WorkerPool) and its bins' memory kept from one
/// draw to the next: draw() gives the same pixels as draw_reference. The threads set up
/// and bin contiguous chunks of the triangles, taken from a shared counter, each chunk
/// into its own per-tile lists; then each thread draws the tiles of its own band of rows
/// and helps with the others' bands when done, and a tile walks the chunks' lists in
/// chunk order, which is submission order. Each tile is
/// trivially rejected or accepted per triangle, else drawn in covered runs
/// (row_runs.hpp).
class TiledRenderer {
  public:
    /// A renderer drawing with `threads` threads (1 .. max_threads), the caller's
    /// included; throws Error for any other count.
    explicit TiledRenderer(int threads);
    ~TiledRenderer();
    TiledRenderer(const TiledRenderer&) = delete;
    TiledRenderer& operator=(const TiledRenderer&) = delete;

    /// The number of threads that draw, the caller included.
    int threads() const { return pool_.size(); }

    /// Draws `triangles` in order into `target`. Throws Error for a bad vertex before
    /// drawing anything. Not reentrant: one draw at a time per renderer.
    void draw(const RenderTarget& target, std::span<const FlatTriangle> triangles);

  private:
    struct State; ///< the per-thread bins, prepared triangles and the phase barrier
    WorkerPool pool_;
    std::unique_ptr<State> state_;
};

/// The same pixels as draw_reference, through a TiledRenderer of `threads` threads
/// (1 .. max_threads) made for this call: its threads are started and joined here.
/// Throws Error for a bad thread count or vertex, before drawing anything.
void draw_tiled(const RenderTarget& target, std::span<const FlatTriangle> triangles,
                int threads);

} // namespace exactpixels
