// opengl_referee.hpp: a shipped scene drawn a second time by Mesa's llvmpipe (OSMesa),
// from the very triangles the renderer draws, and the two pictures compared.
//
// Usage (tests/referee_opengl.cpp, figures/ch09_referee.cpp; links OSMesa):
//   std::string why;
//   if (!opengl_referee_ready(why)) { /* skip, saying why */ }
//   const RefereeComparison c = referee_scene(load_scene(path), "boxes");
//   CHECK(c.coverage_differences.empty());
//
// Both sides start from run_geometry's ScreenTriangles with every corner snapped to
// 1/256 px (snap_in_range, as draw_triangle snaps). Ours: the renderer's image
// (render_scene) and an ID map drawn with the renderer's own pieces (scanline_spans,
// the nearness plane, DepthBuffer): the index of the triangle that wins each pixel.
// llvmpipe's: an ID pass (flat colour = triangle index + 1) and a colour pass (nearest
// texels, GL_MODULATE, vertex colours), glOrtho(0, W, H, 0) so that vertex (x, y) lands
// on our pixel (x, y), y down; clip coordinates (x w, y w, z w, w) so GL interpolates
// perspective-correctly; depth = the nearness mapped linearly (it is linear on screen)
// with GL_LEQUAL, so ties go to the later triangle as in DepthBuffer. Colours are
// compared against the scene rendered with the exact mapper in double and
// perspective-correct colours (what GL computes; the shipped mapper's own departure is
// chapter 7's texel error): unlit and Gouraud meshes with nearest texels drawn by GL's
// fixed pipeline, within referee_rounding_levels; meshes lit per pixel (Phong) drawn by
// a GLSL program that computes light_colour in single precision from the point and
// normal GL interpolates, within referee_lit_levels, after probe passes read those
// inputs back to bound what float costs. Filtered textures are not compared, and the
// comparison says so and counts their pixels: GL leaves anisotropic filtering to the
// implementation and approximates the level of detail from 2 x 2 pixel differences.
#pragma once

#include "exactpixels/base/framebuffer.hpp"
#include "exactpixels/scene/scene.hpp"
#include "exactpixels/scene/scene_renderer.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace exactpixels {

/// A pixel, named by its column and row (origin top-left).
struct RefereePixel {
    int x = 0; ///< column
    int y = 0; ///< row
};

/// Our colour tolerance, levels per channel, before the renderer's own colour bound:
/// ours rounds the exact value once (1/2 level); llvmpipe interpolates in float and
/// rounds to 8 bits (1/2 level) and multiplies texel by colour in 8-bit arithmetic
/// (1 level). The tolerance is their sum, 2 levels.
inline constexpr int referee_rounding_levels = 2;

/// Our colour tolerance, levels per channel, at pixels lit per pixel (Phong): each
/// side rounds one lit value to 8 bits (1/2 level each) and GL's single precision moves
/// that value by less than one level (RefereeComparison::worst_lit_float, checked), so
/// two integers that are less than 2 apart differ by at most 1 (@eq:scene-referee-lit).
inline constexpr int referee_lit_levels = 1;

/// A bound on the relative error GL's float arithmetic leaves in each term of the linear
/// light at a lit pixel, given the point and normal it interpolated. GLSL 4.50 computes
/// pow(f, s) as exp2(y), y = s log2 f: log2 within 2^-21 absolute on [0.5, 2] gives f^s
/// within s 2^-21 (ln 2 < 1); below 0.5, log2 within 3 units of 2^-24 relative and exp2
/// within 3 + 2|y| units give (3 + 5|y|) 2^-24, at most 80 2^-21 while f^s is a normal
/// float (|y| <= 126; smaller, it is far below a level). The sRGB curves' pow, the
/// float uniforms and the dozen other float operations are folded into 16 2^-21 more.
inline double referee_float_relative(double shininess) {
    return (shininess + 96.0) * std::ldexp(1.0, -21);
}

/// A pixel counts as on a texel edge when the renderer's texture coordinate there lies
/// within this many texels of a texel boundary (u or v): llvmpipe computes the
/// coordinate in float and may pick the neighbouring texel.
inline constexpr double referee_texel_edge = 1.0 / 64.0;

/// Two surfaces closer than this, as a fraction of the scene's nearness range, are a tie
/// to llvmpipe: it sets up and steps window depth in single precision, whose rounding
/// (2^-24 of the range per operation, a few operations per pixel) it cannot resolve
/// below about 2^-22; 2^-20 leaves a factor of 4.
inline constexpr double referee_depth_tie = 1.0 / (1 << 20);

