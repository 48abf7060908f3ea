// scene_renderer.hpp: drawing a loaded scene, running for each mesh only the stages it
// calls for, and counting what ran.
//
// Usage:
//   const Scene scene = load_scene("scenes/horizon.toml");
//   RenderResult result = render_scene(scene);
//   write_png("horizon.png", result.image);
//   std::fputs(format_report(result.report).c_str(), stdout);
//   TexelError e = check_against_exact(scene);   // worst and mean texel error
//
// Meshes are drawn in file order, each over the ones before; when meshes can overlap on
// screen (or the scene says `depth = true`) a depth stage keeps the nearest surface at
// each pixel, ties going to the later triangle (depth_buffer.hpp, plan_depth). Coverage
// is chapter 1's fixed-point scanline rasterizer (vertices snapped to 1/256 px, top-left
// rule); texture coordinates come from chapter 3's span mappers with chapter 4's
// rounding; vertex colours are interpolated linearly on screen or, as the scene asks,
// perspective-correct (c/w over 1/w). A scene with lights runs a lighting stage
// (lighting.hpp): per vertex (Gouraud, the lit colours go through the colour stage) or
// per pixel (Phong, after the texture and colour stages). Timings are wall clock seconds
// of a single run: the geometry stage and each mesh's drawing are timed whole, and a
// mesh's drawing time is shared among its stages as measured span by span on about 512
// of its triangles (timed_triangles_per_mesh: reading the clock per span would cost more
// than small spans do); counts are exact.
//
// The code is in one file per part of chapter 7: camera.hpp (the camera and the
// projection), geometry_stage.cpp (run_geometry), span_stages.cpp (drawing a mesh span by
// span), filter_stage.cpp (chapter 8's filters), render_report.cpp (the report and its
// clocks) and scene_renderer.cpp (render_scene, which runs them in order).
#pragma once

#include "exactpixels/base/framebuffer.hpp"
#include "exactpixels/raster/fill_work.hpp"
#include "exactpixels/scene/lighting.hpp"
#include "exactpixels/scene/render_report.hpp"
#include "exactpixels/scene/scene.hpp"
#include "exactpixels/scene/scene_pipeline.hpp"
#include "exactpixels/texture/texel_error.hpp"
#include "exactpixels/texture/texture_mapper.hpp"

#include <array>
#include <string>
#include <vector>

