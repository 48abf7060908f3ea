// Chapter 10 benchmark: the fast paths against the teaching path and against Mesa's
// llvmpipe (through OSMesa) drawing the same triangles into the same kind of frame.
//
// Run:   bench_ch10_fast [--benchmark_min_time=0.05] [--benchmark_out=f.csv
//                         --benchmark_out_format=csv]
// Names: MODE/VARIANT/AREA/THREADS, MODE flat (one colour into RGBA8) or depth (the same
//        with a 32-bit depth test, less), AREA 3, 15, 80, 1000 or 65536 px, VARIANT one
//        of
//          walk      chapter 2's pixel walk (traverse_pixels), the teaching path
//          blocks    chapter 2's 8x8 blocks (traverse_blocks_stepped), per-pixel output
//          runs      covered runs per row (row_runs.hpp), one triangle at a time
//          masks     8x8 masks, SSE2 lanes (block_masks.hpp), one triangle at a time
//          tiled     a kept TiledRenderer: 64x64 tiles, binning, runs; THREADS threads
//                    (its pool and bins made once for the whole run)
//          plain     a plain fill of the same number of pixels (no coverage test)
//          llvmpipe  OSMesa/llvmpipe, LP_NUM_THREADS rasterizer threads (default 1)
// Counters: tri_per_s and pix_per_s per second of process CPU time (all threads, so
// llvmpipe's rasterizer thread counts; a loaded machine does not distort it), except
// the wall-clock runs (the scaling target), with 1 and 2 threads:
//          wall/tiled/AREA/THREADS          the kept TiledRenderer
//          wall/tiled_per_call/AREA/THREADS draw_tiled, its threads started per call
//          wall/llvmpipe/AREA/THREADS       llvmpipe, THREADS = LP_NUM_THREADS: OSMesa
//                    reads it once, when the process makes its first context, so one
//                    process measures one count (full_run.sh runs LP_NUM_THREADS=2 too).
//
// One iteration is one frame: the same 1024 triangles of one area (triangle_sets.hpp,
// the set of chapter 2's benchmark) drawn into a 1024 x 1024 frame, each triangle with
// its own colour, a 24-bit id (so that a compared frame shows order as well as
// coverage), and its own depth plane. The measurement protocol of chapter 10
// (@sec:fast-protocol) holds on both sides:
//   the same input   both sides start every frame from the same vertex arrays: per
//                    vertex x, y in pixels and window depth z as floats (x and y exact
//                    multiples of 1/256 px) and RGBA8. Ours snaps each vertex, sets up
//                    its depth plane and its edges inside the frame (setup_triangle);
//                    llvmpipe gets the arrays in one glDrawArrays with an orthographic
//                    projection that puts vertex (x, y, z) on the project's pixel (x, y)
//                    at window depth z, flat shading, then glFinish.
//   the same state   with depth, the depth buffer is cleared at the start of every frame
//                    on both sides (std::fill, glClear), so every frame tests and writes.
//   fixed costs      AREA 0 is a frame with no triangle in it (for llvmpipe one triangle
//     apart          of zero area, so that glFinish still copies its frame to ours): the
//                    clear, llvmpipe's frame copy, the tiled renderer's thread wake-up.
//                    Readers of the run subtract it (net_rate in figures/ch10_speed.cpp).
//   checked after    after the timed loop each run compares its frame with the teaching
//     timing         path's frame of the same set (counters coverage_differ: pixels
//                    drawn in one frame only, colour_differ: pixels drawn in both with
//                    another id); a project variant that differs at all is an error.
// If OSMesa cannot make a context, the llvmpipe runs report an error and are skipped.
//
// Instruction counts (chapters/10-fast-pixels/callgrind.sh): `--once=MODE/VARIANT/AREA`
// draws the set once untimed, then once more inside ch10_draw_once, the function that
// valgrind --tool=callgrind --toggle-collect=ch10_draw_once counts; `--list` prints the
// names. Run it with LP_NUM_THREADS=0 so that llvmpipe rasterizes in the counted thread.
//
// Textured (issue 19's third target), only with `--textured`, so that the default run
// (data/ch10_fast.csv) is unchanged: names textured/VARIANT/AREA/1, VARIANT one of
//          teaching  draw_textured_triangle per triangle (chapter 3's exact mapper in
//                    double, nearest texel), the teaching path
//          runs      draw_textured_runs (textured_runs.hpp): covered runs, one divide
//                    per pixel, the same pixels (tested)
//          llvmpipe  the same triangles with clip-space w = the vertex's depth (so GL
//                    interpolates perspective-correctly), GL_NEAREST, GL_REPEAT,
//                    GL_REPLACE
// The set is the flat set's triangles, each vertex with a depth w in {1, 9/8, ..., 4}
// (few bits, so x w is an exact float) and uv = 0.75 (x, y) + (17, 5) texels on a
// 256 x 256 RGBA8 texture whose texel (i, j) is (i, j, i ^ j), repeated.
// `--compare-textured=AREA` prints one CSV row: pixels drawn, pixels whose coverage
// differs between llvmpipe and the teaching path, pixels covered by both whose texel
// differs, how many of those are a neighbouring texel, and pixels where the runs differ
// from the teaching path. `--once=textured/VARIANT/AREA` works as above (--list leaves
// the textured runs out: callgrind.sh counts the default run only).
//
// Vector instruction sets, only with `--simd` (chapters/10-fast-pixels/simd_run.sh):
// textured/runs_SET/AREA/1 for every SET this CPU has (fast/simd.hpp: portable, sse2,
// avx2, avx512, neon), the runs forced to it, and textured/llvmpipe/AREA/1, at AREA 0
// and 1000. `--once=textured/runs_SET/AREA` counts one. EXACTPIXELS_SIMD, if set, must
// name an instruction set this CPU has (else exit 2, one line).
#include "exactpixels/base/error.hpp"
#include "exactpixels/fast/simd.hpp"
#include "exactpixels/fast/textured_runs.hpp"
#include "exactpixels/fast/tiled_rasterizer.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"
#include "exactpixels/texture/texture_mapper.hpp"
#include "triangle_sets.hpp"

