// Chapter 7 benchmark: the 102,400-triangle torus (model_generator.hpp) at 1280 x 720,
// the project's renderer against Mesa's llvmpipe (through OSMesa) drawing the same
// triangles with the same effects, one core each.
//
// Run:   taskset -c 1 bench_ch07_big_scene [--benchmark_out=f.csv
//                                           --benchmark_out_format=csv]
// Names: ours/EFFECTS or llvmpipe/EFFECTS, EFFECTS one of
//          full        the scene as shipped: texture (auto mapper), depth on, back faces
//                      culled
//          no_depth    the same without the depth stage (depth = false)
//          no_texture  the same without the texture (the mesh's flat colour)
//          flat        neither depth nor texture: only geometry, culling and coverage
// Counters: frames per second and tri_per_s (the model's 102,400 triangles per second),
// per second of process CPU time (every thread of the process, so llvmpipe's rasterizer
// thread counts too, and a loaded machine does not distort it).
//
// What each side does in one frame:
//   ours      render_scene(scene): the whole pipeline, geometry stage included (every
//             triangle moved to view space, projected and culled), into a fresh frame.
//   llvmpipe  glClear, one glDrawArrays of the triangles run_geometry(scene) handed out
//             (taken once, before timing: back faces already culled, so llvmpipe does
//             less than we do), glFinish. Each corner goes in as the clip-space point
//             (x w, y w, z w, w) of its pixel position, so llvmpipe's own perspective
//             divide puts it on our pixel, with z w = w - 2 near (window depth linear in
//             1/w, as our nearness), depth test GL_LEQUAL (ties to the later triangle,
//             as ours), the texture with GL_NEAREST, GL_REPEAT, GL_REPLACE and
//             perspective-correct coordinates (u / width, v / height). LP_NUM_THREADS=1
//             unless the caller sets it.
// If OSMesa cannot make a context, the llvmpipe runs report an error and are skipped.
//
// Instruction counts (chapters/07-scenes/big_scene.sh): `--once=SIDE/EFFECTS` draws
// one frame untimed, then one more inside ch07_frame_once, the function that
// valgrind --tool=callgrind --toggle-collect=ch07_frame_once counts. Run it with
// LP_NUM_THREADS=0 so that llvmpipe rasterizes in the counted thread.
// `--report` prints format_report of the median of seven renders (by total time) of each
// EFFECTS; `--png=FILE` writes our render of the full scene. `--fast=NAMES` (before
// --once, --report or --png) makes our side use only the named fast paths (FastPaths,
// scene_renderer.hpp), a comma-separated list of screen_accept, masked_fetch,
// unlit_geometry and lean_spans, or
// `none` for the plain path: the instruction count of each fast path is the difference
// it makes.
#define GL_GLEXT_PROTOTYPES 1
#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/lab/model_generator.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"

#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <unistd.h>
#include <vector>

using namespace exactpixels;

