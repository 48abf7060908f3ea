// Chapter 7 benchmark: the 102,400-triangle torus (model_generator.hpp) at 1280 x 720,
// the project's renderer against Mesa's llvmpipe (through OSMesa) drawing the same
// model with the same effects, one core each, under the measurement protocol of
// chapter 7's @sec:scene-speed: the same input and the same work on both sides, fixed
// costs measured apart, the frames compared after timing.
//
// Run:   taskset -c 1 bench_ch07_big_scene [--benchmark_out=f.csv
//                                           --benchmark_out_format=csv]
// Names: ours/RUN or llvmpipe/RUN, RUN one of
//          full        the scene as shipped: texture (auto mapper), depth on, back faces
//                      culled
//          no_depth    the same without the depth stage (depth = false)
//          no_texture  the same without the texture (the mesh's flat colour)
//          flat        neither depth nor texture: only geometry, culling and coverage
//          empty       full's frame with no triangle in it: the fixed cost of a frame
//                      (ours: a frame and a depth buffer made and cleared; llvmpipe:
//                      clear of colour and depth, glFinish and its copy of the frame)
//          empty_no_depth  the same without depth (no_depth's and flat's fixed cost)
//        and llvmpipe/frame_copy, the part of llvmpipe's empty frame that is OSMesa's
//        copy of the frame into our buffer (llvmpipe_frame_copy).
// Two threads each: `--threads=2` (first) runs instead full_2_threads and
// empty_2_threads, full and empty drawn by ours with FastPaths::threads = 2 and by
// llvmpipe with LP_NUM_THREADS=2 (set by the program), both timed in wall-clock time
// (process CPU time would add the threads' times up); run it on two cores.
// Counters: frames per second and tri_per_s (the model's 102,400 triangles per second),
// per second of process CPU time (every thread of the process, so llvmpipe's rasterizer
// thread counts too, and a loaded machine does not distort it). llvmpipe's runs also
// report the frame check: covered (pixels our frame covers), coverage_diff (pixels
// covered in one frame but not the other) and colour_diff (pixels covered in both whose
// colour differs).
//
// What each side does in one frame, from the same input: the model as loaded, its
// world-space positions and texture coordinates, and the scene's camera.
//   ours      render_scene(scene): the whole pipeline (every position moved to view
//             space once, every triangle projected, tested and culled, then drawn)
//             into a fresh frame and, with depth on, a fresh depth buffer.
//   llvmpipe  glClear (colour, and depth when the run has depth), one glDrawElements of
//             the mesh, glFinish (which copies the frame into our buffer). The mesh
//             goes in once, before timing, as it was loaded: one vertex per distinct
//             (position, texture coordinate) pair, world-space x, y, z and s = u / width,
//             t = v / height, in a buffer object, and the triangles as indices, so that
//             llvmpipe's vertex cache transforms each shared vertex once, as our
//             geometry stage moves each shared position once. GL transforms with the
//             camera's modelview (world to our view space: x right, y up, z the depth)
//             and a projection that puts each point on our pixel: x_clip / w_clip and
//             y_clip / w_clip are our pixel position in NDC (y up, read back top row
//             first with OSMESA_Y_UP 0), w_clip = z, and z_clip = w - 2 near, so that
//             window depth 1 - near / w is linear in 1/w, as our nearness, and GL's
//             near plane is ours. GL culls the back faces (glEnable(GL_CULL_FACE), front
//             faces counter-clockwise in window space, ours); depth test GL_LEQUAL
//             (ties to the later triangle, as ours); the texture with GL_NEAREST,
//             GL_REPEAT, GL_REPLACE, perspective-correct. LP_NUM_THREADS=1 unless the
//             caller sets it.
// Checked after timing (check_frames): llvmpipe's last frame against our render of the
// same scene, pixel by pixel. A pixel is covered when it keeps its colour over a second
// background (each frame drawn once more over it, untimed); the check counts the pixels
// covered in one frame only and those covered in both in different colours. A run
// fails (SkipWithError) when more than max_coverage_differences of the pixels our
// frame covers differ in coverage.
// Precision: ours moves and projects in double; GL gets the matrices in double
// (glLoadMatrixd, rounded to float by Mesa) and the positions and texture coordinates
// as floats, and llvmpipe transforms, clips and sets up its planes in float. So a corner
// may land a float's spacing (2^-13 px between 1024 and 2048 px) from ours and snap to
// the neighbouring 1/256 px, a triangle almost edge-on may be culled on one side only,
// and a pixel near a texel edge may take the neighbouring texel (as it may where our auto
// mapper's approximation, within its budget, crosses the edge): the frame check counts
// what that changes.
// If OSMesa cannot make a context, the llvmpipe runs report an error and are skipped.
//
// Instruction counts (chapters/07-scenes/big_scene.sh): `--once=SIDE/RUN` draws
// one frame untimed, then one more inside ch07_frame_once, the function that
// valgrind --tool=callgrind --toggle-collect=ch07_frame_once counts. Run it with
// LP_NUM_THREADS=0 so that llvmpipe rasterizes in the counted thread. The toggle counts
// our calling thread only; `--thread-counts` (with --threads=N, before --once=ours/RUN)
// has each of our N threads dump its own counts just before and just after that frame
// (callgrind client requests, on the renderer's shared pool), so that
//   valgrind --tool=callgrind --separate-threads=yes bench_ch07_big_scene --threads=2
//       --thread-counts --once=ours/full
// writes each thread's count of the frame in the dumps whose trigger is "after frame".
// `--report` prints format_report of the median of seven renders (by total time) of each
// drawn RUN; `--png=FILE` writes our render of the full scene. `--fast=NAMES` (before
// --once, --report or --png) makes our side use only the named fast paths (FastPaths,
// scene_renderer.hpp), a comma-separated list of masked_fetch, lean_spans and
// lean_geometry, or `none` for the teaching path: the instruction count of each fast path
// is the difference it makes.
#define GL_GLEXT_PROTOTYPES 1
#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/fast/worker_pool.hpp"
#include "exactpixels/lab/model_generator.hpp"
#include "exactpixels/scene/mesh_transform.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"

