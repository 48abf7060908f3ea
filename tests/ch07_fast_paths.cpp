// Chapter 7 tests: the renderer's fast paths (FastPaths) are speed tricks only. With
// them on and off, every shipped scene and the big torus of the speed comparison give
// the same pixels, the same texel coordinates and the same report counts; the masked
// texel fetch reads the texel fetch_texel reads. The geometry stage's indexed mesh: its
// outcodes reject and clip random triangles placed on and around the screen's edges,
// the guard band, the near and the far plane as the view volume's plane tests do, and
// a mesh drawn from its own index, from one made again after a change or from none
// gives the same picture. The threaded driver (FastPaths::threads): every shipped
// scene, the big torus and the refused scenes give the same pixels, texel coordinates,
// report counts and error message with 1, 2, 3 and 7 threads as the book's loop, and the
// command line refuses a bad thread count. Every test that starts a thread is named
// "any number of threads ...": the arm64 workflow leaves those out (tests/CMakeLists.txt
// says why).
#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/base/printable.hpp"
#include "exactpixels/fast/worker_pool.hpp"
#include "exactpixels/lab/model_generator.hpp"
#include "exactpixels/scene/camera.hpp"
#include "exactpixels/scene/corner_quotients.hpp"
#include "exactpixels/scene/lighting.hpp"
#include "exactpixels/scene/mesh_transform.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "exactpixels/texture/perspective.hpp"
#include "exactpixels/texture/rounding.hpp"
#include "exactpixels/texture/texture.hpp"
#include "support/printing.hpp"
#include "support/process.hpp"
#include "support/scene_files.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

using namespace exactpixels;