#include <GL/osmesa.h>
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

using namespace exactpixels;

namespace {

constexpr int frame_side = 1024;
constexpr int triangle_count = 1024;
constexpr int areas[] = {3, 15, 80, 1000, 65536};
/// The areas timed: each set, and 0 for the frame with nothing in it (its fixed cost).
constexpr int timed_areas[] = {0, 3, 15, 80, 1000, 65536};

constexpr int empty_set = 0; ///< the "area" of a frame with no triangle in it

/// The input both sides draw a set from: three vertices per triangle, each as x, y in
/// pixels and window depth z (floats; x and y exact multiples of 1/256 px, z in [0, 1])
/// and its triangle's colour (RGBA8, the same at all three vertices).
struct VertexArrays {
    std::vector<float> xyz;         ///< 3 floats per vertex
    std::vector<std::uint8_t> rgba; ///< 4 bytes per vertex
    std::size_t triangles() const { return xyz.size() / 9; }
};

/// Triangle n's colour: its 24-bit id n + 1 (0 is the background), red the low byte.
Rgba8 id_colour(std::size_t n) {
    const std::size_t id = n + 1;
    return rgba(static_cast<std::uint8_t>(id), static_cast<std::uint8_t>(id >> 8),
                static_cast<std::uint8_t>(id >> 16));
}

/// One area's set as vertex arrays (for empty_set, one triangle of zero area): the
/// triangles of chapter 2's benchmark, triangle n with id colour n + 1 and depths (z, 1 -
/// z, 1/2) at its three vertices, z = (n mod 97) / 97.
const VertexArrays& vertex_arrays(int area) {
    static std::map<int, VertexArrays> cache;
    auto [it, inserted] = cache.try_emplace(area);
    if (inserted && area == empty_set) { // one triangle of zero area: no pixel
        it->second.xyz.assign(9, 0.5f);
        it->second.rgba.assign(12, 255);
    } else if (inserted) {
        const bench::TriangleSet set =
            bench::make_triangles(area, triangle_count, frame_side);
        for (std::size_t n = 0; n < set.fixed.size(); ++n) {
            const float z = static_cast<float>(n % 97) / 97.0f; // any spread will do
            const float depths[3] = {z, 1.0f - z, 0.5f};
            const Rgba8 c = id_colour(n);
            for (std::size_t k = 0; k < 3; ++k) {
                const Point2 p = to_pixels(set.fixed[n][k]);
                it->second.xyz.insert(
                    it->second.xyz.end(),
                    {static_cast<float>(p.x), static_cast<float>(p.y), depths[k]});
                it->second.rgba.insert(it->second.rgba.end(), {c.r, c.g, c.b, 255});
            }
        }
    }
    return it->second;
}

/// Triangle n of `a` as the project draws it: its vertices snapped (1/256 px), its depth
/// plane (only `with_depth`: without a depth test neither side interpolates depth) and
/// its colour. The per-triangle setup ours does inside every frame.
FlatTriangle setup_triangle(const VertexArrays& a, std::size_t n, bool with_depth) {
    FlatTriangle t;
    std::array<float, 3> z{};
    for (std::size_t k = 0; k < 3; ++k) {
        const float* v = &a.xyz[9 * n + 3 * k];
        t.v[k] = snap_to_subpixel(Point2{v[0], v[1]});
        z[k] = v[2];
    }
    if (with_depth) {
        t.depth = depth_plane(t.v, z);
    }
    const std::uint8_t* c = &a.rgba[12 * n];
    t.colour = rgba(c[0], c[1], c[2]);
    return t;
}

/// Every triangle of `a` set up into `out` (its memory kept from frame to frame).
void setup_set(const VertexArrays& a, bool with_depth, std::vector<FlatTriangle>& out) {
    out.clear();
    for (std::size_t n = 0; n < a.triangles(); ++n) {
        out.push_back(setup_triangle(a, n, with_depth));
    }
}

/// One area's triangles set up, outside any timed loop (the textured set and the
/// reference frames start from them).
const std::vector<FlatTriangle>& triangles(int area) {
    static std::map<int, std::vector<FlatTriangle>> cache;
    auto [it, inserted] = cache.try_emplace(area);
    if (inserted) {
        setup_set(vertex_arrays(area), true, it->second);
    }
    return it->second;
}

/// One area's triangles textured: the same snapped corners, each with a depth w of few
/// bits, w = m / 8 for m in 8 .. 32, and uv = 0.75 (x, y) + (17, 5) texels.
const std::vector<std::array<TexturedVertex, 3>>& textured_triangles(int area) {
    static std::map<int, std::vector<std::array<TexturedVertex, 3>>> cache;
    auto [it, inserted] = cache.try_emplace(area);
    if (inserted) {
        std::mt19937_64 rng(static_cast<std::uint64_t>(area) + 19);
        for (const FlatTriangle& t : triangles(area)) {
            std::array<TexturedVertex, 3> tri{};
            for (std::size_t k = 0; k < 3; ++k) {
                const Point2 p = to_pixels(t.v[k]);
                const double w = static_cast<double>(8 + rng() % 25) / 8.0;
                tri[k] = {p, w, {0.75 * p.x + 17.0, 0.75 * p.y + 5.0}};
            }
            it->second.push_back(tri);
        }
    }
    return it->second;
}

constexpr int texture_side = 256;

/// The 256 x 256 texture: texel (i, j) is (i, j, i ^ j), every one its own colour.
const Texture& texture() {
    static const Texture t = [] {
        std::vector<Rgba8> texels;
        for (int j = 0; j < texture_side; ++j) {
            for (int i = 0; i < texture_side; ++i) {
                texels.push_back(rgba(static_cast<std::uint8_t>(i),
                                      static_cast<std::uint8_t>(j),
                                      static_cast<std::uint8_t>(i ^ j)));
            }
        }
        return Texture(texture_side, texture_side, std::move(texels));
    }();
    return t;
}

/// The teaching path's frame (draw_textured_triangle draws into a Framebuffer).
Framebuffer& teaching_frame() {
    static Framebuffer f(frame_side, frame_side, rgba(0, 0, 0, 0));
    return f;
}

/// The frame every project variant draws into, with its depth buffer.
struct Frame {
    std::vector<Rgba8> colour =
        std::vector<Rgba8>(std::size_t{frame_side} * frame_side, rgba(0, 0, 0));
    std::vector<float> depth =
        std::vector<float>(std::size_t{frame_side} * frame_side, 1.0f);
    RenderTarget target(bool with_depth) {
        return {colour.data(), with_depth ? depth.data() : nullptr, frame_side,
                frame_side};
    }
};

Frame& frame() {
    static Frame f;
    return f;
}

std::int64_t covered_pixels(int area) {
    static std::map<int, std::int64_t> cache;
    auto [it, inserted] = cache.try_emplace(area, 0);
    if (inserted) {
        for (const FlatTriangle& t : triangles(area)) {
            edge_rasterize_pixels(t.v, Viewport{frame_side, frame_side},
                                  [&](int, int) { ++it->second; });
        }
    }
    return it->second;
}

void report(benchmark::State& state, int area) {
    using benchmark::Counter;
    const double frames = static_cast<double>(state.iterations());
    const double count = area == empty_set ? 0.0 : triangle_count;
    state.counters["tri_per_s"] = Counter(frames * count, Counter::kIsRate);
    state.counters["pix_per_s"] =
        Counter(frames * static_cast<double>(covered_pixels(area)), Counter::kIsRate);
}

/// The background of every compared frame: no triangle has id 0.
constexpr Rgba8 background = rgba(0, 0, 0);

/// The teaching path's frame of one area's set, with depth or without, drawn once into
/// a cleared frame: what every run's frame must hold after its timed loop.
const std::vector<Rgba8>& reference_frame(int area, bool with_depth) {
    static std::map<std::pair<int, bool>, std::vector<Rgba8>> cache;
    auto [it, inserted] = cache.try_emplace({area, with_depth});
    if (inserted) {
        std::vector<Rgba8> colour(std::size_t{frame_side} * frame_side, background);
        std::vector<float> depth(colour.size(), 1.0f);
        draw_reference(
            {colour.data(), with_depth ? depth.data() : nullptr, frame_side, frame_side},
            triangles(area));
        it->second = std::move(colour);
    }
    return it->second;
}

/// Compares a run's frame (`pixel(i)` the colour of pixel i) with the teaching path's,
/// `want` (pixels equal to `background` are not drawn), and puts the counts in the run's
/// counters: coverage_differ, pixels drawn in one frame only; colour_differ, pixels
/// drawn in both in another colour (another triangle's id, or another texel). A project
/// variant (`exact`) must give the teaching path's pixels: any difference is an error.
template <typename Pixel>
void check_frame(benchmark::State& state, const std::vector<Rgba8>& want,
                 Rgba8 background, bool exact, Pixel pixel) {
    std::int64_t coverage = 0, colour = 0;
    for (std::size_t i = 0; i < want.size(); ++i) {
        const Rgba8 got = pixel(i);
        const bool drawn = got != background, wanted = want[i] != background;
        coverage += drawn != wanted;
        colour += drawn && wanted && got != want[i];
    }
    state.counters["coverage_differ"] = static_cast<double>(coverage);
    state.counters["colour_differ"] = static_cast<double>(colour);
    if (exact && coverage + colour != 0) {
        state.SkipWithError("the frame differs from the teaching path's");
    }
}

enum class Variant { walk, blocks, runs, masks, tiled, tiled_per_call, plain };

/// The kept tiled renderer with `threads` threads: made on first use, kept for the run.
TiledRenderer& renderer(int threads) {
    static std::map<int, std::unique_ptr<TiledRenderer>> kept;
    auto& r = kept[threads];
    if (!r) {
        r = std::make_unique<TiledRenderer>(threads);
    }
    return *r;
}

/// One frame of `variant` (threads: for tiled only): the depth buffer cleared when the
/// target has one, then the whole set of `area` from its vertex arrays, every triangle
/// snapped and set up in this frame.
void draw_set(Variant variant, const RenderTarget& target, int area, int threads) {
    const VertexArrays& a = vertex_arrays(area);
    const bool with_depth = target.depth != nullptr;
    static std::vector<FlatTriangle> set_up; // its memory kept from frame to frame
    if (target.depth != nullptr) {
        std::fill_n(target.depth, std::size_t{frame_side} * frame_side, 1.0f);
    }
    const Viewport vp{frame_side, frame_side};
    const int side = static_cast<int>(std::ceil(std::sqrt(area)));
    switch (variant) {
    case Variant::walk:
        setup_set(a, with_depth, set_up);
        draw_reference(target, set_up);
        break;
    case Variant::blocks:
        for (std::size_t n = 0; n < a.triangles(); ++n) {
            const FlatTriangle t = setup_triangle(a, n, with_depth);
            const EdgeSetup<FixedEdge> s = setup_edges(t.v);
            if (s.empty) {
                continue;
            }
            auto plot = [&](int x, int y) {
                const std::size_t i = static_cast<std::size_t>(y) * frame_side +
                                      static_cast<std::size_t>(x);
                if (target.depth != nullptr) {
                    const float z = t.depth.at(x, y);
                    if (!(z < target.depth[i])) {
                        return;
                    }
                    target.depth[i] = z;
                }
                target.colour[i] = t.colour;
            };
            traverse_blocks_stepped(s, pixel_bounds(t.v, vp), plot);
        }
        break;
    case Variant::runs:
        for (std::size_t n = 0; n < a.triangles(); ++n) {
            draw_runs(target, setup_triangle(a, n, with_depth));
        }
        break;
    case Variant::masks:
        for (std::size_t n = 0; n < a.triangles(); ++n) {
            draw_masks(target, setup_triangle(a, n, with_depth));
        }
        break;
    case Variant::tiled:
        setup_set(a, with_depth, set_up);
        renderer(threads).draw(target, set_up);
        break;
    case Variant::tiled_per_call:
        setup_set(a, with_depth, set_up);
        draw_tiled(target, set_up, threads);
        break;
    case Variant::plain: // `area` pixels as a near-square rectangle per triangle
        for (std::size_t n = 0; n < a.triangles(); ++n) {
            const std::uint8_t* c = &a.rgba[12 * n];
            const int x0 = static_cast<int>(a.xyz[9 * n]) % (frame_side - side);
            const int y0 = static_cast<int>(a.xyz[9 * n + 1]) % (frame_side - side);
            for (int left = area, y = y0; left > 0; left -= side, ++y) {
                Rgba8* row = target.colour + static_cast<std::size_t>(y) * frame_side;
                fill_run(row + x0, std::min(left, side), rgba(c[0], c[1], c[2]));
            }
        }
        break;
    }
}

void project(benchmark::State& state, Variant variant, bool with_depth) {
    const int area = static_cast<int>(state.range(0));
    const int threads = static_cast<int>(state.range(1));
    Frame& f = frame();
    std::fill(f.colour.begin(), f.colour.end(), background);
    for (auto _ : state) {
        draw_set(variant, f.target(with_depth), area, threads);
        benchmark::ClobberMemory();
    }
    report(state, area);
    // A plain fill is no rasterizer: its counts (other pixels than the set's) are
    // reported, as every run's are, and must not be zero.
    check_frame(state, reference_frame(area, with_depth), background,
                variant != Variant::plain, [&](std::size_t i) { return f.colour[i]; });
}

enum class TexturedVariant { teaching, runs };

/// Draws the textured set of `area` once with `variant` (the runs in the instruction set
/// `simd`).
void draw_textured_set(TexturedVariant variant, int area,
                       SimdVariant simd = chosen_simd()) {
    const auto& tris = textured_triangles(area);
    switch (variant) {
    case TexturedVariant::teaching: {
        MapperSettings settings; // exact, double, rule 1, repeat
        for (const auto& t : tris) {
            draw_textured_triangle(teaching_frame(), t, texture(), settings);
        }
        break;
    }
    case TexturedVariant::runs:
        draw_textured_runs(frame().target(false), tris, texture(), Wrap::repeat, simd);
        break;
    }
}

/// The background of the textured frames: transparent, where every texel is opaque.
constexpr Rgba8 transparent = rgba(0, 0, 0, 0);

/// The teaching path's frame of one area's textured set, drawn once into a cleared
/// frame: what every textured run's frame must hold after its timed loop.
const std::vector<Rgba8>& textured_reference(int area) {
    static std::map<int, std::vector<Rgba8>> cache;
    auto [it, inserted] = cache.try_emplace(area);
    if (inserted) {
        Framebuffer f(frame_side, frame_side, transparent);
        for (const auto& t : textured_triangles(area)) {
            draw_textured_triangle(f, t, texture(), MapperSettings{});
        }
        it->second = f.pixels();
    }
    return it->second;
}

void project_textured(benchmark::State& state, TexturedVariant variant,
                      SimdVariant simd = chosen_simd()) {
    const int area = static_cast<int>(state.range(0));
    teaching_frame() = Framebuffer(frame_side, frame_side, transparent);
    std::fill(frame().colour.begin(), frame().colour.end(), transparent);
    for (auto _ : state) {
        draw_textured_set(variant, area, simd);
        benchmark::ClobberMemory();
    }
    report(state, area);
    const std::vector<Rgba8>& drawn =
        variant == TexturedVariant::teaching ? teaching_frame().pixels() : frame().colour;
    check_frame(state, textured_reference(area), transparent, true,
                [&](std::size_t i) { return drawn[i]; });
}

/// llvmpipe through OSMesa: one context for the whole run, made on first use.
struct Peer {
    OSMesaContext context = nullptr;
    std::vector<std::uint8_t> pixels =
        std::vector<std::uint8_t>(std::size_t{frame_side} * frame_side * 4, 0);
    std::string problem; ///< why there is no context, if there is none
    GLuint texture = 0;  ///< texture() as a GL texture, made on first textured use
};

Peer& peer() {
    static Peer p = [] {
        Peer q;
        setenv("LP_NUM_THREADS", "1", 0); // one rasterizer thread unless the caller says
        q.context = OSMesaCreateContextExt(OSMESA_RGBA, 32, 0, 0, nullptr);
        if (q.context == nullptr) {
            q.problem = "OSMesaCreateContextExt failed: no llvmpipe";
            return q;
        }
        if (!OSMesaMakeCurrent(q.context, q.pixels.data(), GL_UNSIGNED_BYTE, frame_side,
                               frame_side)) {
            q.problem = "OSMesaMakeCurrent failed";
            return q;
        }
        OSMesaPixelStore(OSMESA_Y_UP, 0); // row 0 of the buffer is the top row
        glViewport(0, 0, frame_side, frame_side);
        glMatrixMode(GL_PROJECTION);
        glLoadIdentity();
        // (x, y, z) to pixel (x, y), y down, as ours, at window depth z: near 0 and
        // far -1 make z_ndc = 2 z - 1, so (z_ndc + 1) / 2 = z.
        glOrtho(0, frame_side, frame_side, 0, 0, -1);
        glMatrixMode(GL_MODELVIEW);
        glLoadIdentity();
        glShadeModel(GL_FLAT);
        glDisable(GL_DITHER);
        glClearColor(0, 0, 0, 1);
        glClearDepth(1.0);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glEnableClientState(GL_VERTEX_ARRAY);
        glEnableClientState(GL_COLOR_ARRAY);
        return q;
    }();
    return p;
}

/// Sets llvmpipe up to draw the set of `area` (depth test or not) from its vertex
/// arrays; returns the vertex count for glDrawArrays.
GLsizei prepare_peer(int area, bool with_depth) {
    const VertexArrays& a = vertex_arrays(area);
    glDisable(GL_TEXTURE_2D); // as a textured run may have left it
    glDisableClientState(GL_TEXTURE_COORD_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    if (with_depth) {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
    } else {
        glDisable(GL_DEPTH_TEST);
    }
    glVertexPointer(3, GL_FLOAT, 0, a.xyz.data());
    glColorPointer(4, GL_UNSIGNED_BYTE, 0, a.rgba.data());
    return static_cast<GLsizei>(a.xyz.size() / 3);
}

/// The textured set's arrays: clip-space (x w, y w, 0, w) through the same orthographic
/// projection (its last row is (0, 0, 0, 1), so the divide by w gives back (x, y)), and
/// texture coordinates (u, v) / 256, both exact in float.
struct TexturedArrays {
    std::vector<float> xyzw; ///< 4 floats per vertex
    std::vector<float> st;   ///< 2 floats per vertex
};

const TexturedArrays& textured_arrays(int area) {
    static std::map<int, TexturedArrays> cache;
    auto [it, inserted] = cache.try_emplace(area);
    if (inserted) {
        for (const auto& tri : textured_triangles(area)) {
            for (const TexturedVertex& v : tri) {
                const double w = v.w;
                it->second.xyzw.insert(it->second.xyzw.end(),
                                       {static_cast<float>(v.position.x * w),
                                        static_cast<float>(v.position.y * w), 0.0f,
                                        static_cast<float>(w)});
                it->second.st.insert(it->second.st.end(),
                                     {static_cast<float>(v.uv.x / texture_side),
                                      static_cast<float>(v.uv.y / texture_side)});
            }
        }
    }
    return it->second;
}

/// Sets llvmpipe up to draw the textured set of `area`; returns the vertex count.
GLsizei prepare_textured_peer(int area) {
    Peer& p = peer();
    if (p.texture == 0) {
        glGenTextures(1, &p.texture);
        glBindTexture(GL_TEXTURE_2D, p.texture);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, texture_side, texture_side, 0, GL_RGBA,
                     GL_UNSIGNED_BYTE, texture().texels().data());
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
        glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
        glHint(GL_PERSPECTIVE_CORRECTION_HINT, GL_NICEST);
    }
    const TexturedArrays& a = textured_arrays(area);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, p.texture);
    glDisableClientState(GL_COLOR_ARRAY);
    glEnableClientState(GL_TEXTURE_COORD_ARRAY);
    glVertexPointer(4, GL_FLOAT, 0, a.xyzw.data());
    glTexCoordPointer(2, GL_FLOAT, 0, a.st.data());
    return static_cast<GLsizei>(a.xyzw.size() / 4);
}

