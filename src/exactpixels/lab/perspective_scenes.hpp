// perspective_scenes.hpp: chapter 3's two test scenes, a floor and a grazing wall.
//
// Usage:
//   const PerspectiveScene floor = floor_scene(320, 240);
//   Framebuffer frame(320, 240, rgba(0, 0, 0));
//   draw_scene(frame, floor, MapperSettings{.mapper = {MapperKind::affine}});
//
// Both scenes are seen through a pinhole camera (perspective.hpp) whose focal length is
// 0.625 times the frame width, looking at the frame's centre. The floor is a plane one
// unit below the eye running from depth 1.2 to depth 40 (depth ratio 33 along its long
// edges), seen with the camera banked by 20 degrees (a level camera sees the floor at one
// depth along each row, where every span mapper is exact), textured with a 64 x 64
// checkerboard of 8-texel squares, 16 texels per unit. The wall stands 1.5 units to the
// right of the eye from depth 1 to depth 60 and is seen almost edge-on, textured with the
// "F" (4 texels per glyph cell), repeated. Each is two triangles, so that a row span
// crosses the whole surface.
#pragma once

#include "exactpixels/base/framebuffer.hpp"
#include "exactpixels/texture/texture.hpp"
#include "exactpixels/texture/texture_mapper.hpp"

#include <array>
#include <vector>

namespace exactpixels {

/// Textured triangles with their texture: everything a mapper needs to draw a scene.
struct PerspectiveScene {
    std::vector<std::array<TexturedVertex, 3>> triangles; ///< screen space, w = depth
    Texture texture;                                      ///< shared by all triangles
    Wrap wrap = Wrap::repeat;                             ///< how the texture repeats
};

/// The perspective floor for a width x height frame (both >= 1).
PerspectiveScene floor_scene(int width, int height);

/// The wall at a grazing angle for a width x height frame (both >= 1).
PerspectiveScene wall_scene(int width, int height);

/// Draws every triangle of the scene with `settings` (its wrap replaced by the scene's).
void draw_scene(Framebuffer& frame, const PerspectiveScene& scene,
                MapperSettings settings);

/// Records the texels every triangle of the scene picks (see map_textured_triangle).
void map_scene(TexelMap& map, const PerspectiveScene& scene,
               const MapperSettings& settings);

} // namespace exactpixels
