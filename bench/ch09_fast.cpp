// Chapter 9 benchmark: the fast paths against the teaching path and against Mesa's
// llvmpipe (through OSMesa) drawing the same triangles into the same kind of frame.
//
// Run:   bench_ch09_fast [--benchmark_min_time=0.05] [--benchmark_out=f.csv
//                         --benchmark_out_format=csv]
// Names: MODE/VARIANT/AREA/THREADS, MODE flat (one colour into RGBA8) or depth (the same
//        with a 32-bit depth test, less), AREA 3, 15, 80, 1000 or 65536 px, VARIANT one
//        of
//          walk      chapter 2's pixel walk (traverse_pixels), the teaching path
//          blocks    chapter 2's 8x8 blocks (traverse_blocks_fast), per-pixel output
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
// One iteration draws a whole set: the same 1024 triangles of one area
// (triangle_sets.hpp, the set of chapter 2's benchmark) into a 1024 x 1024 frame, each
// triangle with its own colour and depth plane. llvmpipe gets them in one glDrawArrays
// (float vertices, exact for 1/256 px below 2^15 px) with an orthographic projection that
// puts vertex (x, y) on the project's pixel (x, y), flat shading, then glFinish. The
// depth buffer is cleared once: after the first pass every fragment is tested and fails
// (the buffer already holds the nearest depth), the same work on both sides.
// If OSMesa cannot make a context, the llvmpipe runs report an error and are skipped.
//
// Instruction counts (chapters/09-fast-pixels/callgrind.sh): `--once=MODE/VARIANT/AREA`
// draws the set once untimed, then once more inside ch09_draw_once, the function that
// valgrind --tool=callgrind --toggle-collect=ch09_draw_once counts; `--list` prints the
// names. Run it with LP_NUM_THREADS=0 so that llvmpipe rasterizes in the counted thread.
// `--compare=AREA` checks that both sides draw the same pixels (see compare()).
//
// Textured (issue 19's third target), only with `--textured`, so that the default run
// (data/ch09_fast.csv) is unchanged: names textured/VARIANT/AREA/1, VARIANT one of
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
#include "exactpixels/raster/edge_rasterizer.hpp"
#include "exactpixels/raster/tiled_rasterizer.hpp"
#include "exactpixels/texture/texture_mapper.hpp"
#include "exactpixels/texture/textured_runs.hpp"
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