namespace {

/// Every count of a stage (its seconds are not counts).
void check_same_counts(const WorkCount& a, const WorkCount& b, const char* stage) {
    INFO(stage);
    CHECK(a.triangles == b.triangles);
    CHECK(a.spans == b.spans);
    CHECK(a.pixels == b.pixels);
    CHECK(a.divides == b.divides);
}

/// Every count of two reports.
void check_same_report(const RenderReport& a, const RenderReport& b) {
    check_same_counts(a.geometry, b.geometry, "geometry");
    check_same_counts(a.rejected, b.rejected, "rejected");
    check_same_counts(a.clipping, b.clipping, "clipping");
    check_same_counts(a.culling, b.culling, "culling");
    check_same_counts(a.depth, b.depth, "depth");
    check_same_counts(a.hidden, b.hidden, "hidden");
    check_same_counts(a.raster, b.raster, "raster");
    check_same_counts(a.flat, b.flat, "flat");
    check_same_counts(a.colour, b.colour, "colour");
    check_same_counts(a.colour_perspective, b.colour_perspective, "colour_perspective");
    check_same_counts(a.texture, b.texture, "texture");
    check_same_counts(a.auto_choice, b.auto_choice, "auto_choice");
    for (std::size_t k = 0; k < a.mappers.size(); ++k) {
        check_same_counts(a.mappers[k], b.mappers[k], "mapper");
    }
    check_same_counts(a.filter, b.filter, "filter");
    check_same_counts(a.lighting, b.lighting, "lighting");
    CHECK(a.lit_vertices == b.lit_vertices);
    CHECK(a.filter_triangles == b.filter_triangles);
    CHECK(a.mip_chains == b.mip_chains);
    CHECK(a.depth_on == b.depth_on);
    CHECK(a.colour_bound == b.colour_bound);
}

/// The same pixels, texel coordinates and report counts in two renders.
void check_same_render(const RenderResult& a, const TexelMap& a_map,
                       const RenderResult& b, const TexelMap& b_map) {
    CHECK(a.image == b.image);
    CHECK(a_map.covered == b_map.covered);
    CHECK(a_map.i == b_map.i);
    CHECK(a_map.j == b_map.j);
    CHECK(a_map.u == b_map.u);
    CHECK(a_map.v == b_map.v);
    check_same_report(a.report, b.report);
}

/// Renders the scene with every fast path and on the teaching path and checks that the
/// pixels, the texel coordinates and the counts are the same: once recording the texel
/// coordinates, and once without, as a plain render runs (lean_spans draws only then).
void check_fast_is_teaching(const Scene& scene) {
    TexelMap fast_map(scene.width, scene.height), plain_map(scene.width, scene.height);
    const RenderResult fast = render_scene(scene, &fast_map);
    const RenderResult plain = render_scene(scene, &plain_map, teaching_path);
    check_same_render(fast, fast_map, plain, plain_map);
    const RenderResult fast_only = render_scene(scene);
    CHECK(fast_only.image == plain.image);
    check_same_report(fast_only.report, plain.report);
}

/// The thread counts the threaded driver is checked with: 1 (the book's loop), two
/// bands per thread and fewer, odd counts, more threads than some images have bands.
constexpr std::array<int, 4> checked_threads = {1, 2, 3, 7};

/// Renders the scene with each of checked_threads threads, with and without a texel map,
/// and checks the pixels, coordinates and counts against the book's loop (one thread,
/// fast paths on) and the teaching path. Returns how many renders it compared.
int check_threads_are_one(const Scene& scene) {
    TexelMap one_map(scene.width, scene.height);
    const RenderResult one = render_scene(scene, &one_map);
    const RenderResult plain = render_scene(scene, nullptr, teaching_path);
    CHECK(one.image == plain.image);
    int compared = 0;
    for (int threads : checked_threads) {
        INFO(threads << " threads");
        FastPaths fast;
        fast.threads = threads;
        TexelMap map(scene.width, scene.height);
        check_same_render(render_scene(scene, &map, fast), map, one, one_map);
        const RenderResult plain_run = render_scene(scene, nullptr, fast);
        CHECK(plain_run.image == plain.image);
        check_same_report(plain_run.report, plain.report);
        FastPaths teaching = teaching_path;
        teaching.threads = threads;
        CHECK(render_scene(scene, nullptr, teaching).image == plain.image);
        compared += 3;
    }
    return compared;
}

/// The message render_scene throws for the scene with `threads` threads, or "" if none.
std::string render_error(const Scene& scene, int threads) {
    FastPaths fast;
    fast.threads = threads;
    try {
        render_scene(scene, nullptr, fast);
    } catch (const Error& error) {
        return error.what();
    }
    return "";
}

/// The big torus of the speed comparison, written by the generator and read back.
Scene big_torus() {
    const std::filesystem::path folder =
        std::filesystem::temp_directory_path() /
        ("exactpixels-test-fast-paths-" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    write_generated_model(big_torus_model(), folder);
    write_file_atomically(folder / "big_torus.toml", "scene", big_torus_scene());
    const Scene scene = load_scene(folder / "big_torus.toml");
    std::filesystem::remove_all(folder);
    return scene;
}

/// Whether two lists hold the same values, bit for bit.
template <class T> bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

/// Runs the geometry stage on the scene, and on it lit, with each of checked_threads
/// threads, and checks that every list, footprint and count is one thread's, bit for
/// bit. Returns the number of threaded runs compared.
int check_geometry_threads(const Scene& unlit) {
    Scene lit = unlit;
    lit.lights.push_back(SceneLight{});
    int compared = 0;
    for (const Scene* scene : {&unlit, static_cast<const Scene*>(&lit)}) {
        RenderReport one_report;
        const SceneGeometry one = run_geometry(*scene, one_report);
        for (int threads : checked_threads) {
            INFO(threads << " threads, " << (scene == &lit ? "lit" : "unlit"));
            RenderReport report;
            const SceneGeometry geometry = run_geometry(*scene, report, threads);
            REQUIRE(geometry.meshes.size() == one.meshes.size());
            for (std::size_t i = 0; i < one.meshes.size(); ++i) {
                INFO("mesh " << i);
                CHECK(same_bits(geometry.meshes[i], one.meshes[i]));
                CHECK(same_bits(geometry.shading[i], one.shading[i]));
                const ScreenBox &a = geometry.footprints[i].box,
                                b = one.footprints[i].box;
                CHECK(std::memcmp(&a, &b, sizeof a) == 0);
                CHECK(geometry.footprints[i].name == one.footprints[i].name);
                CHECK(geometry.footprints[i].can_overlap_itself ==
                      one.footprints[i].can_overlap_itself);
            }
            check_same_report(report, one_report);
            CHECK(report.gouraud_meshes == one_report.gouraud_meshes);
            CHECK(report.phong_meshes == one_report.phong_meshes);
            compared += 1;
        }
    }
    return compared;
}

/// The message run_geometry throws for the scene with `threads` threads, or "" if none.
std::string geometry_error(const Scene& scene, int threads) {
    RenderReport report;
    try {
        run_geometry(scene, report, threads);
    } catch (const Error& error) {
        return error.what();
    }
    return "";
}

/// The TOML number that reads back as x exactly (fmt's shortest round trip).
std::string number(double x) {
    return fmt::format("{}", x);
}

/// Two scenes of 3,000 random textured triangles, the first seen in perspective, the
/// second orthographic, for the tests of the view volume's planes.
std::array<Scene, 2> edge_scenes() {
    // Corners placed on screen at and around each line the tests compare with: the
    // screen's edges, the guard band's, the margin inside them; at depths at and
    // around the near and the far plane. A corner (px, py) at depth z is the view-space
    // point ((px - cx) z / f, (cy - py) z / f, z), all within the loader's 1e6 units.
    constexpr int width = 64, height = 48;
    constexpr double near = 0.5, far = 40.0;
    const double f = 0.5 * height / std::tan(0.25 * std::acos(-1.0)); // fov 90
    const double band = guard_band_px, tiny = 1.0 / 256.0;
    const std::vector<double> xs = {-band - 1.0,
                                    -band,
                                    -band + tiny,
                                    -band + 2.0 * tiny,
                                    -1.0,
                                    -tiny,
                                    0.0,
                                    tiny / 2.0,
                                    tiny,
                                    2.0 * tiny,
                                    10.0,
                                    width - tiny,
                                    width - tiny / 2.0,
                                    width,
                                    width + 1.0,
                                    band - 2.0 * tiny,
                                    band - tiny,
                                    band,
                                    band + 1.0,
                                    band + 1000.0};
    std::vector<double> ys = xs;
    for (double& y : ys) {
        y = y == width ? height : y == width - tiny ? height - tiny : y;
    }
    const std::vector<double> zs = {std::nextafter(near, 0.0), near, 1.0, 3.0, far,
                                    std::nextafter(far, 1e9),  44.0};
    std::mt19937 random(1717);
    const auto pick = [&](const std::vector<double>& from) {
        return from[std::uniform_int_distribution<std::size_t>(0,
                                                               from.size() - 1)(random)];
    };
    std::array<Scene, 2> scenes;
    for (std::size_t i = 0; i < scenes.size(); ++i) {
        const bool perspective = i == 0;
        const char* projection = perspective ? "perspective" : "orthographic";
        std::string positions, uvs;
        for (int t = 0; t < 3000;) {
            std::array<glm::dvec3, 3> corner{};
            for (glm::dvec3& c : corner) {
                // Mostly near the screen, so that most triangles cover pixels.
                const bool wild = std::uniform_int_distribution<int>(0, 2)(random) == 0;
                const double px = wild ? pick(xs)
                                       : std::uniform_real_distribution<double>(
                                             -4.0, width + 4.0)(random);
                const double py = wild ? pick(ys)
                                       : std::uniform_real_distribution<double>(
                                             -4.0, height + 4.0)(random);
                const double z = pick(zs);
                const double scale = perspective ? z / f : 1.0 / f; // view_height = h / f
                c = {(px - 0.5 * width) * scale, (0.5 * height - py) * scale, z};
            }
            const glm::dvec3 a = corner[1] - corner[0], b = corner[2] - corner[0];
            if (glm::length(glm::cross(a, b)) <= 1e-6 * glm::length(a) * glm::length(b)) {
                continue; // the loader refuses a triangle without area
            }
            for (std::size_t k = 0; k < 3; ++k) {
                positions += fmt::format("[{}, {}, {}],", number(corner[k].x),
                                         number(corner[k].y), number(corner[k].z));
                uvs += fmt::format("[{}, {}],", 8 * k, 4 * t % 64);
            }
            t += 1;
        }
        const std::string toml = fmt::format(
            "[image]\nwidth = {}\nheight = {}\n[camera]\nprojection = \"{}\"\n"
            "position = [0, 0, 0]\ntarget = [0, 0, 1]\nfov = 90\nview_height = {}\n"
            "near = {}\nfar = {}\n[render]\ndepth = true\nmapper = \"auto\"\n"
            "[textures.checks]\nkind = \"checkerboard\"\nsize = [64, 64]\n"
            "square = 8\n"
            "[[mesh]]\nprimitive = \"triangles\"\ntexture = \"checks\"\n"
            "positions = [{}]\nuv = [{}]\n",
            width, height, projection, number(height / f), number(near), number(far),
            positions, uvs);
        scenes[i] = parse_scene(toml, "edges.toml", ".");
    }
    return scenes;
}

} // namespace

TEST_CASE("the fast paths draw every shipped scene as the teaching path does") {
    const std::filesystem::path folder = shipped_scene_folder();
    int scenes = 0;
    for (const std::filesystem::path& path : exactpixels::testing::scene_files(folder)) {
        INFO(path.string());
        check_fast_is_teaching(load_scene(path));
        scenes += 1;
    }
    CHECK(scenes >= 7); // shipped_scenes() and the model scenes
    // A narrow view (corners far off screen, inside the guard band) and a far plane
    // that cuts: the undecided triangles go the plain way.
    Scene narrow = load_scene(folder / "horizon.toml");
    narrow.camera.fov_degrees = 5.0;
    check_fast_is_teaching(narrow);
    Scene cut = load_scene(folder / "corridor.toml");
    cut.camera.far = 0.5 * (cut.camera.near + 20.0);
    check_fast_is_teaching(cut);
}

TEST_CASE("the fast paths draw the big torus as the teaching path does") {
    const Scene scene = big_torus();
    REQUIRE(scene.meshes.size() == 1);
    CHECK(scene.meshes[0].triangles.size() == 102400);
    // A closed grid of 400 x 128 quads: each position is shared by six corners, and
    // the geometry stage moves each once.
    CHECK(scene.meshes[0].positions.size() == 400 * 128);
    check_fast_is_teaching(scene);
    // Corners changed after loading, the index made again: the picture changes, and is
    // the one the stage draws from a mesh without an index, which it indexes itself.
    Scene changed = scene;
    for (std::size_t t = 0; t < changed.meshes[0].triangles.size(); t += 97) {
        glm::dvec3& p = changed.meshes[0].triangles[t][t % 3].position;
        p = p * 1.001;
    }
    share_positions(changed.meshes[0]);
    check_fast_is_teaching(changed);
    Scene unindexed = changed;
    unindexed.meshes[0].positions.clear();
    unindexed.meshes[0].corner_positions.clear();
    const RenderResult from_index = render_scene(changed);
    CHECK(from_index.image != render_scene(scene).image);
    CHECK(render_scene(unindexed).image == from_index.image);
    check_same_report(render_scene(unindexed).report, from_index.report);
    // Each fast path alone (as big_scene.sh counts their instructions), on the torus and
    // on it without depth, where every pixel a triangle covers is written: the same
    // pixels and counts as the teaching path. All of them together is the check above.
    Scene no_depth = scene;
    no_depth.options.depth = DepthMode::off;
    for (const Scene* s : std::array<const Scene*, 2>{&scene, &no_depth}) {
        const RenderResult plain = render_scene(*s, nullptr, teaching_path);
        for (int path = 0; path < 4; ++path) {
            INFO("fast path " << path << (s == &scene ? ", depth on" : ", depth off"));
            FastPaths alone = teaching_path;
            bool* const flags[] = {&alone.masked_fetch, &alone.lean_spans,
                                   &alone.exact_lanes, &alone.lean_geometry};
            *flags[path] = true;
            const RenderResult fast = render_scene(*s, nullptr, alone);
            CHECK(fast.image == plain.image);
            check_same_report(fast.report, plain.report);
        }
    }
}

// A stub of ch07-plan-mesh (no texture stage) leaves no affine pixel to count, so it
// grades that exercise.
TEST_CASE("the direct span's affine texels are the teaching path's" *
          doctest::description("points: 1; exercise: ch07-plan-mesh")) {
    // The big torus maps every triangle affine (auto); the direct span (lean_spans) then
    // steps u and v itself and takes each texel index with its span's rounding set up
    // once. Its texture coordinates moved and stretched (negative slopes: rule 2's
    // ceil; past 2^30 texels: the library's floor), some corners thrown far off screen
    // or next to another's (thin and empty triangles), affine forced by the scene or
    // chosen by auto, rounding on and off: the same pixels and counts as the teaching
    // path.
    const Scene torus = big_torus();
    std::mt19937_64 random(36);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    struct Stretch {
        double scale, offset;
    };
    int renders = 0;
    for (const Stretch stretch : {Stretch{1.0, 0.0}, Stretch{-3.75, 1000.5},
                                  Stretch{1e6, 2e9}, Stretch{-1e6, -2e9}}) {
        Scene scene = torus;
        SceneMesh& mesh = scene.meshes[0];
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
            for (std::size_t k = 0; k < 3; ++k) {
                TexCoord& uv = mesh.triangles[t][k].uv;
                uv = {uv.x * stretch.scale + stretch.offset,
                      uv.y * stretch.scale - stretch.offset};
            }
            if (t % 211 == 0) { // far off screen, in the view or out
                mesh.triangles[t][t % 3].position *= 1.0 + 40.0 * unit(random);
            } else if (t % 223 == 0) { // one corner next to another: a point on screen
                mesh.triangles[t][1].position =
                    mesh.triangles[t][0].position * (1 + 1e-9);
            } else if (t % 227 == 0) { // next to the middle of an edge: a line on screen
                mesh.triangles[t][2].position =
                    0.5 *
                    (mesh.triangles[t][0].position + mesh.triangles[t][1].position) *
                    (1 + 1e-9);
            }
        }
        share_positions(mesh);
        for (int variant = 0; variant < 4; ++variant) {
            Scene s = scene;
            s.options.rounding = variant % 2 == 0;
            if (variant >= 2) { // affine forced, every triangle
                s.options.mapper.automatic = false;
                s.options.mapper.mapper = {MapperKind::affine, 2};
            }
            INFO("stretch ", stretch.scale, ", variant ", variant);
            const RenderResult plain = render_scene(s, nullptr, teaching_path);
            FastPaths lean = teaching_path;
            lean.lean_spans = true;
            const RenderResult fast = render_scene(s, nullptr, lean);
            CHECK(fast.image == plain.image);
            check_same_report(fast.report, plain.report);
            const RenderResult all = render_scene(s);
            CHECK(all.image == plain.image);
            check_same_report(all.report, plain.report);
            // Most pixels affine on the whole triangle (auto, where the stretch leaves
            // the bound fitting), all where forced.
            const long long affine =
                plain.report.mappers[static_cast<std::size_t>(MapperKind::affine)].pixels;
            if (variant >= 2) {
                CHECK(affine == plain.report.texture.pixels);
            } else if (std::abs(stretch.scale) < 10.0) {
                CHECK(affine > plain.report.texture.pixels / 2);
            }
            renders += 1;
        }
    }
    CHECK(renders == 16);
}