#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>
#include <benchmark/benchmark.h>
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define EXACTPIXELS_CALLGRIND 1
#endif

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <unistd.h>
#include <vector>

using namespace exactpixels;

namespace {

/// The runs that draw the torus, and the two that draw nothing (a frame's fixed cost).
const char* const effects_names[] = {"full", "no_depth", "no_texture", "flat"};
const char* const empty_names[] = {"empty", "empty_no_depth"};

/// The most pixels, as a fraction of those our frame covers, that may be covered in one
/// frame and not the other before a llvmpipe run fails: a few edge pixels where a
/// float corner snaps to a neighbouring 1/256 px (see the top of the file).
constexpr double max_coverage_differences = 1e-4;

/// The fast paths our side uses: all unless --fast says otherwise.
FastPaths fast_paths{};

/// The threads each side draws with (--threads=N): 1, the one-core runs, or N for the
/// runs RUN_N_threads.
int bench_threads = 1;

/// The scene's effects of run `name`: itself, or full for full_2_threads.
std::string effects_of(const std::string& name) {
    const std::size_t suffix =
        name.find('_' + std::to_string(bench_threads) + "_threads");
    return bench_threads > 1 && suffix != std::string::npos ? name.substr(0, suffix)
                                                            : name;
}

/// Reads --fast=NAMES into fast_paths; false for a name it does not know.
bool read_fast_paths(const std::string& names) {
    fast_paths = teaching_path;
    std::size_t at = 0;
    while (at <= names.size()) {
        const std::size_t comma = std::min(names.find(',', at), names.size());
        const std::string name = names.substr(at, comma - at);
        if (name == "masked_fetch") {
            fast_paths.masked_fetch = true;
        } else if (name == "lean_spans") {
            fast_paths.lean_spans = true;
        } else if (name == "lean_geometry") {
            fast_paths.lean_geometry = true;
        } else if (name != "none") {
            std::fprintf(stderr, "bench_ch07_big_scene: unknown fast path %s\n",
                         name.c_str());
            return false;
        }
        at = comma + 1;
    }
    return true;
}

/// The side of the id texture: texel (i, j) is triangle j * id_texture_side + i's.
constexpr int id_texture_side = 512;

/// A texture with one texel for each of `triangles` triangles, texel n's colour its
/// 24-bit id n + 1 (red the low byte): the "ids" run draws every triangle of the torus
/// with its corners' texture coordinates at its own texel's centre, so that both sides'
/// frames show which triangle won each pixel.
Texture id_texture(std::size_t triangles) {
    const int rows = static_cast<int>((triangles + id_texture_side - 1) / id_texture_side);
    int height = 1;
    while (height < rows) {
        height *= 2; // a power of two, as the torus's own texture is
    }
    std::vector<Rgba8> texels(static_cast<std::size_t>(id_texture_side) * height);
    for (std::size_t n = 0; n < texels.size(); ++n) {
        const std::size_t id = n + 1;
        texels[n] = rgba(static_cast<std::uint8_t>(id), static_cast<std::uint8_t>(id >> 8),
                         static_cast<std::uint8_t>(id >> 16));
    }
    return Texture(id_texture_side, height, std::move(texels));
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
    if (effects == "no_depth" || effects == "flat" || effects == "empty_no_depth") {
        scene.options.depth = DepthMode::off;
    }
    if (effects == "no_texture" || effects == "flat") {
        for (SceneMesh& mesh : scene.meshes) {
            mesh.texture.reset();
        }
    }
    if (effects == "empty" || effects == "empty_no_depth") {
        for (SceneMesh& mesh : scene.meshes) {
            mesh.triangles.clear();
            mesh.positions.clear();
            mesh.corner_positions.clear();
            mesh.corner_uvs.clear();
        }
    }
    if (effects == "ids") { // every triangle in a colour of its own (id_texture)
        std::size_t n = 0;
        for (SceneMesh& mesh : scene.meshes) {
            mesh.colour = {1.0, 1.0, 1.0};
            for (auto& triangle : mesh.triangles) {
                for (SceneVertex& corner : triangle) {
                    corner.uv = {static_cast<double>(n % id_texture_side) + 0.5,
                                 static_cast<double>(n / id_texture_side) + 0.5};
                }
                ++n;
            }
            share_positions(mesh); // the packed uv follow
            mesh.texture = 0;
        }
        scene.textures.at(0).texture = id_texture(n);
    }
    return scene;
}

/// Whether `name` is one of the runs.
bool known_run(const std::string& name) {
    const auto in = [&name](const auto& names) {
        return std::find(std::begin(names), std::end(names), name) != std::end(names);
    };
    return in(effects_names) || in(empty_names);
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

/// What the frame check finds (counts of pixels).
struct FrameCheck {
    long long covered = 0;  ///< covered in our frame
    long long coverage = 0; ///< covered in one frame and not in the other
    long long colour = 0;   ///< covered in both, with different colours
};

/// Puts a frame check into the run's counters: every run of this program reports the
/// same three (Google Benchmark's CSV needs the same counters in every run).
void report_check(benchmark::State& state, const FrameCheck& check) {
    state.counters["covered"] = static_cast<double>(check.covered);
    state.counters["coverage_diff"] = static_cast<double>(check.coverage);
    state.counters["colour_diff"] = static_cast<double>(check.colour);
}

/// Our frame of `effects` over the scene's background and over another, made once.
const std::array<std::vector<Rgba8>, 2>& our_frames(const std::string& effects);

/// Which pixels a frame covers, from the same frame over two backgrounds.
std::vector<bool> covered_pixels(const std::vector<Rgba8>& a,
                                 const std::vector<Rgba8>& b);

void ours(benchmark::State& state, const std::string& effects) {
    const Scene scene = big_scene(effects);
    FastPaths fast = fast_paths;
    fast.threads = bench_threads;
    std::optional<RenderResult> last; // each frame replaces (and frees) the one before
    for (auto _ : state) {
        last = render_scene(scene, nullptr, fast);
        benchmark::DoNotOptimize(last->image.pixels().data());
    }
    report(state, model_triangles(scene));
    // Checked after timing: the timed frames are the picture of an untimed render.
    const auto& reference = our_frames(effects);
    const std::vector<bool> covers = covered_pixels(reference[0], reference[1]);
    FrameCheck check;
    check.covered = std::count(covers.begin(), covers.end(), true);
    report_check(state, check);
    if (!last || last->image.pixels() != reference[0]) {
        state.SkipWithError("a timed frame differs from the untimed render");
    }
}

/// A scene's camera as OpenGL matrices, column-major for glLoadMatrixd: the modelview
/// takes world space to our view space (x right, y up, z the depth, @eq:scene-look-at),
/// the projection takes view space to clip space with x_clip / w_clip, y_clip / w_clip
/// our pixel position in NDC (x right, y up, so that row 0 read back with OSMESA_Y_UP 0
/// is our top row), w_clip = z and z_clip = z - 2 near: window depth 1 - near / z.
struct PeerMatrices {
    std::array<double, 16> modelview{}, projection{};
};

PeerMatrices peer_matrices(const Scene& scene) {
    const SceneCamera& camera = scene.camera;
    // The camera's axes as the renderer builds them (@eq:scene-look-at).
    const glm::dvec3 forward = glm::normalize(camera.target - camera.position);
    const glm::dvec3 right = glm::normalize(glm::cross(camera.up, forward));
    const glm::dvec3 up = glm::cross(forward, right);
    // The pinhole (@eq:scene-focal): focal length f in pixels, the axis through the
    // image centre, so that x_s = W/2 + f x / z and y_s = H/2 - f y / z (y down).
    const double half_angle = 0.5 * camera.fov_degrees * std::acos(-1.0) / 180.0;
    const double f = 0.5 * scene.height / std::tan(half_angle);
    const double cx = 0.5 * scene.width, cy = 0.5 * scene.height;
    const double W = scene.width, H = scene.height, n = camera.near;
    // Rows of each matrix, then stored column by column.
    const double view[4][4] = {
        {right.x, right.y, right.z, -glm::dot(right, camera.position)},
        {up.x, up.y, up.z, -glm::dot(up, camera.position)},
        {forward.x, forward.y, forward.z, -glm::dot(forward, camera.position)},
        {0.0, 0.0, 0.0, 1.0}};
    // x_ndc = 2 x_s / W - 1 and y_ndc = 1 - 2 y_s / H, times w_clip = z.
    const double project[4][4] = {{2.0 * f / W, 0.0, 2.0 * cx / W - 1.0, 0.0},
                                  {0.0, 2.0 * f / H, 1.0 - 2.0 * cy / H, 0.0},
                                  {0.0, 0.0, 1.0, -2.0 * n},
                                  {0.0, 0.0, 1.0, 0.0}};
    PeerMatrices m;
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) {
            m.modelview[4 * column + row] = view[row][column];
            m.projection[4 * column + row] = project[row][column];
        }
    }
    return m;
}

