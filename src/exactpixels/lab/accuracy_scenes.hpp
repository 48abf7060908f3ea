// accuracy_scenes.hpp: chapter 5's fixed test bench: three scenes and the list of
// mapper configurations that are timed and scored on them.
//
// Usage:
//   for (const AccuracyScene& scene : accuracy_scenes())
//       for (const MapperConfig& mapper : accuracy_mappers()) {
//           Framebuffer frame(scene.width, scene.height);
//           draw_with(frame, scene, mapper);            // what the benchmark times
//       }
//
// Every scene is 320 x 240 pixels, its triangles given in screen space (pixels, origin
// top-left, y down) with w the view-space depth (> 0) and uv in texels, as
// texture_mapper.hpp expects. The scenes are built from fixed numbers and a fixed
// pseudo-random sequence (no std:: distributions), so they are the same on every
// platform and every run:
//   - "wall":  a wall facing the camera (w = 2 everywhere), 1/2 texel per pixel, its u
//              running right to left: every other pixel centre sits exactly on a texel
//              edge in u and in v, so the tie rule of chapter 4 decides half the texels;
//   - "floor": a floor from depth 1 to depth 28, one texel per unit, seen at a grazing
//              angle by a camera rolled by 80 degrees, so that the depth changes along
//              every row: the depth ratio across a row span ranges from 1.12 to 20.7;
//   - "field": 60 triangles of three sizes (about 4, 16 and 64 px across) with random
//              positions, depths in [1, 8] and texture scales.
#pragma once

#include "exactpixels/base/framebuffer.hpp"
#include "exactpixels/texture/texel_error.hpp"
#include "exactpixels/texture/texture.hpp"
#include "exactpixels/texture/texture_mapper.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace exactpixels {

/// A textured triangle list with its texture and frame size: one benchmark scene.
struct AccuracyScene {
    std::string name;                                     ///< "wall", "floor", "field"
    int width = 320;                                      ///< frame width, pixels
    int height = 240;                                     ///< frame height, pixels
    std::vector<std::array<TexturedVertex, 3>> triangles; ///< drawn in this order
    Texture texture;                                      ///< shared by all triangles
};

/// One mapper as the benchmark runs it: chapter 3's settings, and whether chapter 4's
/// rounding rule is chosen per triangle (the "rounding modifier") or rule 1 is kept.
struct MapperConfig {
    std::string name;             ///< short, unique, no commas: "subdivided:16 fixed"
    MapperSettings settings;      ///< kind, span, precision, wrap
    bool choose_rounding = false; ///< true: TexelRounding from choose_rounding()
};

/// The three scenes of chapter 5, in the order wall, floor, field.
std::vector<AccuracyScene> accuracy_scenes();

/// The facing wall alone (see the usage block).
AccuracyScene wall_facing_scene();
/// The grazing floor alone.
AccuracyScene grazing_floor_scene();
/// The random field alone.
AccuracyScene random_field_scene();

/// Every mapper configuration the chapter measures; the first is the affine mapper with
/// a 16.16 fixed-point inner loop, the baseline that time ratios are taken against.
std::vector<MapperConfig> accuracy_mappers();

/// The reference every error is measured against: the exact mapper in double with
/// chapter 4's rounding chosen per triangle.
MapperConfig reference_mapper();

/// The settings `mapper` uses for one triangle: its own, with the rounding replaced by
/// choose_rounding(triangle, kind) when mapper.choose_rounding is set.
MapperSettings settings_for(const MapperConfig& mapper,
                            const std::array<TexturedVertex, 3>& triangle);

/// Draws every triangle of the scene into `frame` (scene-sized) with the mapper.
void draw_with(Framebuffer& frame, const AccuracyScene& scene,
               const MapperConfig& mapper);

/// Records the texels the mapper picks for every triangle of the scene into `map`.
void map_with(TexelMap& map, const AccuracyScene& scene, const MapperConfig& mapper);

/// Maps the scene with the reference and with `mapper` and compares the two.
TexelError measure_mapper_error(const AccuracyScene& scene, const MapperConfig& mapper);

/// The benchmark's name for one run: "scene/mapper" with spaces as '_' and '+' dropped,
/// e.g. "floor/subdivided:16_fixed_rule".
std::string benchmark_name(const AccuracyScene& scene, const MapperConfig& mapper);

/// Pixel writes one drawing of the scene makes (overdraw counted): the "per pixel" of
/// every time and instruction count.
std::int64_t pixel_writes(const AccuracyScene& scene);

/// For every pixel (row-major), the depth ratio max(w) / min(w) across the row span of
/// the last triangle that covers it; 0 where no triangle does.
std::vector<double> span_ratio_map(const AccuracyScene& scene);

/// For every pixel (row-major), the larger depth w at the two ends of the row span of
/// the last triangle that covers it: how far that span reaches; 0 where no triangle does.
std::vector<double> span_far_depth_map(const AccuracyScene& scene);

/// The smallest and largest depth ratio max(w) / min(w) across the row spans of the
/// scene's triangles (spans of at least two pixels).
std::array<double, 2> span_depth_ratios(const AccuracyScene& scene);

/// The bands of span depth ratio, [low, high), that chapter 5's picks table splits the
/// floor into (figures/ch05_table.cpp; the test that explains the picks uses the same).
inline constexpr std::array<std::array<double, 2>, 4> picks_ratio_bands = {
    {{1.0, 2.0}, {2.0, 5.0}, {5.0, 10.0}, {10.0, 30.0}}};

} // namespace exactpixels