TEST_CASE("any number of threads draws every shipped scene and the big torus as one") {
    const std::filesystem::path folder = shipped_scene_folder();
    int scenes = 0, renders = 0;
    for (const std::filesystem::path& path : exactpixels::testing::scene_files(folder)) {
        INFO(path.string());
        renders += check_threads_are_one(load_scene(path));
        scenes += 1;
    }
    CHECK(scenes >= 7);
    Scene narrow = load_scene(folder / "horizon.toml"); // corners far off screen
    narrow.camera.fov_degrees = 5.0;
    renders += check_threads_are_one(narrow);
    renders += check_threads_are_one(big_torus());
    MESSAGE((scenes + 2) << " scenes, " << renders << " threaded renders compared");
}

TEST_CASE("any number of threads draws triangles at the bands' edges as one") {
    // Orthographic, one world unit a pixel: each corner lands on screen where it is
    // placed. Each triangle's flat side lies at, or within 3/512 px of, the centre of the
    // last row of a band or the first row of the next (64 k -+ 1/2), its apex 3 px above
    // or below: the rows the bins' margins decide. A bin that misses the band of such a
    // row loses the triangle's pixels there.
    constexpr int width = 256, height = 256;
    std::string positions, uvs;
    int triangles = 0;
    for (const int edge : {64, 128, 192}) {
        for (const double centre : {edge - 0.5, edge + 0.5}) {
            for (int d = -3; d <= 3; ++d) {
                for (const double apex : {-3.0, 3.0}) {
                    const double x = 3.0 * triangles + 0.25, y = centre + d / 512.0;
                    const std::array<glm::dvec2, 3> corners = {
                        glm::dvec2{x, y}, glm::dvec2{x + 2.5, y},
                        glm::dvec2{x + 1.25, y + apex}};
                    for (std::size_t k = 0; k < 3; ++k) { // screen (px, py): world
                        positions += fmt::format(         // (px - w/2, h/2 - py, 1)
                            "[{}, {}, 1],", number(corners[k].x - 0.5 * width),
                            number(0.5 * height - corners[k].y));
                        uvs += fmt::format("[{}, {}],", 8 * k, 4 * triangles % 64);
                    }
                    triangles += 1;
                }
            }
        }
    }
    const Scene scene = parse_scene(
        fmt::format("[image]\nwidth = {}\nheight = {}\n[camera]\nprojection = "
                    "\"orthographic\"\nposition = [0, 0, 0]\ntarget = [0, 0, 1]\n"
                    "view_height = {}\n[render]\nmapper = \"auto\"\n"
                    "[textures.checks]\nkind = \"checkerboard\"\nsize = [64, 64]\n"
                    "square = 8\n[[mesh]]\nprimitive = \"triangles\"\n"
                    "texture = \"checks\"\npositions = [{}]\nuv = [{}]\n",
                    width, height, height, positions, uvs),
        "band_edges.toml", ".");
    const RenderResult one = render_scene(scene);
    REQUIRE(one.report.raster.triangles == triangles); // none culled or clipped
    REQUIRE(one.report.raster.pixels > 2 * triangles); // pixels in both bands' rows
    CHECK(check_threads_are_one(scene) == 12);
}