/// llvmpipe through OSMesa: one context for the whole run, made on first use.
struct Peer {
    OSMesaContext context = nullptr;
    int width = 0, height = 0;
    std::vector<std::uint8_t> pixels; ///< RGBA, row 0 the top row (OSMESA_Y_UP 0)
    Colour background;                ///< the clear colour of the timed frames
    std::string problem;              ///< why there is no context, if there is none
};

Peer& peer() {
    static Peer p = [] {
        Peer q;
        const Scene scene = big_scene("full");
        q.width = scene.width;
        q.height = scene.height;
        q.background = scene.background;
        q.pixels.assign(static_cast<std::size_t>(q.width) * q.height * 4, 0);
        if (scene.camera.projection != Projection::perspective ||
            std::isfinite(scene.camera.far)) {
            q.problem = "the GL projection here is for a pinhole without a far plane";
            return q;
        }
        // One rasterizer thread unless the caller says; --threads=N: N.
        setenv("LP_NUM_THREADS", std::to_string(bench_threads).c_str(),
               bench_threads > 1);
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
        const PeerMatrices m = peer_matrices(scene);
        glMatrixMode(GL_PROJECTION);
        glLoadMatrixd(m.projection.data());
        glMatrixMode(GL_MODELVIEW);
        glLoadMatrixd(m.modelview.data());
        glDisable(GL_DITHER);
        glFrontFace(GL_CCW); // ours: counter-clockwise on screen seen from the front
        glCullFace(GL_BACK);
        glHint(GL_PERSPECTIVE_CORRECTION_HINT, GL_NICEST);
        glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
        glClearColor(static_cast<float>(q.background.r),
                     static_cast<float>(q.background.g),
                     static_cast<float>(q.background.b), 1.0f);
        glClearDepth(1.0);
        glDepthFunc(GL_LEQUAL); // ties go to the later triangle, as ours
        return q;
    }();
    return p;
}

