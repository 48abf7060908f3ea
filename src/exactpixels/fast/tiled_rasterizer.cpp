#include "exactpixels/fast/tiled_rasterizer.hpp"

#include "exactpixels/base/error.hpp"
#include "exactpixels/fast/block_masks.hpp"
#include "exactpixels/fast/depth_lanes.hpp"
#include "exactpixels/fast/depth_lanes_kernel.hpp"
#include "exactpixels/fast/row_runs.hpp"
#include "exactpixels/fast/sign_lanes4.hpp"
#include "exactpixels/fast/tiny_triangle.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"
#include "exactpixels/raster/gradients.hpp"

#include <fmt/format.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstring>
#include <optional>
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

//> fill-run
void fill_run(Rgba8* first, int count, Rgba8 colour) {
#if defined(__SSE2__)
    if (count >= 4) { // four pixels per store; the last four overlap the ones before
        std::int32_t bits;
        std::memcpy(&bits, &colour, sizeof bits);
        const __m128i four = _mm_set1_epi32(bits);
        for (int i = 0; i + 4 < count; i += 4) {
            _mm_storeu_si128(reinterpret_cast<__m128i*>(first + i), four);
        }
        _mm_storeu_si128(reinterpret_cast<__m128i*>(first + count - 4), four);
        return;
    }
    if (count > 0) { // 1 to 3 pixels: the first, middle and last, which overlap
        first[0] = first[count / 2] = first[count - 1] = colour;
    }
#else
    for (int i = 0; i < count; ++i) {
        first[i] = colour;
    }
#endif
}
//< fill-run

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

/// A triangle's runs ready to draw: its plane and colour, and the depth kernel of the
/// chosen instruction set (made once per triangle, used on every run).
struct RunDrawer {
    RunPlane plane;   ///< the depth plane and the colour
    DepthRunFn depth; ///< depth_run_kernel(chosen_simd()); none without depth
    RunDrawer(const FlatTriangle& tri, DepthRunFn kernel)
        : plane{tri.depth.z0, tri.depth.dzdx, tri.depth.dzdy, tri.colour}, depth(kernel) {
    }
};

/// Draws the run s: one fill without depth, a register of depth tests at a time with it
/// (depth_lanes_kernel.hpp: the bits plot writes).
void plot_run(const RenderTarget& t, const RunDrawer& d, Span s) {
    if (t.depth == nullptr) {
        fill_run(t.colour + index(t, s.x_begin, s.y), s.x_end - s.x_begin,
                 d.plane.colour);
        return;
    }
    const std::size_t row = index(t, 0, s.y);
    d.depth(d.plane, s.y, s.x_begin, s.x_end, t.depth + row, t.colour + row);
}