TEST_CASE("any number of threads runs the geometry stage as one") {
    const std::filesystem::path folder = shipped_scene_folder();
    int compared = 0;
    Scene all; // every shipped scene's meshes in one scene, seen by horizon's camera
    for (const std::filesystem::path& path : exactpixels::testing::scene_files(folder)) {
        INFO(path.string());
        const Scene scene = load_scene(path);
        compared += check_geometry_threads(scene);
        if (path.filename() == "horizon.toml") {
            const std::vector<SceneMesh> meshes = std::move(all.meshes);
            all = scene;
            all.meshes.insert(all.meshes.begin(), meshes.begin(), meshes.end());
        } else {
            all.meshes.insert(all.meshes.end(), scene.meshes.begin(), scene.meshes.end());
        }
    }
    for (SceneMesh& mesh : all.meshes) {
        mesh.texture.reset(); // the textures are horizon's
    }
    compared += check_geometry_threads(all);            // threads' stretches cross meshes
    Scene narrow = load_scene(folder / "horizon.toml"); // corners far off screen
    narrow.camera.fov_degrees = 5.0;
    compared += check_geometry_threads(narrow);
    compared += check_geometry_threads(big_torus());
    MESSAGE(compared << " threaded geometry runs compared");
}

TEST_CASE("any number of threads names the geometry stage's first error as one") {
    // Texture coordinates whose u/w leaves float on scattered triangles of the big
    // torus in float precision (a different index each): the first in scene order is
    // named whichever thread's stretch holds it, also when a thread before it and a
    // thread after it meet one too.
    const Scene torus = big_torus();
    const std::size_t count = torus.meshes.at(0).triangles.size();
    const auto poisoned = [&](const std::vector<std::size_t>& at) {
        Scene scene = torus;
        scene.options.precision = Precision::float32;
        for (std::size_t t : at) {
            scene.meshes[0].triangles[t][2].uv.x = 1e300;
        }
        share_positions(scene.meshes[0]); // the packed uv follow the changed corners
        return scene;
    };
    const std::vector<std::vector<std::size_t>> cases = {
        {count / 7, count / 3, count / 2, count - 1}, // in the first stretches
        {count - 1, count / 2 + 1, count / 2},        // the first in the second half
        {count / 3 + 1},                              // at the edge of a stretch
        {count - 3, count - 2},                       // in the last stretch only
    };
    for (const std::vector<std::size_t>& at : cases) {
        const Scene scene = poisoned(at);
        const std::string one = geometry_error(scene, 1);
        CHECK(one.find("not finite in float") != std::string::npos);
        for (int threads : checked_threads) {
            INFO(threads << " threads: " << one);
            CHECK(geometry_error(scene, threads) == one);
        }
    }
    // Two meshes: an error late in the first beats one early in the second.
    Scene two = poisoned({count - 5});
    two.meshes.push_back(poisoned({0, 1}).meshes[0]);
    const std::string one = geometry_error(two, 1);
    CHECK(one.find(fmt::format("triangle {}:", count - 5)) != std::string::npos);
    for (int threads : checked_threads) {
        INFO(threads << " threads");
        CHECK(geometry_error(two, threads) == one);
    }
    MESSAGE("one thread: " << one);
}

/// Runs the geometry stage's lean forms and its plain forms on the scene, unlit and lit,
/// in double and in float precision, and checks that the lists, footprints, counts and
/// any error message are the same, bit for bit. Returns the number of runs compared.
int check_lean_geometry(const Scene& unlit) {
    int compared = 0;
    for (const Precision precision : {Precision::float64, Precision::float32}) {
        for (const bool with_light : {false, true}) {
            Scene scene = unlit;
            scene.options.precision = precision;
            if (with_light) {
                scene.lights.push_back(SceneLight{});
            }
            INFO(std::string(with_light ? "lit, " : "unlit, ")
                 << (precision == Precision::float32 ? "float" : "double"));
            RenderReport lean_report, plain_report;
            std::optional<SceneGeometry> lean, plain;
            std::string lean_error, plain_error;
            try {
                lean = run_geometry(scene, lean_report, 1, true);
            } catch (const Error& error) {
                lean_error = error.what();
            }
            try {
                plain = run_geometry(scene, plain_report, 1, false);
            } catch (const Error& error) {
                plain_error = error.what();
            }
            CHECK(lean_error == plain_error);
            REQUIRE(lean.has_value() == plain.has_value());
            compared += 1;
            if (!lean) {
                continue;
            }
            REQUIRE(lean->meshes.size() == plain->meshes.size());
            for (std::size_t i = 0; i < plain->meshes.size(); ++i) {
                INFO("mesh " << i);
                CHECK(same_bits(lean->meshes[i], plain->meshes[i]));
                CHECK(same_bits(lean->shading[i], plain->shading[i]));
                const ScreenBox &a = lean->footprints[i].box,
                                b = plain->footprints[i].box;
                CHECK(std::memcmp(&a, &b, sizeof a) == 0);
            }
            check_same_report(lean_report, plain_report);
        }
    }
    return compared;
}