/// One mesh as llvmpipe draws it: a range of the index buffer and its state.
struct PeerMesh {
    std::size_t first = 0;  ///< byte offset of its first index
    GLsizei indices = 0;    ///< three per triangle
    GLuint texture = 0;     ///< 0: the flat colour
    bool cull = false;      ///< back faces culled
    Colour colour{1, 1, 1}; ///< the flat colour (untextured)
};

/// A scene's meshes as loaded, as OpenGL vertex and index buffers, and the textures.
struct PeerScene {
    GLuint vertices = 0, indices = 0; ///< buffer objects
    std::vector<PeerMesh> meshes;
    bool depth = false;
    std::size_t distinct_vertices = 0; ///< (position, uv) pairs, each once
};

/// The floats of one vertex: world-space x, y, z and the texture's s, t.
constexpr int peer_floats = 5;

const PeerScene& peer_scene(const std::string& effects) {
    static std::map<std::string, PeerScene> cache;
    auto [it, inserted] = cache.try_emplace(effects);
    if (!inserted) {
        return it->second;
    }
    PeerScene& ps = it->second;
    const Scene scene = big_scene(effects);
    std::vector<float> data; // per vertex: x, y, z, s, t
    std::vector<GLuint> indices;
    for (const SceneMesh& mesh : scene.meshes) {
        const Texture* texture =
            mesh.texture ? &scene.textures[*mesh.texture].texture : nullptr;
        // Each distinct (position, uv) pair once, bit for bit, as share_positions lists
        // positions.
        std::map<std::array<std::uint64_t, 5>, GLuint> index_of;
        PeerMesh pm;
        pm.first = indices.size() * sizeof(GLuint);
        for (const auto& triangle : mesh.triangles) {
            for (const SceneVertex& v : triangle) {
                const TexCoord uv = texture ? v.uv : TexCoord{0.0, 0.0};
                const std::array<std::uint64_t, 5> key = {
                    std::bit_cast<std::uint64_t>(v.position.x),
                    std::bit_cast<std::uint64_t>(v.position.y),
                    std::bit_cast<std::uint64_t>(v.position.z),
                    std::bit_cast<std::uint64_t>(uv.x),
                    std::bit_cast<std::uint64_t>(uv.y)};
                const auto [at, added] = index_of.try_emplace(
                    key, static_cast<GLuint>(data.size() / peer_floats));
                if (added) {
                    const double s = texture ? uv.x / texture->width() : 0.0;
                    const double t = texture ? uv.y / texture->height() : 0.0;
                    for (const double value :
                         {v.position.x, v.position.y, v.position.z, s, t}) {
                        data.push_back(static_cast<float>(value));
                    }
                }
                indices.push_back(at->second);
            }
        }
        pm.indices = static_cast<GLsizei>(indices.size() - pm.first / sizeof(GLuint));
        pm.cull = mesh.cull_back;
        pm.colour = mesh.colour;
        if (texture != nullptr) {
            glGenTextures(1, &pm.texture);
            glBindTexture(GL_TEXTURE_2D, pm.texture);
            glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, texture->width(), texture->height(),
                         0, GL_RGBA, GL_UNSIGNED_BYTE, texture->texels().data());
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
        }
        ps.meshes.push_back(pm);
    }
    ps.distinct_vertices = data.size() / peer_floats;
    glGenBuffers(1, &ps.vertices);
    glBindBuffer(GL_ARRAY_BUFFER, ps.vertices);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(float)),
                 data.data(), GL_STATIC_DRAW);
    glGenBuffers(1, &ps.indices);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ps.indices);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(indices.size() * sizeof(GLuint)), indices.data(),
                 GL_STATIC_DRAW);
    ps.depth = scene.options.depth != DepthMode::off;
    return ps;
}