/// One area's triangles as the project draws them: snapped, coloured, with depth.
const std::vector<FlatTriangle>& triangles(int area) {
    static std::map<int, std::vector<FlatTriangle>> cache;
    auto [it, inserted] = cache.try_emplace(area);
    if (inserted) {
        const bench::TriangleSet set =
            bench::make_triangles(area, triangle_count, frame_side);
        for (std::size_t n = 0; n < set.fixed.size(); ++n) {
            const auto c = static_cast<std::uint8_t>(n);
            const float z = static_cast<float>(n % 97) / 97.0f; // any spread will do
            it->second.push_back({set.fixed[n],
                                  depth_plane(set.fixed[n], {z, 1.0f - z, 0.5f}),
                                  rgba(c, static_cast<std::uint8_t>(255 - c), 128)});
        }
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
    const double sets = static_cast<double>(state.iterations());
    state.counters["tri_per_s"] = Counter(sets * triangle_count, Counter::kIsRate);
    state.counters["pix_per_s"] =
        Counter(sets * static_cast<double>(covered_pixels(area)), Counter::kIsRate);
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

/// Draws the whole set of `area` once with `variant` (threads: for tiled only).
void draw_set(Variant variant, bool with_depth, int area, int threads) {
    const auto& tris = triangles(area);
    const RenderTarget target = frame().target(with_depth);
    const Viewport vp{frame_side, frame_side};
    const int side = static_cast<int>(std::ceil(std::sqrt(area)));
    switch (variant) {
    case Variant::walk:
        draw_reference(target, tris);
        break;
    case Variant::blocks:
        for (const FlatTriangle& t : tris) {
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
            traverse_blocks_fast(s, pixel_bounds(t.v, vp), plot);
        }
        break;
    case Variant::runs:
        for (const FlatTriangle& t : tris) {
            draw_runs(target, t);
        }
        break;
    case Variant::masks:
        for (const FlatTriangle& t : tris) {
            draw_masks(target, t);
        }
        break;
    case Variant::tiled:
        renderer(threads).draw(target, tris);
        break;
    case Variant::tiled_per_call:
        draw_tiled(target, tris, threads);
        break;
    case Variant::plain: // `area` pixels as a near-square rectangle per triangle
        for (const FlatTriangle& t : tris) {
            const int x0 = static_cast<int>(t.v[0].x >> 8) % (frame_side - side);
            const int y0 = static_cast<int>(t.v[0].y >> 8) % (frame_side - side);
            for (int left = area, y = y0; left > 0; left -= side, ++y) {
                Rgba8* row = target.colour + static_cast<std::size_t>(y) * frame_side;
                fill_run(row + x0, std::min(left, side), t.colour);
            }
        }
        break;
    }
}

void project(benchmark::State& state, Variant variant, bool with_depth) {
    const int area = static_cast<int>(state.range(0));
    const int threads = static_cast<int>(state.range(1));
    std::fill(frame().depth.begin(), frame().depth.end(), 1.0f); // as glClear does
    for (auto _ : state) {
        draw_set(variant, with_depth, area, threads);
        benchmark::ClobberMemory();
    }
    report(state, area);
}

enum class TexturedVariant { teaching, runs };

/// Draws the textured set of `area` once with `variant`.
void draw_textured_set(TexturedVariant variant, int area) {
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
        draw_textured_runs(frame().target(false), tris, texture(), Wrap::repeat);
        break;
    }
}

void project_textured(benchmark::State& state, TexturedVariant variant) {
    const int area = static_cast<int>(state.range(0));
    for (auto _ : state) {
        draw_textured_set(variant, area);
        benchmark::ClobberMemory();
    }
    report(state, area);
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
        glOrtho(0, frame_side, frame_side, 0, -1, 1); // (x, y) px, y down, as ours
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

/// The vertex and colour arrays of one area's set, for glDrawArrays.
struct PeerArrays {
    std::vector<float> xyz;         ///< 3 floats per vertex
    std::vector<std::uint8_t> rgba; ///< 4 bytes per vertex (flat: the last one counts)
};

const PeerArrays& peer_arrays(int area) {
    static std::map<int, PeerArrays> cache;
    auto [it, inserted] = cache.try_emplace(area);
    if (inserted) {
        for (const FlatTriangle& t : triangles(area)) {
            for (const FixedPoint2& p : t.v) {
                const Point2 q = to_pixels(p);
                // Window depth (1 - z_ndc) / 2 with glOrtho(.., -1, 1): z_ndc = -zv.
                const float z = t.depth.at(static_cast<int>(q.x), static_cast<int>(q.y));
                it->second.xyz.insert(it->second.xyz.end(),
                                      {static_cast<float>(q.x), static_cast<float>(q.y),
                                       1.0f - 2.0f * std::clamp(z, 0.0f, 1.0f)});
                it->second.rgba.insert(it->second.rgba.end(),
                                       {t.colour.r, t.colour.g, t.colour.b, 255});
            }
        }
    }
    return it->second;
}

/// Sets llvmpipe up to draw the set of `area` (depth test or not); returns the vertex
/// count for glDrawArrays.
GLsizei prepare_peer(int area, bool with_depth) {
    const PeerArrays& a = peer_arrays(area);
    glDisable(GL_TEXTURE_2D); // as a textured run may have left it
    glDisableClientState(GL_TEXTURE_COORD_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    if (with_depth) {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glClear(GL_DEPTH_BUFFER_BIT);
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

/// Times llvmpipe drawing the `vertices` prepared for `area` (one uncounted drawing
/// first, which compiles its code for this state).
void time_peer(benchmark::State& state, int area, GLsizei vertices) {
    glDrawArrays(GL_TRIANGLES, 0, vertices); // compiles llvmpipe's code for this state
    glFinish();
    for (auto _ : state) {
        glDrawArrays(GL_TRIANGLES, 0, vertices);
        glFinish();
    }
    if (glGetError() != GL_NO_ERROR) {
        state.SkipWithError("OpenGL reported an error");
    }
    report(state, area);
}

void llvmpipe_textured(benchmark::State& state) {
    const int area = static_cast<int>(state.range(0));
    Peer& p = peer();
    if (p.context == nullptr) {
        state.SkipWithError(p.problem.c_str());
        return;
    }
    time_peer(state, area, prepare_textured_peer(area));
}

void llvmpipe(benchmark::State& state, bool with_depth) {
    const int area = static_cast<int>(state.range(0));
    Peer& p = peer();
    if (p.context == nullptr) {
        state.SkipWithError(p.problem.c_str());
        return;
    }
    time_peer(state, area, prepare_peer(area, with_depth));
}

/// The one drawing callgrind counts (see the top of the file).
extern "C" __attribute__((noinline)) void
ch09_draw_once(const std::function<void()>& draw) {
    draw();
}

/// --compare=AREA: draws the flat set of AREA with the teaching path and with llvmpipe
/// into cleared frames and prints how many pixels differ (the same work on both sides
/// means nearly the same pixels: only centres exactly on an edge may go either way).
int compare(int area) {
    if (std::find(std::begin(areas), std::end(areas), area) == std::end(areas) ||
        peer().context == nullptr) {
        std::fprintf(stderr, "bench_ch09_fast: cannot compare area %d\n", area);
        return 2;
    }
    std::fill(frame().colour.begin(), frame().colour.end(), rgba(0, 0, 0));
    draw_reference(frame().target(false), triangles(area));
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDrawArrays(GL_TRIANGLES, 0, prepare_peer(area, false));
    glFinish();
    std::int64_t differ = 0, drawn = 0;
    const auto& gl = peer().pixels;
    for (std::size_t i = 0; i < frame().colour.size(); ++i) {
        const Rgba8 ours = frame().colour[i];
        drawn += ours != rgba(0, 0, 0);
        differ +=
            ours.r != gl[4 * i] || ours.g != gl[4 * i + 1] || ours.b != gl[4 * i + 2];
    }
    std::printf(
        "area %d: %lld pixels drawn by the teaching path, %lld differ in llvmpipe's "
        "frame\n",
        area, static_cast<long long>(drawn), static_cast<long long>(differ));
    return 0;
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
        std::fprintf(stderr, "bench_ch09_fast: cannot compare area %d\n", area);
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

/// --once=MODE/VARIANT/AREA: draws the set once, then once more inside ch09_draw_once.
/// Returns the exit code (2 for a name it does not know).
int draw_once(const std::string& name) {
    const auto first = name.find('/'), second = name.rfind('/');
    if (first == std::string::npos || second == first) {
        std::fprintf(stderr, "bench_ch09_fast: --once=%s is not MODE/VARIANT/AREA\n",
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
            draw = [vertices] {
                glDrawArrays(GL_TRIANGLES, 0, vertices);
                glFinish();
            };
        } else if (variant == "teaching" || variant == "runs") {
            draw = [=] {
                draw_textured_set(variant == "runs" ? TexturedVariant::runs
                                                    : TexturedVariant::teaching,
                                  area);
            };
        }
    } else if (variant == "llvmpipe") {
        if (peer().context == nullptr) {
            std::fprintf(stderr, "bench_ch09_fast: %s\n", peer().problem.c_str());
            return 2;
        }
        const GLsizei vertices = prepare_peer(area, with_depth);
        draw = [vertices] {
            glDrawArrays(GL_TRIANGLES, 0, vertices);
            glFinish();
        };
    } else if (variants.count(variant) != 0) {
        draw = [=, v = variants.at(variant)] { draw_set(v, with_depth, area, 1); };
    }
    if (!draw || (mode != "flat" && mode != "depth" && mode != "textured") ||
        std::find(std::begin(areas), std::end(areas), area) == std::end(areas)) {
        std::fprintf(stderr, "bench_ch09_fast: unknown run %s\n", name.c_str());
        return 2;
    }
    draw(); // the first pass fills the depth buffer and compiles llvmpipe's code
    ch09_draw_once(draw);
    return 0;
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
            for (const int area : areas) {
                benchmark::RegisterBenchmark(
                    (mode + name).c_str(),
                    [variant, depth](benchmark::State& s) { project(s, variant, depth); })
                    ->Args({area, 1})
                    ->MeasureProcessCPUTime();
            }
        }
        for (const int area : areas) {
            benchmark::RegisterBenchmark(
                (mode + "llvmpipe").c_str(),
                [depth](benchmark::State& s) { llvmpipe(s, depth); })
                ->Args({area, peer_threads})
                ->MeasureProcessCPUTime();
        }
    }
    // Threads: wall-clock time of the tiled renderer with 1 and 2 threads, kept and
    // started per call, and of llvmpipe with this process's LP_NUM_THREADS.
    for (const int area : areas) {
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
        for (const int area : areas) {
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
    for (const int area : areas) {
        benchmark::RegisterBenchmark("textured/llvmpipe", llvmpipe_textured)
            ->Args({area, peer_threads})
            ->MeasureProcessCPUTime();
    }
}

} // namespace

int main(int argc, char** argv) {
    bool textured = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--textured") { // taken out of argv before Google Benchmark reads it
            textured = true;
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
                    for (const int area : areas) {
                        std::printf("%s/%s/%d %d\n", mode, v, area, triangle_count);
                    }
                }
            }
            return 0;
        }
        if (arg.rfind("--compare-textured=", 0) == 0) {
            return compare_textured(std::atoi(arg.c_str() + 19));
        }
        if (arg.rfind("--compare=", 0) == 0) {
            return compare(std::atoi(arg.c_str() + 10));
        }
        if (arg.rfind("--once=", 0) == 0) {
            return draw_once(arg.substr(7));
        }
    }
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
        return 1;
    }
    if (textured) {
        register_textured();
    } else {
        register_all();
    }
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
}