/// The scene with each corner position of its first mesh replaced, one in `every`, by
/// a hard one drawn by `random`: huge, tiny, zero, on the camera, behind it, at the
/// near plane, far off screen, not finite (positions past the loader's limits); and a
/// corner's texture coordinate, one in 7 `every`, by one whose u/w or v/w lies near
/// the largest float or double.
Scene with_hard_positions(Scene scene, std::mt19937& random, std::size_t every) {
    const CameraFrame frame = camera_frame(scene.camera);
    const double inf = std::numeric_limits<double>::infinity();
    const std::vector<double> values = {
        0.0,  -0.0,  1e-300, -1e-300, 1e-3,    -1e-3,    1.0, -1.0, 1e6,         -1e6,
        1e30, -1e30, 1e300,  -1e300,  1.7e308, -1.7e308, inf, -inf, std::nan("")};
    const auto pick = [&] {
        return values[std::uniform_int_distribution<std::size_t>(0, values.size() -
                                                                        1)(random)];
    };
    const std::vector<double> large_uvs = {1e37,  2e38,   -3e38, 5e38,   1e39,
                                           1e307, -5e307, 1e308, 1.7e308};
    SceneMesh& mesh = scene.meshes.at(0);
    std::size_t n = 0;
    for (auto& triangle : mesh.triangles) {
        for (SceneVertex& corner : triangle) {
            if (n % (7 * every) == 3) {
                const double uv = large_uvs[std::uniform_int_distribution<std::size_t>(
                    0, large_uvs.size() - 1)(random)];
                (n % 2 == 0 ? corner.uv.x : corner.uv.y) = uv;
            }
            if (n++ % every != 0) {
                continue;
            }
            switch (std::uniform_int_distribution<int>(0, 4)(random)) {
            case 0: // anywhere
                corner.position = {pick(), pick(), pick()};
                break;
            case 1: // along the view axis, behind or before the camera, or on it
                corner.position = frame.eye + pick() * frame.forward;
                break;
            case 2: // at the near plane, off to one side
                corner.position =
                    frame.eye + scene.camera.near * frame.forward + pick() * frame.right;
                break;
            case 3: // in front of the camera, far off screen
                corner.position = frame.eye + frame.forward + pick() * frame.up;
                break;
            default: // where another corner is: a degenerate triangle
                corner.position = triangle[0].position;
                break;
            }
        }
    }
    share_positions(mesh);
    return scene;
}

TEST_CASE("the geometry stage's lean forms give the plain forms' bits") {
    const std::filesystem::path folder = shipped_scene_folder();
    int compared = 0;
    std::mt19937 random(3434);
    for (const std::filesystem::path& path : exactpixels::testing::scene_files(folder)) {
        INFO(path.string());
        const Scene scene = load_scene(path);
        compared += check_lean_geometry(scene);
        for (const std::size_t every : {5, 23, 101}) {
            for (int k = 0; k < 4; ++k) {
                compared +=
                    check_lean_geometry(with_hard_positions(scene, random, every));
            }
        }
    }
    Scene narrow = load_scene(folder / "horizon.toml"); // corners far off screen
    narrow.camera.fov_degrees = 5.0;
    compared += check_lean_geometry(narrow);
    Scene cut = load_scene(folder / "corridor.toml"); // a far plane that cuts
    cut.camera.far = 0.5 * (cut.camera.near + 20.0);
    compared += check_lean_geometry(cut);
    const Scene torus = big_torus();
    compared += check_lean_geometry(torus);
    compared += check_lean_geometry(with_hard_positions(torus, random, 9973));
    // One corner's v/w just past the largest float, its neighbours' not (their 1/w
    // differ): each corner's test reads its own 1/w, in the corner's order.
    const CameraFrame frame = camera_frame(torus.camera);
    for (std::size_t t = 1000; t < 7000; t += 1001) {
        for (std::size_t k = 0; k < 3; ++k) {
            Scene poisoned = torus;
            SceneVertex& corner = poisoned.meshes[0].triangles[t][k];
            const double w = glm::dot(corner.position - frame.eye, frame.forward);
            corner.uv.y = double(std::numeric_limits<float>::max()) * w * (1.0 + 1e-9);
            share_positions(poisoned.meshes[0]); // and the packed uv
            compared += check_lean_geometry(poisoned);
        }
    }
    Scene behind = torus; // the camera inside the torus's ring: corners all around it
    behind.camera.position = {0.0, 0.0, 0.0};
    behind.camera.target = {1.0, 0.0, 0.0};
    compared += check_lean_geometry(behind);
    MESSAGE(compared << " geometry runs compared");
}

// A stub of ch07-plan-mesh (no stage runs) maps no texture coordinate, so no triangle is
// refused: the test grades that exercise.
TEST_CASE("project's message prints a NaN without its sign, which two exact paths may "
          "differ in") {
    // IEEE 754 leaves an operation's NaN's sign open; the lean and the plain geometry
    // meet such points on the hard-position variants of near_plane.toml.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const double x : {nan, std::copysign(nan, -1.0)}) {
        CHECK_THROWS_WITH_AS(project(Pinhole{}, {x, -x, 2.0}, {}),
                             "project: view-space point (nan, nan, 2) is not finite and "
                             "in front of the eye (z must be > 0)",
                             Error);
    }
    CHECK(std::signbit(unsigned_nan(-1.5)));
    CHECK(unsigned_nan(-0.0) == 0.0);
    CHECK(std::signbit(unsigned_nan(-0.0)));
}

TEST_CASE("any number of threads refuses a bad scene with the message of one" *
          doctest::description("points: 1; exercise: ch07-plan-mesh")) {
    // Texture coordinates past the mapper's limit on one triangle in every 499 of the
    // big torus, each a different value: one thread meets the first in scene order, and
    // every thread count names the same one, whichever band it lies in.
    Scene scene = big_torus();
    std::vector<std::array<SceneVertex, 3>>& triangles = scene.meshes[0].triangles;
    for (std::size_t t = 250; t < triangles.size(); t += 499) {
        triangles[t][1].uv.x = 1e31 * static_cast<double>(t);
    }
    share_positions(scene.meshes[0]); // the packed uv follow the changed corners
    const std::string one = render_error(scene, 1);
    CHECK(one.find("texture coordinate") != std::string::npos);
    for (int threads : checked_threads) {
        INFO(threads << " threads");
        CHECK(render_error(scene, threads) == one);
    }
    MESSAGE("one thread: " << one);
    // Trilinear, with every triangle bad: the threaded driver makes the mip chains
    // first, in scene order, and meets the first bad triangle there; it then leaves the
    // frame to the book's loop, which names the same error.
    scene.options.filter = SceneFilter::trilinear;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        triangles[t][2].uv.y = -1e31 * static_cast<double>(t + 1);
    }
    share_positions(scene.meshes[0]);
    const std::string filtered = render_error(scene, 1);
    CHECK(filtered.find("texture coordinate") != std::string::npos);
    for (int threads : checked_threads) {
        INFO(threads << " threads, trilinear");
        CHECK(render_error(scene, threads) == filtered);
    }
}

TEST_CASE("a bad thread count is refused before any work") {
    const Scene scene = load_scene(shipped_scene_folder() / "horizon.toml");
    for (int threads : {0, -1, max_threads + 1}) {
        FastPaths fast;
        fast.threads = threads;
        CHECK_THROWS_WITH_AS(
            render_scene(scene, nullptr, fast),
            fmt::format("thread count {} is outside 1 .. {}", threads, max_threads)
                .c_str(),
            Error);
    }
    const auto result = exactpixels::testing::run_command(
        exactpixels::testing::cli_path() + " render --threads 65 -o /dev/null");
    CHECK(result.exit_code == 2);
    CHECK(result.err == "exactpixels render: thread count 65 is outside 1 .. 64\n");
    CHECK(result.out.empty());
}