/// Binds the buffers of `effects` and sets its depth state; returns the scene.
const PeerScene& prepare_peer(const std::string& effects) {
    const PeerScene& ps = peer_scene(effects);
    glBindBuffer(GL_ARRAY_BUFFER, ps.vertices);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ps.indices);
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(3, GL_FLOAT, peer_floats * sizeof(float), nullptr);
    glTexCoordPointer(2, GL_FLOAT, peer_floats * sizeof(float),
                      reinterpret_cast<const void*>(3 * sizeof(float)));
    if (ps.depth) {
        glEnable(GL_DEPTH_TEST);
    } else {
        glDisable(GL_DEPTH_TEST);
    }
    return ps;
}

/// One llvmpipe frame: clear, draw each mesh, finish (OSMesa copies the frame then).
void peer_frame(const PeerScene& ps) {
    glClear(ps.depth ? GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT : GL_COLOR_BUFFER_BIT);
    for (const PeerMesh& mesh : ps.meshes) {
        if (mesh.texture != 0) {
            glEnable(GL_TEXTURE_2D);
            glBindTexture(GL_TEXTURE_2D, mesh.texture);
            glEnableClientState(GL_TEXTURE_COORD_ARRAY);
        } else {
            glDisable(GL_TEXTURE_2D);
            glDisableClientState(GL_TEXTURE_COORD_ARRAY);
            glColor4f(static_cast<float>(mesh.colour.r),
                      static_cast<float>(mesh.colour.g),
                      static_cast<float>(mesh.colour.b), 1.0f);
        }
        if (mesh.cull) {
            glEnable(GL_CULL_FACE);
        } else {
            glDisable(GL_CULL_FACE);
        }
        glDrawElements(GL_TRIANGLES, mesh.indices, GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(mesh.first));
    }
    glFinish();
}