namespace exactpixels {

//> guard-band
/// Half the side of the guard band, px: a triangle whose corners all lie within
/// [-guard_band_px, guard_band_px] on both screen axes is drawn uncut; one reaching past
/// it is clipped in view space at the band's four planes. Half of chapter 2's exact
/// fixed-point range (max_fixed_coordinate_px = 2^20), so that a corner computed on a
/// band plane, off by rounding, is still far inside that range (@eq:scene-guard-band).
inline constexpr double guard_band_px = 524288.0; // 2^19
//< guard-band

//> fast-paths
/// The renderer's speed tricks: each a named fast variant beside a plain step of the
/// pipeline, giving the same pixels and the same report counts on every scene
/// (tests/ch07_fast_paths.cpp). All on by default; all off is the teaching path.
struct FastPaths {
    /// Texture: a power-of-two texture under `repeat` is read inline with the indices
    /// wrapped by a bit mask (fetch_texel_masked) instead of two integer remainders.
    bool masked_fetch = true;
    /// Drawing: for a mesh whose only stages are nearest texels (or its flat colour)
    /// and depth, the span loop calls the direct span (span_stages.cpp), which writes
    /// each visible pixel straight to the frame instead of shading a row of pixels that
    /// later stages would change.
    bool lean_spans = true;
    /// Texture: chapter 3's exact mapper in double divides 2, 4 or 8 pixels at once in
    /// the vector instruction set chosen_simd picks (map_span_exact_lanes) instead of
    /// one pixel at a time.
    bool exact_lanes = true;
    /// Geometry: the stage's lean forms (geometry_lanes.hpp: outcodes two planes at a
    /// time, an unshaded mesh's triangles tested and stored without copies, its uv read
    /// packed; smooth normals summed per shared position, mesh_normals_shared) instead
    /// of the plain ones the book shows.
    bool lean_geometry = true;
    /// Threads: with more than one, the geometry stage, the fill work and the binning
    /// are shared out among this many threads (from one to max_threads; a process-wide
    /// pool kept from frame to frame, run_on_shared_pool), and the threaded driver
    /// (scene_renderer.cpp) draws the bands of rows on them, each band's triangles in
    /// scene order: the same pixels, coordinates, counts and first error for any number.
    /// One is the book's loop, mesh by mesh.
    int threads = 1;
};

/// Every fast path off: the teaching path.
inline constexpr FastPaths teaching_path{false, false, false, false};
//< fast-paths

/// The stages a mesh runs in this scene: plan_mesh's, and under Gouraud lighting the
/// colour stage, which interpolates the lit colours (they hold the mesh's colour).
MeshStages mesh_stages(const Scene& scene, const SceneMesh& mesh);

/// A triangle after the geometry stage: moved to view space, clipped, projected, not
/// culled, with what every mesh's stages need at its corners.
struct ScreenTriangle {
    std::array<TexturedVertex, 3> corners; ///< pixels (not yet snapped), depth w, texels
    /// The depth stage's nearness: 1/w (perspective) or -z (orthographic).
    std::array<double, 3> nearness;
};

/// What the colour and lighting stages read at a triangle's corners, kept only for a
/// mesh that runs one of them (an unlit mesh without vertex colours writes none).
struct ShadedCorners {
    std::array<Colour, 3> colours;     ///< vertex colours; under Gouraud the lit colours
    std::array<glm::dvec3, 3> points;  ///< view space (used by Phong lighting)
    std::array<glm::dvec3, 3> normals; ///< view space (used by Phong lighting)
};

/// What the geometry stage hands the rest of the pipeline.
struct SceneGeometry {
    std::vector<std::vector<ScreenTriangle>> meshes; ///< per mesh, in file order
    /// Per mesh: the ShadedCorners of each of its triangles in `meshes` where the scene
    /// has lights or the mesh a colour stage, else none.
    std::vector<std::vector<ShadedCorners>> shading;
    std::vector<MeshFootprint> footprints; ///< per mesh, for the depth plan
    std::vector<ViewLight> lights;         ///< the lights in view space
};

/// The geometry stage alone, as render_scene runs it: each mesh as an indexed mesh,
/// every distinct position moved to view space, given its outcode and projected once;
/// every triangle rejected when its corners lie outside one plane of the view volume,
/// lit per vertex (Gouraud meshes), clipped when a corner is outside a clipping plane
/// (near, far, the guard band), and back-face culled (a triangle not clipped before it
/// is lit). Counts go to `report` (geometry, rejected, clipping, culling, lit_vertices,
/// the lighting fields). Throws Error naming the mesh when a corner projects to a value
/// that is not finite. With `threads` > 1 (1 .. max_threads) the positions and then the
/// triangles are split among that many threads (run_on_shared_pool) and each thread's
/// part joined in order: the same geometry, counts and first error for any number.
/// `lean` runs the stage's lean forms (geometry_lanes.hpp), which give the plain forms'
/// bits; false runs only the plain forms the book shows (tests compare the two).
SceneGeometry run_geometry(const Scene& scene, RenderReport& report, int threads = 1,
                           bool lean = true);

/// The fill work of each mesh of `geometry` (fill_work.hpp): the pixels of its
/// triangles' bounding boxes inside `image`. render_scene refuses a scene whose sum
/// exceeds max_fill_work before it draws anything.
std::vector<long long> fill_work(const SceneGeometry& geometry, Viewport image);

/// A rendered image and what it cost.
struct RenderResult {
    Framebuffer image;   ///< scene.width x scene.height
    RenderReport report; ///< what ran
};

/// Renders the scene. When `coordinates` is given (scene-sized), it records at every
/// pixel last written by a textured triangle the texel coordinate the mapper computed
/// (and the indices it picked); pixels written by untextured triangles are uncovered.
/// Throws Error naming the mesh (file, line, column, key path) when a triangle leaves
/// the range the rasterizer or the mapper can handle exactly, and, before drawing
/// anything, naming the mesh whose triangles take the scene's fill work past
/// max_fill_work. `fast` chooses the fast variants (FastPaths); pixels, coordinates and
/// counts are the same either way.
RenderResult render_scene(const Scene& scene, TexelMap* coordinates = nullptr,
                          FastPaths fast = {});

/// Throws Error naming `threads` unless it is a thread count render_scene takes, from
/// one to max_threads (worker_pool.hpp). render_scene checks it before any work.
void check_thread_count(int threads);

/// Bytes a TexelMap holds per pixel: the covered bit, the texel indices i and j, and the
/// coordinates u and v.
inline constexpr double texel_map_bytes_per_pixel =
    0.125 + 2.0 * sizeof(int) + 2.0 * sizeof(double);

/// The most memory `render --check` may take, bytes (1088 MiB), for the largest scene the
/// limits allow (scene_loader.hpp): the check holds two TexelMaps of max_image_pixels
/// (2 x 24.125 B x 2^24 = 772 MiB) beside the textures (max_scene_texture_bytes,
/// 128 MiB), the image being written (64 MiB) and the image of the render in progress
/// (64 MiB): 1028 MiB, plus 60 MiB for the program and the allocator. A second copy of
/// the textures (128 MiB) would break it. tests/ch07_limits.cpp measures the peak.
inline constexpr long long max_check_peak_bytes = 1088LL << 20;

/// Renders the scene as it asks and again with the exact mapper in double precision,
/// and measures the texel error of the first against the second. The scene is taken by
/// value and its options changed in place for the second render, so a caller that
/// moves its scene in keeps one copy of the textures, not two.
TexelError check_against_exact(Scene scene);

} // namespace exactpixels