TEST_CASE("share_positions lists each distinct position once, bit for bit") {
    SceneMesh mesh;
    const auto vertex = [](double x, double y, double z) {
        SceneVertex v;
        v.position = {x, y, z};
        return v;
    };
    // Two triangles of a quad share two corners; 0 and -0 are different positions (a
    // sign of zero can survive into view space), and equal positions with different
    // texture coordinates are one position.
    SceneVertex uv_seam = vertex(1, 1, 0);
    uv_seam.uv = {5.0, 5.0};
    mesh.triangles = {{vertex(0, 0, 0), vertex(1, 0, 0), vertex(1, 1, 0)},
                      {vertex(0, 0, 0), uv_seam, vertex(0, 1, 0)},
                      {vertex(-0.0, 0, 0), vertex(1, 0, 0), vertex(0, 1, 0)}};
    share_positions(mesh);
    REQUIRE(mesh.corner_positions.size() == 3);
    CHECK(mesh.positions.size() == 5);
    CHECK(mesh.corner_positions[0] == std::array<std::uint32_t, 3>{0, 1, 2});
    CHECK(mesh.corner_positions[1] == std::array<std::uint32_t, 3>{0, 2, 3});
    CHECK(mesh.corner_positions[2] == std::array<std::uint32_t, 3>{4, 1, 3});
    const auto bits = [](const glm::dvec3& p) {
        return std::array<std::uint64_t, 3>{std::bit_cast<std::uint64_t>(p.x),
                                            std::bit_cast<std::uint64_t>(p.y),
                                            std::bit_cast<std::uint64_t>(p.z)};
    };
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        for (std::size_t k = 0; k < 3; ++k) {
            CHECK(bits(mesh.positions[mesh.corner_positions[t][k]]) ==
                  bits(mesh.triangles[t][k].position));
        }
    }
}

TEST_CASE("share_positions packs each corner's texture coordinate, and index_matches "
          "finds a corner changed after it") {
    // The loader's index of the torus, read back corner by corner.
    Scene scene = load_scene(shipped_scene_folder() / "torus.toml");
    SceneMesh& mesh = scene.meshes.at(0);
    REQUIRE(mesh.corner_uvs.size() == mesh.triangles.size());
    const auto bits = [](const TexCoord& uv) {
        return std::array<std::uint64_t, 2>{std::bit_cast<std::uint64_t>(uv.x),
                                            std::bit_cast<std::uint64_t>(uv.y)};
    };
    std::size_t differ = 0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        for (std::size_t k = 0; k < 3; ++k) {
            differ += bits(mesh.corner_uvs[t][k]) != bits(mesh.triangles[t][k].uv);
        }
    }
    CHECK(differ == 0);
    SharedPositions index{mesh.positions, mesh.corner_positions, mesh.corner_uvs};
    CHECK(index_matches(mesh.triangles, index));
    // A corner changed after sharing, and the index no longer holds: the geometry stage
    // would read the old uv (debug builds assert index_matches before each mesh).
    mesh.triangles[2][0].uv.x += 1.0;
    CHECK_FALSE(index_matches(mesh.triangles, index));
    index.uvs[2][0].x = mesh.triangles[2][0].uv.x;
    CHECK(index_matches(mesh.triangles, index));
    index.corners[0][0] = index.corners[0][1]; // another corner's position
    CHECK_FALSE(index_matches(mesh.triangles, index));
    index.corners[0][0] = static_cast<std::uint32_t>(index.positions.size()); // past it
    CHECK_FALSE(index_matches(mesh.triangles, index));
}

/// How many corners' normals differ, bit for bit, between mesh_normals and
/// mesh_normals_shared over the mesh's own index.
int normals_differing(const SceneMesh& mesh) {
    const std::vector<CornerNormals> plain = mesh_normals(mesh),
                                     shared = mesh_normals_shared(mesh, mesh.positions,
                                                                  mesh.corner_positions);
    REQUIRE(plain.size() == shared.size());
    int differ = 0;
    for (std::size_t t = 0; t < plain.size(); ++t) {
        differ += std::memcmp(&plain[t], &shared[t], sizeof plain[t]) != 0;
    }
    return differ;
}

TEST_CASE("smooth normals summed per shared position are mesh_normals's, bit for bit") {
    // lit.toml's smooth torus, and the big torus made smooth: no -0 in a position, so
    // the sums per position run (not the fallback).
    const Scene lit = load_scene(shipped_scene_folder() / "lit.toml");
    Scene big = big_torus();
    big.meshes.at(0).normals = NormalSource::smooth;
    int smooth_meshes = 0;
    for (const Scene* scene : std::array<const Scene*, 2>{&lit, &big}) {
        for (const SceneMesh& mesh : scene->meshes) {
            INFO(mesh.name);
            CHECK(normals_differing(mesh) == 0);
            if (mesh.normals != NormalSource::smooth) {
                continue;
            }
            smooth_meshes += 1;
            const auto negative_zero = [](double c) {
                return c == 0.0 && std::signbit(c);
            };
            for (const glm::dvec3& p : mesh.positions) {
                const bool any =
                    negative_zero(p.x) || negative_zero(p.y) || negative_zero(p.z);
                REQUIRE_FALSE(any);
            }
        }
    }
    CHECK(smooth_meshes == 2);
    // A corner at -0 and one at 0: two positions to the index, one to the map, whose
    // sum there holds both faces. The fallback keeps the map's normals.
    SceneMesh folded;
    folded.normals = NormalSource::smooth;
    const auto at = [](double x, double y, double z) {
        SceneVertex v;
        v.position = {x, y, z};
        return v;
    };
    folded.triangles = {{at(0.0, 0, 0), at(1, 0, 0), at(0, 1, 0)},
                        {at(-0.0, 0, 0), at(0, 1, 0), at(0, 0, 1)}};
    share_positions(folded);
    CHECK(folded.positions.size() == 5);
    CHECK(normals_differing(folded) == 0);
    const glm::dvec3 n = mesh_normals(folded)[0][0]; // both faces summed
    CHECK(n.x < 0.0);
    CHECK(n.z < 0.0);
}

