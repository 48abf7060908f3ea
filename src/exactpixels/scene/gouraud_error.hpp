// gouraud_error.hpp: how far Gouraud colours (linear on screen) are from perspective-
// correct colours in a scene.
//
// Usage:
//   const Scene scene = load_scene("chapters/07-scenes/scenes/gouraud.toml");
//   GouraudError e = gouraud_perspective_error(scene); // e.worst: colour units in [0, 1]
//
// The renderer interpolates vertex colours linearly on screen (chapter 7). The colour a
// perspective camera would see is linear on the surface: c/w and 1/w are linear on
// screen and c = (c/w) / (1/w), exactly as for texture coordinates (chapter 3,
// eq:linear-in-screen). The difference is the affine mapper's error with the colour
// channel in place of u. It is measured that way: each vertex-coloured mesh is drawn with
// one channel as its u, once by the affine mapper (what the colour stage computes) and
// once by the exact mapper, in double, and the two coordinate maps are compared over the
// pixels of vertex-coloured meshes that remain visible. Colour units: 1 is the full range
// of a channel (255 levels of an 8-bit image).
#pragma once

#include "exactpixels/scene/scene.hpp"

namespace exactpixels {

/// The error of screen-linear (Gouraud) colours against perspective-correct colours.
struct GouraudError {
    double worst = 0.0;   ///< the largest difference in any channel, colour units
    double mean = 0.0;    ///< the mean over pixels and channels, colour units
    long long pixels = 0; ///< visible pixels of vertex-coloured meshes compared
};

/// Measures the Gouraud colours of `scene` against perspective-correct ones (see above).
/// A scene without vertex colours gives zero pixels. Throws Error as render_scene does.
GouraudError gouraud_perspective_error(const Scene& scene);

} // namespace exactpixels