namespace {

const char* const effects_names[] = {"full", "no_depth", "no_texture", "flat"};

/// The fast paths our side uses: all unless --fast says otherwise.
FastPaths fast_paths{};

/// Reads --fast=NAMES into fast_paths; false for a name it does not know.
bool read_fast_paths(const std::string& names) {
    fast_paths = plain_paths;
    std::size_t at = 0;
    while (at <= names.size()) {
        const std::size_t comma = std::min(names.find(',', at), names.size());
        const std::string name = names.substr(at, comma - at);
        if (name == "screen_accept") {
            fast_paths.screen_accept = true;
        } else if (name == "masked_fetch") {
            fast_paths.masked_fetch = true;
        } else if (name == "unlit_geometry") {
            fast_paths.unlit_geometry = true;
        } else if (name == "lean_spans") {
            fast_paths.lean_spans = true;
        } else if (name != "none") {
            std::fprintf(stderr, "bench_ch07_big_scene: unknown fast path %s\n",
                         name.c_str());
            return false;
        }
        at = comma + 1;
    }
    return true;
}

/// The big torus scene as written by the generator and read back through the OBJ
/// reader, with the effects `effects` asks for.
Scene big_scene(const std::string& effects) {
    static const Scene shipped = [] {
        const std::filesystem::path folder =
            std::filesystem::temp_directory_path() /
            ("exactpixels-bench-big-scene-" + std::to_string(::getpid()));
        std::filesystem::create_directories(folder);
        write_generated_model(big_torus_model(), folder);
        write_file_atomically(folder / "big_torus.toml", "scene", big_torus_scene());
        Scene s = load_scene(folder / "big_torus.toml");
        std::filesystem::remove_all(folder);
        return s;
    }();
    Scene scene = shipped;
    if (effects == "no_depth" || effects == "flat") {
        scene.options.depth = DepthMode::off;
    }
    if (effects == "no_texture" || effects == "flat") {
        for (SceneMesh& mesh : scene.meshes) {
            mesh.texture.reset();
        }
    }
    return scene;
}

std::size_t model_triangles(const Scene& scene) {
    std::size_t n = 0;
    for (const SceneMesh& mesh : scene.meshes) {
        n += mesh.triangles.size();
    }
    return n;
}

void report(benchmark::State& state, std::size_t triangles) {
    using benchmark::Counter;
    const double frames = static_cast<double>(state.iterations());
    state.counters["frames_per_s"] = Counter(frames, Counter::kIsRate);
    state.counters["tri_per_s"] =
        Counter(frames * static_cast<double>(triangles), Counter::kIsRate);
}

void ours(benchmark::State& state, const std::string& effects) {
    const Scene scene = big_scene(effects);
    for (auto _ : state) {
        const RenderResult result = render_scene(scene, nullptr, fast_paths);
        benchmark::DoNotOptimize(result.image.pixels().data());
    }
    report(state, model_triangles(scene));
}

/// llvmpipe through OSMesa: one context for the whole run, made on first use.
struct Peer {
    OSMesaContext context = nullptr;
    int width = 0, height = 0;
    std::vector<std::uint8_t> pixels;
    std::string problem; ///< why there is no context, if there is none
};

Peer& peer() {
    static Peer p = [] {
        Peer q;
        const Scene scene = big_scene("full");
        q.width = scene.width;
        q.height = scene.height;
        q.pixels.assign(static_cast<std::size_t>(q.width) * q.height * 4, 0);
        setenv("LP_NUM_THREADS", "1", 0); // one rasterizer thread unless the caller says
        q.context = OSMesaCreateContextExt(OSMESA_RGBA, 32, 0, 0, nullptr);
        if (q.context == nullptr) {
            q.problem = "OSMesaCreateContextExt failed: no llvmpipe";
            return q;
        }
        if (!OSMesaMakeCurrent(q.context, q.pixels.data(), GL_UNSIGNED_BYTE, q.width,
                               q.height)) {
            q.problem = "OSMesaMakeCurrent failed";
            return q;
        }
        OSMesaPixelStore(OSMESA_Y_UP, 0); // row 0 of the buffer is the top row
        glViewport(0, 0, q.width, q.height);
        glMatrixMode(GL_PROJECTION);
        glLoadIdentity(); // the vertices are clip-space points already
        glMatrixMode(GL_MODELVIEW);
        glLoadIdentity();
        glDisable(GL_DITHER);
        glDisable(GL_CULL_FACE); // run_geometry culled them
        glHint(GL_PERSPECTIVE_CORRECTION_HINT, GL_NICEST);
        const Colour bg = scene.background;
        glClearColor(static_cast<float>(bg.r), static_cast<float>(bg.g),
                     static_cast<float>(bg.b), 1.0f);
        glClearDepth(1.0);
        glDepthFunc(GL_LEQUAL); // ties go to the later triangle, as ours
        return q;
    }();
    return p;
}

/// The triangles run_geometry hands out for `effects`, as OpenGL vertex arrays in one
/// buffer object, and the texture.
struct PeerScene {
    GLuint buffer = 0, texture = 0;
    GLsizei vertices = 0;
    bool textured = false, depth = false;
};

const PeerScene& peer_scene(const std::string& effects) {
    static std::map<std::string, PeerScene> cache;
    auto [it, inserted] = cache.try_emplace(effects);
    if (!inserted) {
        return it->second;
    }
    PeerScene& ps = it->second;
    const Scene scene = big_scene(effects);
    RenderReport report;
    const SceneGeometry geometry = run_geometry(scene, report);
    const double near = scene.camera.near;
    std::vector<float> data; // per vertex: x, y, z, w, s, t
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const SceneMesh& mesh = scene.meshes[m];
        const Texture* texture =
            mesh.texture ? &scene.textures[*mesh.texture].texture : nullptr;
        for (const ScreenTriangle& t : geometry.meshes[m]) {
            for (const TexturedVertex& v : t.corners) {
                const double x = 2.0 * v.position.x / scene.width - 1.0;
                const double y = 1.0 - 2.0 * v.position.y / scene.height;
                const double w = v.w;
                const double s = texture ? v.uv.x / texture->width() : 0.0;
                const double tt = texture ? v.uv.y / texture->height() : 0.0;
                for (const double value : {x * w, y * w, w - 2.0 * near, w, s, tt}) {
                    data.push_back(static_cast<float>(value));
                }
            }
        }
    }
    ps.vertices = static_cast<GLsizei>(data.size() / 6);
    glGenBuffers(1, &ps.buffer);
    glBindBuffer(GL_ARRAY_BUFFER, ps.buffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(float)),
                 data.data(), GL_STATIC_DRAW);
    ps.depth = scene.options.depth != DepthMode::off;
    ps.textured = scene.meshes.at(0).texture.has_value();
    glColor4f(static_cast<float>(scene.meshes.at(0).colour.r),
              static_cast<float>(scene.meshes.at(0).colour.g),
              static_cast<float>(scene.meshes.at(0).colour.b), 1.0f);
    if (ps.textured) {
        const Texture& texture = scene.textures[*scene.meshes.at(0).texture].texture;
        glGenTextures(1, &ps.texture);
        glBindTexture(GL_TEXTURE_2D, ps.texture);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, texture.width(), texture.height(), 0,
                     GL_RGBA, GL_UNSIGNED_BYTE, texture.texels().data());
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
        glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    }
    return ps;
}