TEST_CASE(
    "outcodes reject and clip as the view volume's planes on triangles at its edges") {
    for (const Scene& scene : edge_scenes()) {
        const bool perspective = scene.camera.projection == Projection::perspective;
        INFO(std::string(perspective ? "perspective" : "orthographic"));
        check_fast_is_teaching(scene);
        check_lean_geometry(scene); // corners on and around every plane
        // The counts the view volume's plane tests give, corner by corner, triangle by
        // triangle (outside_one, then any_outside), as chapter 6 states them.
        const CameraFrame frame = camera_frame(scene.camera);
        const ViewVolume volume = view_volume(scene, pinhole(scene));
        long long rejected = 0, cut = 0;
        for (const auto& triangle : scene.meshes.at(0).triangles) {
            std::array<ViewVertex, 3> view{};
            for (std::size_t k = 0; k < 3; ++k) {
                const glm::dvec3 d = triangle[k].position - frame.eye;
                view[k] = {{glm::dot(d, frame.right), glm::dot(d, frame.up),
                            glm::dot(d, frame.forward)},
                           triangle[k].uv};
            }
            if (outside_one(volume.reject, view)) {
                rejected += 1;
            } else if (any_outside(volume.clip, view)) {
                cut += 1;
            }
        }
        // The scene reaches every case: some triangles rejected, some cut, some drawn.
        const RenderReport report = render_scene(scene).report;
        CHECK(report.rejected.triangles == rejected);
        CHECK(report.clipping.triangles == cut);
        CHECK(report.rejected.triangles > 0);
        CHECK(report.clipping.triangles > 0);
        CHECK(report.raster.triangles > 1000);
        // Every stored corner is project_vertex's projection of its view-space point,
        // with 1/w (or -z) as the depth stage wants it: the stage projects each moved
        // position once, with project()'s arithmetic written out.
        // The unlit mesh keeps no view-space points (no stage reads them); lit, the
        // same triangles keep them, and the check reads them there.
        RenderReport geometry_report;
        const SceneGeometry geometry = run_geometry(scene, geometry_report);
        CHECK(geometry.shading.at(0).empty());
        Scene lit = scene;
        lit.lights.push_back(SceneLight{});
        RenderReport lit_report;
        const SceneGeometry lit_geometry = run_geometry(lit, lit_report);
        REQUIRE(lit_geometry.meshes.at(0).size() == geometry.meshes.at(0).size());
        REQUIRE(lit_geometry.shading.at(0).size() == geometry.meshes.at(0).size());
        const Pinhole lens = pinhole(scene);
        long long corners = 0, differ = 0;
        for (std::size_t i = 0; i < geometry.meshes.at(0).size(); ++i) {
            const ScreenTriangle& t = geometry.meshes.at(0)[i];
            const std::array<glm::dvec3, 3>& points =
                lit_geometry.shading.at(0)[i].points;
            for (std::size_t k = 0; k < 3; ++k) {
                const TexturedVertex p =
                    project_vertex(scene, lens, {points[k], t.corners[k].uv});
                const double nearness = perspective ? 1.0 / p.w : -points[k].z;
                corners += 1;
                differ += !(p.position == t.corners[k].position &&
                            p.w == t.corners[k].w && nearness == t.nearness[k]);
            }
        }
        CHECK(corners > 3000);
        CHECK(differ == 0);
    }
}

TEST_CASE(
    "any number of threads runs the geometry stage as one at the view volume's edges") {
    // Triangles rejected, cut and culled in every thread's stretch.
    int compared = 0;
    for (const Scene& scene : edge_scenes()) {
        compared += check_geometry_threads(scene);
    }
    CHECK(compared == 2 * 2 * static_cast<int>(checked_threads.size()));
}

TEST_CASE("fetch_texel_masked reads fetch_texel's texel on power-of-two textures") {
    for (const auto& [w, h] :
         {std::pair{1, 1}, std::pair{2, 8}, std::pair{64, 32}, std::pair{16, 16}}) {
        const Texture texture =
            checkerboard_texture(w, h, 1, rgba(1, 2, 3), rgba(9, 8, 7));
        std::vector<Rgba8> texels(texture.texels().size());
        for (std::size_t k = 0; k < texels.size(); ++k) { // every texel different
            texels[k] = rgba(static_cast<std::uint8_t>(k % 251),
                             static_cast<std::uint8_t>(k / 251 % 251), 17);
        }
        const Texture numbered(w, h, texels);
        REQUIRE(can_fetch_masked(numbered, Wrap::repeat));
        std::vector<int> indices;
        for (int i = -3 * 64; i <= 3 * 64; ++i) {
            indices.push_back(i);
        }
        for (const int i : {INT_MIN, INT_MIN + 1, INT_MAX - 1, INT_MAX}) {
            indices.push_back(i);
        }
        for (const int i : indices) {
            for (const int j :
                 {-65, -64, -33, -1, 0, 1, 31, 32, 63, 64, INT_MIN, INT_MAX, i}) {
                REQUIRE(fetch_texel_masked(numbered, i, j) ==
                        fetch_texel(numbered, i, j, Wrap::repeat));
            }
        }
        CHECK(!can_fetch_masked(texture, Wrap::clamp));
    }
    CHECK(!can_fetch_masked(checkerboard_texture(20, 28, 4), Wrap::repeat));
    CHECK(!can_fetch_masked(checkerboard_texture(64, 48, 4), Wrap::repeat));
    CHECK(!can_fetch_masked(checkerboard_texture(48, 64, 4), Wrap::repeat));
}

/// The same plane: corner, value and gradient, bit for bit.
void check_same_plane(const ScreenPlane& a, const ScreenPlane& b) {
    CHECK(a.origin == b.origin);
    CHECK(a.value == b.value);
    CHECK(a.g.dx == b.g.dx);
    CHECK(a.g.dy == b.g.dy);
}

/// A triangle mapped affine set up alone (affine_planes, choose_affine_rounding) gives
/// the u and v planes of chapter 3's full setup `planes` and chapter 4's affine rounding.
void check_affine_setup(const std::array<Point2, 3>& p,
                        const std::array<TexturedVertex, 3>& v,
                        const TexturePlanes& planes) {
    const auto [u, t] = affine_planes(p, v);
    check_same_plane(u, planes.u);
    check_same_plane(t, planes.v);
    const TexelRounding affine = choose_rounding(v, MapperKind::affine);
    const TexelRounding at_once = choose_affine_rounding(v);
    CHECK(at_once.u_modifier == affine.u_modifier);
    CHECK(at_once.v_modifier == affine.v_modifier);
}

/// The same double, bit for bit (0.0 and -0.0 differ).
bool same_bits(double a, double b) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

