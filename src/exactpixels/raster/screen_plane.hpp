// screen_plane.hpp: a value that is linear over the screen, set up once per triangle and
// read at any pixel centre.
//
// Usage:
//   std::array<Point2, 3> p{{{0.5, 0.5}, {8.5, 2.5}, {3.5, 6.5}}};   // pixels
//   ScreenPlane c = plane_through(p, {0.0, 1.0, 0.25});   // c at each corner
//   double at_centre = c.at(2.5, 3.5);                    // c at pixel (2, 3)
//   double step = c.g.dx;                                 // c per pixel to the right
//
// The plane holds c at the first corner and chapter 1's gradient (closed form, double),
// so c(x, y) = c0 + dc/dx (x - x0) + dc/dy (y - y0). Colours, 1/w, u/w and v/w, and the
// affine mapper's u and v are all such values.
#pragma once

#include "exactpixels/base/types.hpp"
#include "exactpixels/raster/gradients.hpp"

#include <array>

namespace exactpixels {

/// A value linear on screen: its value at a corner and its gradient.
struct ScreenPlane {
    Point2 origin;      ///< the corner where `value` holds, pixels
    double value = 0.0; ///< the value at `origin`
    Gradient<double> g; ///< its change per pixel right (dx) and down (dy)
    /// The value at the screen point (x, y), pixels.
    double at(double x, double y) const {
        return value + g.dx * (x - origin.x) + g.dy * (y - origin.y);
    }
};

/// The plane through the values c[k] at the corners p[k] (chapter 1's closed form).
inline ScreenPlane plane_through(const std::array<Point2, 3>& p,
                                 const std::array<double, 3>& c) {
    return {p[0], c[0], closed_form_gradient<double>(p, c)};
}

} // namespace exactpixels