/// One llvmpipe frame of `vertices`: the depth buffer cleared when the depth test is
/// on, the draw, and glFinish, which copies the frame into Peer::pixels.
void peer_frame(GLsizei vertices, bool with_depth) {
    if (with_depth) {
        glClear(GL_DEPTH_BUFFER_BIT);
    }
    glDrawArrays(GL_TRIANGLES, 0, vertices);
    glFinish();
}

/// Peer::pixels' pixel i as an Rgba8.
Rgba8 peer_pixel(std::size_t i) {
    const std::uint8_t* p = &peer().pixels[4 * i];
    return rgba(p[0], p[1], p[2], p[3]);
}

/// Times llvmpipe drawing frames of the `vertices` prepared for `area` into a frame
/// cleared to `clear` (one uncounted frame first, which compiles its code for this
/// state), then compares its frame with `want`, the teaching path's.
void time_peer(benchmark::State& state, int area, GLsizei vertices, bool with_depth,
               Rgba8 clear, const std::vector<Rgba8>& want) {
    glClearColor(clear.r / 255.0f, clear.g / 255.0f, clear.b / 255.0f, clear.a / 255.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    peer_frame(vertices, with_depth); // compiles llvmpipe's code for this state
    for (auto _ : state) {
        peer_frame(vertices, with_depth);
    }
    if (glGetError() != GL_NO_ERROR) {
        state.SkipWithError("OpenGL reported an error");
        return;
    }
    report(state, area);
    check_frame(state, want, clear, false, peer_pixel);
}

void llvmpipe_textured(benchmark::State& state) {
    const int area = static_cast<int>(state.range(0));
    Peer& p = peer();
    if (p.context == nullptr) {
        state.SkipWithError(p.problem.c_str());
        return;
    }
    time_peer(state, area, prepare_textured_peer(area), false, transparent,
              textured_reference(area));
}

void llvmpipe(benchmark::State& state, bool with_depth) {
    const int area = static_cast<int>(state.range(0));
    Peer& p = peer();
    if (p.context == nullptr) {
        state.SkipWithError(p.problem.c_str());
        return;
    }
    time_peer(state, area, prepare_peer(area, with_depth), with_depth, background,
              reference_frame(area, with_depth));
}

/// The one drawing callgrind counts (see the top of the file).
extern "C" __attribute__((noinline)) void
ch10_draw_once(const std::function<void()>& draw) {
    draw();
}

/// --compare-textured=AREA: draws the textured set of AREA into cleared frames (alpha 0;
/// every texel has alpha 255) with the teaching path, the runs and llvmpipe, and prints
/// one CSV row: textured/AREA, pixels the teaching path drew, pixels whose coverage
/// differs in llvmpipe's frame, pixels both drew with another texel, how many of those
/// are a neighbouring texel (i and j each within one, modulo 256), and pixels where the
/// runs' frame differs from the teaching path's.
int compare_textured(int area) {
    if (std::find(std::begin(areas), std::end(areas), area) == std::end(areas) ||
        peer().context == nullptr) {
        std::fprintf(stderr, "bench_ch10_fast: cannot compare area %d\n", area);
        return 2;
    }
    teaching_frame() = Framebuffer(frame_side, frame_side, rgba(0, 0, 0, 0));
    std::fill(frame().colour.begin(), frame().colour.end(), rgba(0, 0, 0, 0));
    draw_textured_set(TexturedVariant::teaching, area);
    draw_textured_set(TexturedVariant::runs, area);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    glDrawArrays(GL_TRIANGLES, 0, prepare_textured_peer(area));
    glFinish();
    glClearColor(0, 0, 0, 1);
    const auto& gl = peer().pixels;
    const auto& ours = teaching_frame().pixels();
    std::int64_t drawn = 0, coverage = 0, texel = 0, neighbour = 0, runs = 0;
    const auto near = [](int a, int b) { return ((a - b + 1) & 255) <= 2; };
    for (std::size_t i = 0; i < ours.size(); ++i) {
        const Rgba8 o = ours[i];
        const bool we = o.a == 255, they = gl[4 * i + 3] == 255;
        drawn += we;
        runs += frame().colour[i] != o;
        coverage += we != they;
        if (we && they && (o.r != gl[4 * i] || o.g != gl[4 * i + 1])) {
            ++texel;
            neighbour += near(o.r, gl[4 * i]) && near(o.g, gl[4 * i + 1]);
        }
    }
    std::printf("textured/%d,%lld,%lld,%lld,%lld,%lld\n", area,
                static_cast<long long>(drawn), static_cast<long long>(coverage),
                static_cast<long long>(texel), static_cast<long long>(neighbour),
                static_cast<long long>(runs));
    return 0;
}

/// --once=MODE/VARIANT/AREA: draws the set once, then once more inside ch10_draw_once.
/// Returns the exit code (2 for a name it does not know).
int draw_once(const std::string& name) {
    const auto first = name.find('/'), second = name.rfind('/');
    if (first == std::string::npos || second == first) {
        std::fprintf(stderr, "bench_ch10_fast: --once=%s is not MODE/VARIANT/AREA\n",
                     name.c_str());
        return 2;
    }
    const std::string mode = name.substr(0, first);
    const std::string variant = name.substr(first + 1, second - first - 1);
    const int area = std::atoi(name.c_str() + second + 1);
    const bool with_depth = mode == "depth";
    const std::map<std::string, Variant> variants{
        {"walk", Variant::walk},   {"blocks", Variant::blocks},
        {"runs", Variant::runs},   {"masks", Variant::masks},
        {"tiled", Variant::tiled}, {"plain", Variant::plain}};
    std::function<void()> draw;
    if (mode == "textured") {
        if (variant == "llvmpipe" && peer().context != nullptr) {
            const GLsizei vertices = prepare_textured_peer(area);
            draw = [vertices] { peer_frame(vertices, false); };
        } else if (variant.rfind("runs_", 0) == 0) { // runs_SET: forced, as --simd
            const SimdVariant simd = simd_from_setting(variant.c_str() + 5);
            draw = [=] { draw_textured_set(TexturedVariant::runs, area, simd); };
        } else if (variant == "teaching" || variant == "runs") {
            draw = [=] {
                draw_textured_set(variant == "runs" ? TexturedVariant::runs
                                                    : TexturedVariant::teaching,
                                  area);
            };
        }
    } else if (variant == "llvmpipe") {
        if (peer().context == nullptr) {
            std::fprintf(stderr, "bench_ch10_fast: %s\n", peer().problem.c_str());
            return 2;
        }
        const GLsizei vertices = prepare_peer(area, with_depth);
        draw = [vertices, with_depth] { peer_frame(vertices, with_depth); };
    } else if (variants.count(variant) != 0) {
        draw = [=, v = variants.at(variant)] {
            draw_set(v, frame().target(with_depth), area, 1);
        };
    }
    if (!draw || (mode != "flat" && mode != "depth" && mode != "textured") ||
        std::find(std::begin(timed_areas), std::end(timed_areas), area) ==
            std::end(timed_areas)) {
        std::fprintf(stderr, "bench_ch10_fast: unknown run %s\n", name.c_str());
        return 2;
    }
    draw(); // the first frame compiles llvmpipe's code
    ch10_draw_once(draw);
    return 0;
}

/// llvmpipe's run name: "llvmpipe", or "llvmpipe_CAPS" when GALLIUM_OVERRIDE_CPU_CAPS
/// limits the instructions it may generate to CAPS (Mesa reads it once per process, so
/// full_run.sh measures llvmpipe restricted to SSE4.1, 128-bit vectors, in a process of
/// its own, beside its default: the difference is what its wider vectors give it).
std::string peer_name() {
    const char* caps = std::getenv("GALLIUM_OVERRIDE_CPU_CAPS");
    return caps != nullptr ? std::string("llvmpipe_") + caps : std::string("llvmpipe");
}

void register_all() {
    const std::pair<const char*, Variant> variants[] = {
        {"walk", Variant::walk},   {"blocks", Variant::blocks},
        {"runs", Variant::runs},   {"masks", Variant::masks},
        {"tiled", Variant::tiled}, {"plain", Variant::plain}};
    const char* lp = std::getenv("LP_NUM_THREADS");
    const int peer_threads = lp != nullptr ? std::atoi(lp) : 1;
    // Process CPU time (every thread of the process, llvmpipe's too): one core's work,
    // whatever else the machine runs.
    for (const bool depth : {false, true}) {
        const std::string mode = depth ? "depth/" : "flat/";
        for (const auto& [name, variant] : variants) {
            if (depth && variant == Variant::plain) {
                continue;
            }
            for (const int area : timed_areas) {
                benchmark::RegisterBenchmark(
                    (mode + name).c_str(),
                    [variant, depth](benchmark::State& s) { project(s, variant, depth); })
                    ->Args({area, 1})
                    ->MeasureProcessCPUTime();
            }
        }
        for (const int area : timed_areas) {
            benchmark::RegisterBenchmark(
                (mode + peer_name()).c_str(),
                [depth](benchmark::State& s) { llvmpipe(s, depth); })
                ->Args({area, peer_threads})
                ->MeasureProcessCPUTime();
        }
    }
    // Threads: wall-clock time of the tiled renderer with 1 and 2 threads, kept and
    // started per call, and of llvmpipe with this process's LP_NUM_THREADS.
    for (const int area : timed_areas) {
        for (const int threads : {1, 2}) {
            for (const auto& [name, variant] :
                 {std::pair{"wall/tiled", Variant::tiled},
                  std::pair{"wall/tiled_per_call", Variant::tiled_per_call}}) {
                benchmark::RegisterBenchmark(name,
                                             [variant = variant](benchmark::State& s) {
                                                 project(s, variant, false);
                                             })
                    ->Args({area, threads})
                    ->UseRealTime();
            }
        }
        benchmark::RegisterBenchmark("wall/llvmpipe",
                                     [](benchmark::State& s) { llvmpipe(s, false); })
            ->Args({area, peer_threads})
            ->UseRealTime();
    }
}

/// The textured benchmarks (--textured), one core each, process CPU time.
void register_textured() {
    for (const auto& [name, variant] : {std::pair{"teaching", TexturedVariant::teaching},
                                        std::pair{"runs", TexturedVariant::runs}}) {
        for (const int area : timed_areas) {
            benchmark::RegisterBenchmark((std::string("textured/") + name).c_str(),
                                         [variant = variant](benchmark::State& s) {
                                             project_textured(s, variant);
                                         })
                ->Args({area, 1})
                ->MeasureProcessCPUTime();
        }
    }
    const char* lp = std::getenv("LP_NUM_THREADS");
    const int peer_threads = lp != nullptr ? std::atoi(lp) : 1;
    for (const int area : timed_areas) {
        benchmark::RegisterBenchmark("textured/llvmpipe", llvmpipe_textured)
            ->Args({area, peer_threads})
            ->MeasureProcessCPUTime();
    }
}

/// The vector instruction sets (--simd), textured 1000 px triangles and the empty frame:
/// the runs in every instruction set this CPU has, named textured/runs_SET, and
/// llvmpipe, one core each, process CPU time.
void register_simd() {
    for (const SimdVariant v : available_simd()) {
        for (const int area : {0, 1000}) {
            benchmark::RegisterBenchmark(
                (std::string("textured/runs_") + std::string(simd_name(v))).c_str(),
                [v](benchmark::State& s) { project_textured(s, TexturedVariant::runs, v); })
                ->Args({area, 1})
                ->MeasureProcessCPUTime();
        }
    }
    const char* lp = std::getenv("LP_NUM_THREADS");
    const int peer_threads = lp != nullptr ? std::atoi(lp) : 1;
    for (const int area : {0, 1000}) {
        benchmark::RegisterBenchmark("textured/llvmpipe", llvmpipe_textured)
            ->Args({area, peer_threads})
            ->MeasureProcessCPUTime();
    }
}

} // namespace