TEST_CASE("closed_form_gradients gives each value's closed_form_gradient, bit for bit") {
    // The renderer's setup takes two or three gradients over one triangle at once, in
    // vector lanes: each must be the one-value gradient's bits, on ordinary, huge and
    // tiny triangles, collinear and coincident corners, and values of any size.
    std::mt19937_64 random(34);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto number = [&](double scale) { // a signed value with a random exponent
        const double magnitude =
            std::ldexp(unit(random), static_cast<int>(unit(random) * 60.0) - 30);
        return (unit(random) < 0.5 ? -1.0 : 1.0) * std::min(magnitude, 1.0) * scale;
    };
    const auto snapped = [&](double scale) { // a corner on the 1/256 px grid
        return to_pixels(snap_to_subpixel(Point2{number(scale), number(scale)}));
    };
    int degenerate = 0;
    for (int n = 0; n < 50000; ++n) {
        const double scale = n % 3 == 0 ? 1048575.0 : n % 3 == 1 ? 1300.0 : 2.0;
        std::array<Point2, 3> p{snapped(scale), snapped(scale), snapped(scale)};
        if (n % 7 == 0) { // the third corner on the line through the first two
            p[2] = p[0] + (p[1] - p[0]) * 2.0;
        } else if (n % 11 == 0) {
            p[1] = p[0]; // two corners at one point
        } else if (n % 13 == 0) {
            p = {Point2{number(1e6), number(1e6)}, Point2{number(1.0), number(1e-3)},
                 Point2{number(1e-6), number(1e6)}}; // off the grid: rounding's corners
        }
        std::array<std::array<double, 3>, 3> c{};
        for (auto& value : c) {
            value = {number(1e3), number(1e3), number(1e3)};
        }
        const std::array<Gradient<double>, 3> three = closed_form_gradients<3>(p, c);
        const std::array<Gradient<double>, 2> two =
            closed_form_gradients<2>(p, {c[0], c[1]});
        for (std::size_t i = 0; i < 3; ++i) {
            const Gradient<double> alone = closed_form_gradient(p, c[i]);
            INFO(n, " value ", i);
            REQUIRE(same_bits(three[i].dx, alone.dx));
            REQUIRE(same_bits(three[i].dy, alone.dy));
            if (i < 2) {
                REQUIRE(same_bits(two[i].dx, alone.dx));
                REQUIRE(same_bits(two[i].dy, alone.dy));
            }
        }
        degenerate += closed_form_gradient(p, c[0]).dx == 0.0;
    }
    CHECK(degenerate > 5000); // the collinear and coincident corners were tried
}

TEST_CASE("texture planes and rounding from shared quotients are those of the corners") {
    // The renderer divides u, v and 1 by each corner's w once (corner_quotients) for the
    // texture's planes and chapter 4's rounding, and takes the depth stage's 1/w plane as
    // the texture's: each must be what dividing again and setting up every plane gives.
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> position(-40.0, 1320.0), depth(0.05, 400.0),
        coordinate(-300.0, 300.0);
    for (int n = 0; n < 20000; ++n) {
        std::array<TexturedVertex, 3> v{};
        std::array<Point2, 3> p{};
        std::array<double, 3> nearness{}; // as the geometry stage computes it
        for (std::size_t k = 0; k < 3; ++k) {
            v[k] = {{position(random), position(random)},
                    depth(random),
                    {coordinate(random), coordinate(random)}};
            p[k] = to_pixels(snap_to_subpixel(v[k].position));
            nearness[k] = 1.0 / v[k].w;
        }
        const CornerQuotients q = corner_quotients(v);
        for (std::size_t k = 0; k < 3; ++k) {
            REQUIRE(q.u_w[k] == v[k].uv.x / v[k].w);
            REQUIRE(q.v_w[k] == v[k].uv.y / v[k].w);
            REQUIRE(q.one_w[k] == nearness[k]);
        }
        const TexturePlanes shared = texture_planes(p, v, q, plane_through(p, nearness),
                                                    /*affine=*/true);
        check_same_plane(shared.u_w,
                         plane_through(p, {v[0].uv.x / v[0].w, v[1].uv.x / v[1].w,
                                           v[2].uv.x / v[2].w}));
        check_same_plane(shared.v_w,
                         plane_through(p, {v[0].uv.y / v[0].w, v[1].uv.y / v[1].w,
                                           v[2].uv.y / v[2].w}));
        check_same_plane(shared.one_w,
                         plane_through(p, {1.0 / v[0].w, 1.0 / v[1].w, 1.0 / v[2].w}));
        check_same_plane(shared.u, plane_through(p, {v[0].uv.x, v[1].uv.x, v[2].uv.x}));
        check_same_plane(shared.v, plane_through(p, {v[0].uv.y, v[1].uv.y, v[2].uv.y}));
        const TexelRounding alone = choose_rounding(v, MapperKind::exact);
        const TexelRounding from_q = choose_rounding(v, q);
        CHECK(from_q.u_modifier == alone.u_modifier);
        CHECK(from_q.v_modifier == alone.v_modifier);
        // A triangle mapped affine: its planes and rounding alone, gradients at once.
        check_affine_setup(p, v, shared);
    }
}

TEST_CASE("the affine setup at once is chapter 3's and 4's on flat and thin triangles") {
    // Collinear and coincident corners (no plane: zero gradients), a constant u or v
    // (zero gradient, rule from dy or the default), and huge values.
    std::mt19937_64 random(35);
    std::uniform_real_distribution<double> position(-1e6, 1e6), depth(0.05, 400.0),
        coordinate(-1e9, 1e9);
    int flat = 0;
    for (int n = 0; n < 20000; ++n) {
        std::array<TexturedVertex, 3> v{};
        for (std::size_t k = 0; k < 3; ++k) {
            v[k] = {{position(random), position(random)},
                    depth(random),
                    {coordinate(random), coordinate(random)}};
        }
        if (n % 3 == 0) {
            v[2].position = v[0].position + (v[1].position - v[0].position) * 0.5;
        } else if (n % 3 == 1) {
            v[1].position = v[0].position;
        }
        if (n % 4 == 0) {
            v[1].uv.x = v[2].uv.x = v[0].uv.x; // u constant
        }
        if (n % 5 == 0) {
            v[2].uv.y = v[0].uv.y; // v constant along one edge
        }
        std::array<Point2, 3> p{};
        for (std::size_t k = 0; k < 3; ++k) {
            p[k] = to_pixels(snap_to_subpixel(v[k].position));
        }
        INFO(n);
        const TexturePlanes planes = texture_planes(p, v);
        check_affine_setup(p, v, planes);
        flat += planes.u.g.dx == 0.0 && planes.u.g.dy == 0.0;
    }
    CHECK(flat > 10000);
}

TEST_CASE("the geometry stage stops a corner that is not finite, naming the triangle") {
    // The loader's limits keep u/w finite; a scene made in code need not. Under float
    // precision a texture coordinate of 1e45 texels gives u/w beyond the largest float at
    // every depth the horizon has: the stage's tests of the moved position and the
    // corner's uv fail and check_finite throws its message, naming the mesh and the
    // triangle, with every fast path and without.
    Scene scene = load_scene(shipped_scene_folder() / "horizon.toml");
    REQUIRE(scene.lights.empty());
    scene.options.precision = Precision::float32;
    SceneMesh& mesh = scene.meshes.at(0);
    const std::size_t first = mesh.triangles.size() / 2; // the ones before stay sane
    for (std::size_t t = first; t < mesh.triangles.size(); ++t) {
        mesh.triangles[t][1].uv = {1e45, 0.0};
    }
    share_positions(mesh); // the packed uv follow the changed corners
    const auto message = [&](FastPaths fast) {
        try {
            render_scene(scene, nullptr, fast);
        } catch (const Error& error) {
            return std::string(error.what());
        }
        return std::string("no error");
    };
    const std::string plain = message(teaching_path);
    INFO(plain);
    CHECK(plain.find("not finite in float") != std::string::npos);
    CHECK(plain.find(mesh.origin + ": triangle ") == 0);
    CHECK(message(FastPaths{}) == plain);
}