/// The comparison of one scene.
struct RefereeComparison {
    std::string name;                ///< the scene
    int width = 0;                   ///< pixels
    int height = 0;                  ///< pixels
    long long triangles = 0;         ///< ScreenTriangles drawn
    bool depth_on = false;           ///< the renderer's depth stage ran (GL's did too)
    long long covered = 0;           ///< pixels ours covers
    bool image_matches_ids = true;   ///< every pixel render_scene drew is covered in ours
    long long exact_differences = 0; ///< ours vs the exact edge-function rasterizer
    std::vector<RefereePixel> coverage_differences; ///< background in one, not the other
    std::vector<RefereePixel> coverage_exact;       ///< of those, where ours = exact
    long long depth_differences = 0;        ///< covered in both, another triangle wins
    std::vector<RefereePixel> depth_pixels; ///< where they are
    /// The largest gap, at a depth difference, between the two triangles' nearness
    /// planes at the pixel centre, as a fraction of the scene's nearness range (the
    /// range GL's depth buffer spans)
    double worst_depth_gap = 0.0;
    /// At every depth difference ours is DepthBuffer's rule applied to the two
    /// triangles' planes: the nearer key wins, equal keys go to the later triangle
    bool depth_ours_right = true;
    long long colour_compared = 0; ///< pixels whose colours were compared
    long long lit_compared = 0;    ///< of those, lit per pixel (Phong)
    /// Compared pixels where the scene as shipped (its own mapper and colour choice)
    /// differs from llvmpipe beyond the tolerance
    long long shipped_differ = 0;
    int tolerance = 0; ///< levels (rounding + the renderer's colour bound)
    /// Compared pixels where the exact reference (exact mapper, double, perspective
    /// colours) and llvmpipe differ beyond the tolerance
    long long colour_over = 0;
    long long texel_edge = 0;   ///< of those, on a texel edge (referee_texel_edge)
    int worst_colour = 0;       ///< largest channel difference (exact reference)
    int worst_off_edge = 0;     ///< largest off texel edges
    int worst_lit_off_edge = 0; ///< largest off texel edges, lit per pixel
    /// The largest bound, over lit pixels off texel edges, on how far GL's single
    /// precision moves the lit value, levels: lit_float_levels in opengl_referee.cpp
    double worst_lit_float = 0.0;
    int phong_meshes = 0; ///< meshes the renderer lights per pixel
    /// Pixels covered by the same triangle in both whose colours were not compared
    long long colour_uncompared = 0;
    std::string uncompared;        ///< why they were not
    Framebuffer ours{1, 1};        ///< render_scene's image
    Framebuffer theirs{1, 1};      ///< llvmpipe's colour pass
    Framebuffer differences{1, 1}; ///< ours in grey, differences highlighted
};

/// The coverage of bare triangles, flat and without depth: ours against llvmpipe.
struct CoverageComparison {
    long long covered = 0;                 ///< pixels ours covers
    long long exact_differences = 0;       ///< ours vs the exact edge functions
    std::vector<RefereePixel> differences; ///< covered in one, not the other
    std::vector<RefereePixel> ours_exact;  ///< of those, where ours = exact
};

/// Draws `triangles` (corners in pixels, snapped as the renderer snaps them) into a
/// width x height frame both ways and compares coverage. Throws Error when OSMesa
/// cannot draw.
CoverageComparison referee_coverage(const std::vector<ScreenTriangle>& triangles,
                                    int width, int height);

/// The frame side, pixels, of the far-reaching triangles' test.
inline constexpr int far_frame = 64;

/// How many far-reaching triangles the test and the figure draw, one frame each.
inline constexpr int far_count = 200;

/// `count` triangles for a far_frame x far_frame frame, each with one corner inside it
/// and two up to 2^10 .. 2^19 px away (cycling), drawn from std::mt19937 seeded 17 (its
/// raw outputs are fixed by the standard, so every platform gets the same triangles).
std::vector<ScreenTriangle> far_reaching_triangles(int count);

/// True when OSMesa makes a context; otherwise false and `why` says what failed.
bool opengl_referee_ready(std::string& why);

/// A fault planted in llvmpipe's per-pixel lighting, for the test that shows the
/// comparison catches one (none by default).
struct RefereeFault {
    bool skip_decode = false;      ///< light the sRGB codes as if they were linear light
    double shininess_offset = 0.0; ///< added to every mesh's Blinn-Phong exponent
};

/// Renders `scene` both ways and compares (see the file comment), with `fault` planted
/// on llvmpipe's side. Throws Error when OSMesa cannot draw it.
RefereeComparison referee_scene(const Scene& scene, const std::string& name,
                                const RefereeFault& fault = {});

/// Every scene shipped with chapter 7 (the *.toml files of shipped_scene_folder(),
/// model scenes included), sorted by file name.
std::vector<std::string> referee_scene_names();

} // namespace exactpixels
