// perspective.hpp: a pinhole camera, just enough to make perspective test scenes.
//
// Usage:
//   Pinhole camera{.focal = 200.0, .centre = {160.0, 120.0}};
//   TexturedVertex v = project(camera, {-1.0, -1.0, 4.0}, {0.0, 0.0});
//
// View space: the eye at the origin looking along +z, x to the right, y up; z is the
// depth w of chapter 3 and must be > 0 (no clipping here: scenes keep every vertex in
// front of the eye). A point (x, y, z) lands on screen at
//   (centre.x + focal * x / z, centre.y - focal * y / z)     (pixels, y down)
// so a view-space line is a screen line, and its depth along the screen line is what
// makes u non-linear on screen (@eq:projection).
#pragma once

#include "exactpixels/base/types.hpp"
#include "exactpixels/texture/texture_mapper.hpp"

#include <glm/glm.hpp>

namespace exactpixels {

/// A pinhole camera: focal length and the screen point straight ahead, in pixels.
struct Pinhole {
    double focal = 200.0;           ///< pixels per unit of x / z
    Point2 centre = {160.0, 120.0}; ///< where the view axis meets the screen, pixels
};

/// A view-space point with its texture coordinate, projected to a TexturedVertex:
/// screen position in pixels, w = z. Throws Error unless z > 0 and all are finite.
TexturedVertex project(const Pinhole& camera, glm::dvec3 view_point, TexCoord uv);

} // namespace exactpixels