/// Sets llvmpipe's state for `effects`; returns the vertex count for glDrawArrays.
GLsizei prepare_peer(const std::string& effects) {
    const PeerScene& ps = peer_scene(effects);
    glBindBuffer(GL_ARRAY_BUFFER, ps.buffer);
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(4, GL_FLOAT, 6 * sizeof(float), nullptr);
    if (ps.textured) {
        glEnable(GL_TEXTURE_2D);
        glBindTexture(GL_TEXTURE_2D, ps.texture);
        glEnableClientState(GL_TEXTURE_COORD_ARRAY);
        glTexCoordPointer(2, GL_FLOAT, 6 * sizeof(float),
                          reinterpret_cast<const void*>(4 * sizeof(float)));
    } else {
        glDisable(GL_TEXTURE_2D);
        glDisableClientState(GL_TEXTURE_COORD_ARRAY);
    }
    if (ps.depth) {
        glEnable(GL_DEPTH_TEST);
    } else {
        glDisable(GL_DEPTH_TEST);
    }
    return ps.vertices;
}

/// One llvmpipe frame: clear, draw, finish.
void peer_frame(GLsizei vertices) {
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDrawArrays(GL_TRIANGLES, 0, vertices);
    glFinish();
}

void llvmpipe(benchmark::State& state, const std::string& effects) {
    Peer& p = peer();
    if (p.context == nullptr) {
        state.SkipWithError(p.problem.c_str());
        return;
    }
    const GLsizei vertices = prepare_peer(effects);
    peer_frame(vertices); // compiles llvmpipe's code for this state
    for (auto _ : state) {
        peer_frame(vertices);
    }
    if (glGetError() != GL_NO_ERROR) {
        state.SkipWithError("OpenGL reported an error");
    }
    report(state, model_triangles(big_scene(effects)));
}

