// types.hpp: names for the values that flow through the book, by meaning.
//
// Usage:
//   Point2 p{3.5, 0.5};        // a point on screen, in pixels (x right, y down)
//   TexCoord t{0.25, 8.0};     // a texture coordinate, in texels
//   Colour c{1.0, 0.5, 0.0};   // RGB, each channel in [0, 1]: sRGB code / 255
//
// Conventions fixed for the whole book (chapter 0):
//   - the origin is the top-left corner of the frame, x grows right, y grows down;
//   - pixel (x, y) covers [x, x+1) x [y, y+1); its centre is (x + 0.5, y + 0.5);
//   - fixed-point screen coordinates carry 8 sub-pixel bits (units of 1/256 px).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>

/// Everything of the book's library lives in this namespace.
namespace exactpixels {

/// A point on screen in pixels, double precision: origin top-left, y down.
using Point2 = glm::dvec2;
/// A point on screen in pixels, single precision.
using Point2f = glm::vec2;
/// A texture coordinate in texels (u right, v down the texture).
using TexCoord = glm::dvec2;
/// An RGB colour, each channel in [0, 1]: an 8-bit sRGB code divided by 255 (the
/// book's one colour rule, chapter 8: filters decode to linear light to average).
using Colour = glm::dvec3;

/// Sub-pixel bits of fixed-point screen coordinates: 1 unit = 1/256 px.
inline constexpr int subpixel_bits = 8;
/// Fixed-point units per pixel (2^subpixel_bits).
inline constexpr int subpixel_scale = 1 << subpixel_bits;

//> pixel-centre
/// The centre of pixel (x, y): the point every coverage and interpolation test samples.
constexpr Point2 pixel_centre(int x, int y) {
    return {x + 0.5, y + 0.5};
}
//< pixel-centre

} // namespace exactpixels