/// A second background: each code of `c` turned into 255 - code, which differs from it
/// in every channel (255 is odd).
Colour other_background(const Colour& c) {
    const Rgba8 code = to_rgba8(c);
    return {(255 - code.r) / 255.0, (255 - code.g) / 255.0, (255 - code.b) / 255.0};
}

/// Which pixels a frame covers: those that are the same over two backgrounds, one
/// bool per pixel. A covered pixel does not depend on the background (no blending); an
/// uncovered one is the background, different in the two.
std::vector<bool> covered_pixels(const std::vector<Rgba8>& a,
                                 const std::vector<Rgba8>& b) {
    std::vector<bool> covered(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        covered[i] = a[i].r == b[i].r && a[i].g == b[i].g && a[i].b == b[i].b;
    }
    return covered;
}

/// Our frame of `effects` over the scene's background and over the other one, made once.
const std::array<std::vector<Rgba8>, 2>& our_frames(const std::string& effects) {
    static std::map<std::string, std::array<std::vector<Rgba8>, 2>> cache;
    auto [it, inserted] = cache.try_emplace(effects);
    if (inserted) {
        Scene scene = big_scene(effects);
        it->second[0] = render_scene(scene, nullptr, fast_paths).image.pixels();
        scene.background = other_background(scene.background);
        it->second[1] = render_scene(scene, nullptr, fast_paths).image.pixels();
    }
    return it->second;
}

/// The buffer OSMesa copied the last frame into, as pixels.
std::vector<Rgba8> peer_pixels(const Peer& p) {
    std::vector<Rgba8> out(p.pixels.size() / 4);
    for (std::size_t i = 0; i < out.size(); ++i) {
        out[i] = {p.pixels[4 * i], p.pixels[4 * i + 1], p.pixels[4 * i + 2],
                  p.pixels[4 * i + 3]};
    }
    return out;
}

/// After the timed loop: llvmpipe's last frame against ours, and one more llvmpipe frame
/// over the other background to find what it covers (its clear colour restored after).
FrameCheck check_frames(Peer& p, const PeerScene& ps, const std::string& effects) {
    const std::vector<Rgba8> peer_a = peer_pixels(p);
    const Colour other = other_background(p.background);
    glClearColor(static_cast<float>(other.r), static_cast<float>(other.g),
                 static_cast<float>(other.b), 1.0f);
    peer_frame(ps);
    const std::vector<Rgba8> peer_b = peer_pixels(p);
    glClearColor(static_cast<float>(p.background.r), static_cast<float>(p.background.g),
                 static_cast<float>(p.background.b), 1.0f);
    const auto& ours = our_frames(effects);
    const std::vector<bool> ours_covers = covered_pixels(ours[0], ours[1]);
    const std::vector<bool> peer_covers = covered_pixels(peer_a, peer_b);
    FrameCheck check;
    for (std::size_t i = 0; i < ours_covers.size(); ++i) {
        check.covered += ours_covers[i] ? 1 : 0;
        if (ours_covers[i] != peer_covers[i]) {
            check.coverage += 1;
        } else if (ours_covers[i] &&
                   (ours[0][i].r != peer_a[i].r || ours[0][i].g != peer_a[i].g ||
                    ours[0][i].b != peer_a[i].b)) {
            check.colour += 1;
        }
    }
    return check;
}