Viewport viewport_of(const RenderTarget& t) {
    return {t.width, t.height};
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

/// Draws the pixels of r covered by `tri` when r is small and the triangle tiny (at most
/// 32 px wide and high): in int32 lanes, with no 64-bit setup. Returns false, drawing
/// nothing, otherwise (the caller walks the box or draws runs).
bool draw_tiny(const RenderTarget& t, const FlatTriangle& tri, PixelRect r) {
    if (!small(r) || !is_tiny(tri.v)) {
        return false;
    }
    if (t.depth == nullptr) { // flat: a store per pixel, no depth test to skip
        traverse_tiny<Lanes4>(
            tri.v, r, [&](int x, int y) { t.colour[index(t, x, y)] = tri.colour; });
    } else {
        traverse_tiny<Lanes4>(tri.v, r, [&](int x, int y) { plot(t, tri, x, y); });
    }
    return true;
}

/// What draw_runs and draw_masks do first: check `tri`, find its pixel bounds r, and
/// draw it here when r is small (tiny in lanes, else pixel by pixel) or empty. Returns
/// the edges when the caller still has to draw r, nothing when the triangle is done.
std::optional<EdgeSetup<FixedEdge>> draw_if_small(const RenderTarget& target,
                                                  const FlatTriangle& tri, PixelRect& r) {
    check_fixed_triangle(tri.v);
    r = pixel_bounds(tri.v, viewport_of(target));
    if (r.empty() || draw_tiny(target, tri, r)) {
        return std::nullopt;
    }
    const EdgeSetup<FixedEdge> s = setup_edges(tri.v);
    if (s.empty) {
        return std::nullopt;
    }
    if (small(r)) {
        walk(target, tri, s, r);
        return std::nullopt;
    }
    return s;
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
    PixelRect r;
    const std::optional<EdgeSetup<FixedEdge>> s = draw_if_small(target, tri, r);
    if (!s) {
        return;
    }
    if (target.depth == nullptr) { // flat: plot_run's fill, decided once per triangle
        traverse_runs_stepped(*s, r, [&](Span run) {
            fill_run(target.colour + index(target, run.x_begin, run.y),
                     run.x_end - run.x_begin, tri.colour);
        });
        return;
    }
    const RunDrawer d(tri, depth_run_kernel(chosen_simd())); // plot_run's depth half
    traverse_runs_stepped(*s, r, [&](Span run) {
        const std::size_t row = index(target, 0, run.y);
        d.depth(d.plane, run.y, run.x_begin, run.x_end, target.depth + row,
                target.colour + row);
    });
}

void draw_masks(const RenderTarget& target, const FlatTriangle& tri) {
    PixelRect r;
    const std::optional<EdgeSetup<FixedEdge>> s = draw_if_small(target, tri, r);
    if (!s) {
        return;
    }
    traverse_block_masks(*s, r, [&](BlockMask m) {
        if (target.depth == nullptr) {
            fill_block_mask(target.colour, target.width, m, tri.colour);
        } else {
            for (int j = 0; j < 8; ++j) { // rows below the image have no bits
                const std::uint8_t bits = m.row(j);
                if (bits != 0) {
                    const std::size_t row = index(target, 0, m.y + j);
                    depth_mask_row(tri.depth, tri.colour, m.y + j, m.x, bits,
                                   target.width, target.depth + row, target.colour + row);
                }
            }
        }
    });
}

//> tiled-state
namespace {
/// One chunk's bins: tile k lists the triangles of the chunk (a contiguous slice of the
/// submission order) whose bounds meet it, in order, as bins[first[k]] ..
/// bins[first[k + 1] - 1] (a counting sort: count per tile, offsets, then fill). Kept
/// from draw to draw, so the memory is allocated once. The three vectors begin a cache
/// line of their own; their arrays are separate allocations.
struct alignas(64) ChunkBins {
    std::vector<std::uint32_t> first; ///< tile_count + 1 offsets into bins
    std::vector<std::uint32_t> bins;  ///< triangle indices, tile after tile
    std::vector<std::uint32_t> fill;  ///< while filling: each tile's next free place
};

/// Chunks per thread: more than one, so that a thread that starts late (the machine is
/// busy) finds the others have binned its share, and nobody waits for it.
constexpr std::size_t chunks_per_thread = 4;
/// The fewest triangles worth a chunk of their own: each chunk costs every tile a look.
constexpr std::size_t min_chunk_triangles = 64;

/// How many chunks `triangles` triangles are binned in by `threads` threads.
std::size_t chunk_count(std::size_t triangles, int threads) {
    if (threads == 1) {
        return 1;
    }
    const std::size_t most = chunks_per_thread * static_cast<std::size_t>(threads);
    return std::clamp<std::size_t>(triangles / min_chunk_triangles, 1, most);
}

/// A counter on a cache line of its own: the next tile of one thread's band.
struct alignas(64) TileCounter {
    std::atomic<std::size_t> next{0}; ///< the band's next tile not yet taken
};
} // namespace

struct TiledRenderer::State {
    explicit State(int threads) : bands(static_cast<std::size_t>(threads)) {}
    std::vector<Prepared> prepared;          ///< every triangle's setup, by index
    std::vector<ChunkBins> chunks;           ///< at least the chunks of this draw
    std::atomic<std::size_t> next_chunk{0};  ///< the next chunk to bin
    std::atomic<std::size_t> chunks_done{0}; ///< chunks binned (or failed)
    std::vector<TileCounter> bands;          ///< per thread: its band of tiles
    std::atomic<bool> failed{false};         ///< a chunk could not be binned: no drawing

    /// Readies a draw of `triangles` triangles in `chunks` chunks over `tiles` tiles.
    void start(std::size_t triangles, std::size_t chunks, std::size_t tiles);
    /// The first tile of band b of a frame of `tiles` tiles (b = bands.size(): the end).
    std::size_t band_begin(std::size_t b, std::size_t tiles) const {
        return tiles * b / bands.size();
    }
    /// One thread's share of binning: bin(c) for every chunk c it takes from next_chunk,
    /// then a wait for the other threads' chunks. False when a chunk failed (then
    /// nothing is drawn); a failure of this thread's own is rethrown.
    template <class BinFn> bool bin_chunks(std::size_t chunks, BinFn&& bin);
    /// Thread `thread`'s share of drawing: draw(tile) for the tiles of its own band,
    /// then for those left in the other bands.
    template <class TileFn> void draw_bands(int thread, std::size_t tiles, TileFn&& draw);
};
//< tiled-state

TiledRenderer::TiledRenderer(int threads)
    : pool_(threads), state_(std::make_unique<State>(threads)) {
}

TiledRenderer::~TiledRenderer() = default;

//> draw-tiled
namespace {
/// The frame in tiles: tile_size squares, `across` to a row, `count` in all.
struct TileGrid {
    int across;        ///< tiles per row
    std::size_t count; ///< tiles in the frame

    /// The tiles of a width x height frame (the last row and column may be cut).
    TileGrid(int width, int height)
        : across((width + tile_size - 1) / tile_size),
          count(
              static_cast<std::size_t>(across * ((height + tile_size - 1) / tile_size))) {
    }

    /// Calls f(tile) for every tile that b meets.
    template <class TileFn> void for_each_tile(const PixelRect& b, TileFn&& f) const {
        for (int ty = b.y_begin / tile_size; ty * tile_size < b.y_end; ++ty) {
            for (int tx = b.x_begin / tile_size; tx * tile_size < b.x_end; ++tx) {
                f(static_cast<std::size_t>(ty * across + tx));
            }
        }
    }

    /// The part of b within tile `tile`.
    PixelRect clip(const PixelRect& b, std::size_t tile) const {
        const int tx = static_cast<int>(tile) % across;
        const int ty = static_cast<int>(tile) / across;
        return {std::max(b.x_begin, tx * tile_size), std::max(b.y_begin, ty * tile_size),
                std::min(b.x_end, (tx + 1) * tile_size),
                std::min(b.y_end, (ty + 1) * tile_size)};
    }
};

/// Binning one chunk, the triangles [begin, end) of the submission order: each is set
/// up (prepared[n]) and sorted into the chunk's bins of the tiles its bounds meet.
void bin_chunk(const RenderTarget& target, std::span<const FlatTriangle> triangles,
               std::size_t begin, std::size_t end, const TileGrid& grid,
               std::span<Prepared> prepared, ChunkBins& chunk) {
    std::vector<std::uint32_t>& first = chunk.first;
    first.assign(grid.count + 1, 0);
    for (std::size_t n = begin; n < end; ++n) {
        Prepared& p = prepared[n];
        p.edges = setup_edges(triangles[n].v);
        p.bounds = p.edges.empty ? PixelRect{}
                                 : pixel_bounds(triangles[n].v, viewport_of(target));
        grid.for_each_tile(p.bounds, [&](std::size_t tile) { ++first[tile + 1]; });
    }
    for (std::size_t k = 0; k < grid.count; ++k) {
        first[k + 1] += first[k];
    }
    std::vector<std::uint32_t>& bins = chunk.bins;
    bins.resize(first[grid.count]);
    std::vector<std::uint32_t>& end_of = chunk.fill;
    end_of.assign(first.begin(), first.end() - 1);
    for (std::size_t n = begin; n < end; ++n) {
        grid.for_each_tile(prepared[n].bounds, [&](std::size_t tile) {
            bins[end_of[tile]++] = static_cast<std::uint32_t>(n);
        });
    }
}

/// Drawing one tile's triangles of one chunk, in order, each tested against the whole
/// tile first (@eq:edge-block): outside, nothing; inside, plain runs; else exact runs.
void draw_tile(const RenderTarget& target, std::span<const FlatTriangle> triangles,
               std::span<const Prepared> prepared, const TileGrid& grid, std::size_t tile,
               const ChunkBins& from, DepthRunFn kernel) {
    for (std::uint32_t k = from.first[tile]; k < from.first[tile + 1]; ++k) {
        const FlatTriangle& tri = triangles[from.bins[k]];
        const Prepared& p = prepared[from.bins[k]];
        const PixelRect r = grid.clip(p.bounds, tile);
        const RunDrawer d(tri, kernel);
        const auto run = [&](Span s) { plot_run(target, d, s); };
        if (small(r)) {
            if (!draw_tiny(target, tri, r)) {
                walk(target, tri, p.edges, r);
            }
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
            traverse_runs_stepped(p.edges, r, run);
            break;
        }
    }
}
} // namespace

void TiledRenderer::State::start(std::size_t triangles, std::size_t chunk_total,
                                 std::size_t tiles) {
    prepared.resize(triangles);
    if (chunks.size() < chunk_total) {
        chunks.resize(chunk_total);
    }
    next_chunk = 0;
    chunks_done = 0;
    for (std::size_t b = 0; b < bands.size(); ++b) {
        bands[b].next = band_begin(b, tiles);
    }
    failed = false;
}

template <class BinFn>
bool TiledRenderer::State::bin_chunks(std::size_t chunk_total, BinFn&& bin) {
    for (std::size_t c = next_chunk++; c < chunk_total; c = next_chunk++) {
        try {
            bin(c);
        } catch (...) { // out of memory: count the chunk, so nobody waits; no drawing
            failed = true;
            if (++chunks_done == chunk_total) {
                chunks_done.notify_all();
            }
            throw;
        }
        if (++chunks_done == chunk_total) {
            chunks_done.notify_all(); // the last chunk is binned: every tile may be drawn
        }
    }
    for (std::size_t d = chunks_done.load(); d < chunk_total; d = chunks_done.load()) {
        chunks_done.wait(d); // another thread bins the last chunks
    }
    return !failed;
}

template <class TileFn>
void TiledRenderer::State::draw_bands(int thread, std::size_t tiles, TileFn&& draw) {
    // Thread t draws the tiles of band t first, the same rows of the frame every time,
    // so they are still in its core's cache from the last frame; then it helps the
    // other bands, taking their tiles from their counters.
    for (std::size_t k = 0; k < bands.size(); ++k) {
        const std::size_t b = (static_cast<std::size_t>(thread) + k) % bands.size();
        std::atomic<std::size_t>& next = bands[b].next;
        for (std::size_t tile = next++; tile < band_begin(b + 1, tiles); tile = next++) {
            draw(tile);
        }
    }
}

void TiledRenderer::draw(const RenderTarget& target,
                         std::span<const FlatTriangle> triangles) {
    check_all(triangles);
    const TileGrid grid(target.width, target.height);
    const std::size_t chunks = chunk_count(triangles.size(), threads());
    state_->start(triangles.size(), chunks, grid.count);
    const std::span<Prepared> prepared(state_->prepared);
    const std::span<const ChunkBins> in_order(state_->chunks.data(), chunks);
    const DepthRunFn kernel = depth_run_kernel(chosen_simd()); // before any thread starts
    pool_.run([&](int thread) {
        // Binning, by every thread at once: the triangles in `chunks` contiguous slices
        // of the submission order, taken from a shared counter, each into its own bins.
        const bool binned = state_->bin_chunks(chunks, [&](std::size_t c) {
            bin_chunk(target, triangles, triangles.size() * c / chunks,
                      triangles.size() * (c + 1) / chunks, grid, prepared,
                      state_->chunks[c]);
        });
        if (!binned) {
            return;
        }
        // Drawing, a tile by one thread: the chunks' bins in chunk order, which is
        // submission order (a chunk's bins are in order, and the chunks follow each
        // other).
        state_->draw_bands(thread, grid.count, [&](std::size_t tile) {
            for (const ChunkBins& from : in_order) {
                draw_tile(target, triangles, prepared, grid, tile, from, kernel);
            }
        });
    });
}
//< draw-tiled

void draw_tiled(const RenderTarget& target, std::span<const FlatTriangle> triangles,
                int threads) {
    TiledRenderer(threads).draw(target, triangles);
}

} // namespace exactpixels