/// The one frame callgrind counts (see the top of the file).
extern "C" __attribute__((noinline)) void
ch07_frame_once(const std::function<void()>& draw) {
    draw();
}

/// --once=SIDE/EFFECTS: one frame, then one more inside ch07_frame_once. Returns the
/// exit code (2 for a name it does not know).
int frame_once(const std::string& name) {
    const auto slash = name.find('/');
    const std::string side = name.substr(0, slash);
    const std::string effects = slash == std::string::npos ? "" : name.substr(slash + 1);
    if (std::find(std::begin(effects_names), std::end(effects_names), effects) ==
        std::end(effects_names)) {
        std::fprintf(stderr, "bench_ch07_big_scene: unknown run %s\n", name.c_str());
        return 2;
    }
    std::function<void()> draw;
    if (side == "llvmpipe") {
        if (peer().context == nullptr) {
            std::fprintf(stderr, "bench_ch07_big_scene: %s\n", peer().problem.c_str());
            return 2;
        }
        const GLsizei vertices = prepare_peer(effects);
        draw = [vertices] { peer_frame(vertices); };
    } else if (side == "ours") {
        draw = [scene = big_scene(effects)] {
            const RenderResult result = render_scene(scene, nullptr, fast_paths);
            benchmark::DoNotOptimize(result.image.pixels().data());
        };
    } else {
        std::fprintf(stderr, "bench_ch07_big_scene: unknown run %s\n", name.c_str());
        return 2;
    }
    draw(); // the first frame compiles llvmpipe's code
    ch07_frame_once(draw);
    return 0;
}

/// How many renders --report times per EFFECTS (after an untimed first one).
constexpr int report_renders = 7;

/// --report: for each EFFECTS, the report of the render whose total time is the median
/// of report_renders renders made after a first one (as the benchmark times frames
/// after the first). One whole report, so that its stages add up to its total; the
/// median, so that one slow spell of a shared machine does not make the breakdown.
int print_reports() {
    for (const char* effects : effects_names) {
        const Scene scene = big_scene(effects);
        render_scene(scene, nullptr, fast_paths);
        std::vector<RenderReport> reports;
        for (int n = 0; n < report_renders; ++n) {
            reports.push_back(render_scene(scene, nullptr, fast_paths).report);
        }
        const auto median = reports.begin() + report_renders / 2;
        std::nth_element(reports.begin(), median, reports.end(),
                         [](const RenderReport& a, const RenderReport& b) {
                             return a.seconds < b.seconds;
                         });
        std::printf("## %s\n\n%s\n", effects, format_report(*median).c_str());
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg.rfind("--fast=", 0) == 0) { // ours only; not for Google Benchmark
            if (!read_fast_paths(arg.substr(7))) {
                return 2;
            }
            std::copy(argv + i + 1, argv + argc, argv + i);
            argc -= 1;
            i -= 1;
            continue;
        }
        if (arg.rfind("--once=", 0) == 0) {
            return frame_once(arg.substr(7));
        }
        if (arg == "--report") {
            return print_reports();
        }
        if (arg.rfind("--png=", 0) == 0) {
            write_png(arg.substr(6),
                      render_scene(big_scene("full"), nullptr, fast_paths).image);
            return 0;
        }
    }
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
        return 1;
    }
    for (const char* effects : effects_names) {
        for (const char* side : {"ours", "llvmpipe"}) {
            const std::string e = effects;
            benchmark::RegisterBenchmark(
                (std::string(side) + "/" + effects).c_str(),
                side == std::string("ours")
                    ? std::function<void(benchmark::State&)>(
                          [e](benchmark::State& s) { ours(s, e); })
                    : std::function<void(benchmark::State&)>(
                          [e](benchmark::State& s) { llvmpipe(s, e); }))
                ->Unit(benchmark::kMillisecond)
                ->MeasureProcessCPUTime();
        }
    }
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
}