void llvmpipe(benchmark::State& state, const std::string& effects) {
    Peer& p = peer();
    if (p.context == nullptr) {
        state.SkipWithError(p.problem.c_str());
        return;
    }
    const PeerScene& ps = prepare_peer(effects);
    peer_frame(ps); // compiles llvmpipe's code for this state
    for (auto _ : state) {
        peer_frame(ps);
    }
    if (glGetError() != GL_NO_ERROR) {
        state.SkipWithError("OpenGL reported an error");
        return;
    }
    const FrameCheck check = check_frames(p, ps, effects);
    report(state, model_triangles(big_scene(effects)));
    report_check(state, check);
    if (static_cast<double>(check.coverage) >
        max_coverage_differences * static_cast<double>(check.covered)) {
        static std::string message; // SkipWithError keeps the pointer
        message = "llvmpipe's frame covers " + std::to_string(check.coverage) +
                  " pixels differently from ours (" + std::to_string(check.covered) +
                  " covered)";
        state.SkipWithError(message.c_str());
    }
}

/// llvmpipe/frame_copy: the part of an empty frame that is OSMesa's copy. Each frame
/// draws one triangle too small to cover a pixel centre (in clip space, in a corner),
/// with no clear, and glFinish copies the whole frame into our buffer: glFinish copies
/// when anything was drawn or cleared since the last one, so the triangle makes it copy
/// at the least cost. Checked after timing: a frame overwrites every pixel of the
/// buffer.
void llvmpipe_frame_copy(benchmark::State& state) {
    Peer& p = peer();
    if (p.context == nullptr) {
        state.SkipWithError(p.problem.c_str());
        return;
    }
    prepare_peer("empty");
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_TEXTURE_2D);
    glDisable(GL_CULL_FACE);
    glMatrixMode(GL_PROJECTION);
    glPushMatrix();
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glPushMatrix();
    glLoadIdentity();
    const auto frame = [] {
        glBegin(GL_TRIANGLES); // a hundredth of a pixel, at the bottom-left corner
        glVertex2f(-1.0f, -1.0f);
        glVertex2f(-1.0f + 1e-5f, -1.0f);
        glVertex2f(-1.0f, -1.0f + 1e-5f);
        glEnd();
        glFinish();
    };
    frame(); // compiles llvmpipe's code for this state
    for (auto _ : state) {
        frame();
    }
    std::fill(p.pixels.begin(), p.pixels.end(), std::uint8_t{7}); // alpha 7: not GL's
    frame();
    const auto untouched = std::count_if(
        p.pixels.begin() + 3, p.pixels.end(), [n = 0](std::uint8_t a) mutable {
            return n++ % 4 == 0 && a == 7; // every fourth byte from the first alpha
        });
    glPopMatrix();
    glMatrixMode(GL_PROJECTION);
    glPopMatrix();
    glMatrixMode(GL_MODELVIEW);
    if (glGetError() != GL_NO_ERROR) {
        state.SkipWithError("OpenGL reported an error");
    } else if (untouched != 0) {
        state.SkipWithError("glFinish did not copy the whole frame");
    }
    report(state, 0);
    report_check(state, FrameCheck{}); // nothing drawn: nothing covered
}

/// --thread-counts: each of our threads dumps its callgrind counts around the frame.
bool thread_counts = false;

/// With --thread-counts, each of our bench_threads threads dumps (and so zeroes) its
/// callgrind counts under the trigger `when`; nothing outside callgrind.
void dump_each_thread([[maybe_unused]] const char* when) {
#ifdef EXACTPIXELS_CALLGRIND
    if (thread_counts) {
        run_on_shared_pool(bench_threads,
                           [when](int) { CALLGRIND_DUMP_STATS_AT(when); });
    }
#endif
}

/// The one frame callgrind counts (see the top of the file).
extern "C" __attribute__((noinline)) void
ch07_frame_once(const std::function<void()>& draw) {
    draw();
}