int main(int argc, char** argv) {
    try { // EXACTPIXELS_SIMD must name an instruction set this CPU has
        (void)chosen_simd();
    } catch (const Error& error) {
        std::fprintf(stderr, "bench_ch10_fast: %s\n", error.what());
        return 2;
    }
    bool textured = false, simd = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--textured" || arg == "--simd") { // taken out of argv before Google
            (arg == "--simd" ? simd : textured) = true; // Benchmark reads it
            for (int j = i; j + 1 < argc; ++j) {
                argv[j] = argv[j + 1];
            }
            --argc;
            --i;
            continue;
        }
        if (arg == "--list") { // the runs --once accepts, with their triangle count
            for (const char* mode : {"flat", "depth"}) {
                for (const char* v :
                     {"walk", "blocks", "runs", "masks", "tiled", "llvmpipe"}) {
                    for (const int area : timed_areas) {
                        std::printf("%s/%s/%d %d\n", mode, v, area,
                                    area == empty_set ? 0 : triangle_count);
                    }
                }
            }
            return 0;
        }
        if (arg.rfind("--compare-textured=", 0) == 0) {
            return compare_textured(std::atoi(arg.c_str() + 19));
        }
        if (arg.rfind("--once=", 0) == 0) {
            return draw_once(arg.substr(7));
        }
    }
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
        return 1;
    }
    if (simd) {
        register_simd();
    } else if (textured) {
        register_textured();
    } else {
        register_all();
    }
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
}