/// --once=SIDE/RUN: one frame, then one more inside ch07_frame_once. Returns the
/// exit code (2 for a name it does not know).
int frame_once(const std::string& name) {
    const auto slash = name.find('/');
    const std::string side = name.substr(0, slash);
    const std::string effects = slash == std::string::npos ? "" : name.substr(slash + 1);
    if (!known_run(effects)) {
        std::fprintf(stderr, "bench_ch07_big_scene: unknown run %s\n", name.c_str());
        return 2;
    }
    std::function<void()> draw;
    if (side == "llvmpipe") {
        if (peer().context == nullptr) {
            std::fprintf(stderr, "bench_ch07_big_scene: %s\n", peer().problem.c_str());
            return 2;
        }
        draw = [&ps = prepare_peer(effects)] { peer_frame(ps); };
    } else if (side == "ours") {
        draw = [scene = big_scene(effects)] {
            FastPaths fast = fast_paths;
            fast.threads = bench_threads; // --threads=N before --once
            const RenderResult result = render_scene(scene, nullptr, fast);
            benchmark::DoNotOptimize(result.image.pixels().data());
        };
    } else {
        std::fprintf(stderr, "bench_ch07_big_scene: unknown run %s\n", name.c_str());
        return 2;
    }
    draw(); // the first frame compiles llvmpipe's code
    dump_each_thread("before frame");
    ch07_frame_once(draw);
    dump_each_thread("after frame");
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

/// The spread of the repetitions (--benchmark_repetitions): their smallest and largest.
double smallest(const std::vector<double>& v) {
    return *std::min_element(v.begin(), v.end());
}
double largest(const std::vector<double>& v) {
    return *std::max_element(v.begin(), v.end());
}

} // namespace

int main(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg.rfind("--threads=", 0) == 0) { // not for Google Benchmark either
            bench_threads = std::atoi(arg.c_str() + 10);
            if (bench_threads < 2 || bench_threads > max_threads) {
                std::fprintf(stderr, "bench_ch07_big_scene: bad thread count %s\n",
                             arg.c_str() + 10);
                return 2;
            }
            std::copy(argv + i + 1, argv + argc, argv + i);
            argc -= 1;
            i -= 1;
            continue;
        }
        if (arg.rfind("--fast=", 0) == 0) { // ours only; not for Google Benchmark
            if (!read_fast_paths(arg.substr(7))) {
                return 2;
            }
            std::copy(argv + i + 1, argv + argc, argv + i);
            argc -= 1;
            i -= 1;
            continue;
        }
        if (arg == "--thread-counts") { // ours on --threads=N only
            thread_counts = bench_threads > 1;
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
    std::vector<std::string> runs(std::begin(effects_names), std::end(effects_names));
    runs.insert(runs.end(), std::begin(empty_names), std::end(empty_names));
    if (bench_threads > 1) { // full and empty on N threads each, and nothing else
        const std::string n = "_" + std::to_string(bench_threads) + "_threads";
        runs = {"full" + n, "empty" + n};
    }
    for (const std::string& run : runs) {
        for (const char* side : {"ours", "llvmpipe"}) {
            const std::string e = effects_of(run);
            benchmark::internal::Benchmark* b =
                benchmark::RegisterBenchmark(
                    (std::string(side) + "/" + run).c_str(),
                    side == std::string("ours")
                        ? std::function<void(benchmark::State&)>(
                              [e](benchmark::State& s) { ours(s, e); })
                        : std::function<void(benchmark::State&)>(
                              [e](benchmark::State& s) { llvmpipe(s, e); }))
                    ->Unit(benchmark::kMillisecond)
                    ->ComputeStatistics("min", smallest)
                    ->ComputeStatistics("max", largest);
            if (bench_threads > 1) {
                b->UseRealTime();
            } else {
                b->MeasureProcessCPUTime();
            }
        }
    }
    if (bench_threads > 1) {
        benchmark::RunSpecifiedBenchmarks();
        benchmark::Shutdown();
        return 0;
    }
    // Checked after timing with every triangle's 24-bit id as its colour: the frame
    // check's colour differences are pixels another triangle won on one side.
    benchmark::RegisterBenchmark("llvmpipe/ids", [](benchmark::State& s) {
        llvmpipe(s, "ids");
    })
        ->Unit(benchmark::kMillisecond)
        ->MeasureProcessCPUTime()
        ->ComputeStatistics("min", smallest)
        ->ComputeStatistics("max", largest);
    benchmark::RegisterBenchmark("llvmpipe/frame_copy", llvmpipe_frame_copy)
        ->Unit(benchmark::kMillisecond)
        ->MeasureProcessCPUTime()
        ->ComputeStatistics("min", smallest)
        ->ComputeStatistics("max", largest);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
}
