// fixed_point.hpp: screen coordinates snapped to 8 sub-pixel bits.
//
// Usage:
//   FixedPoint2 p = snap_to_subpixel({10.3, 4.0});  // {2637, 1024}: units of 1/256 px
//
// A fixed-point coordinate X stands for the real coordinate X / 256 in pixels (origin
// top-left, y down). Snapping rounds to the nearest 1/256 px, halves rounding up
// (towards +infinity), so a shift of the whole input by a multiple of 1/256 px never
// changes how it snaps. Chapter 2 derives the coordinate range for which rasterizing
// snapped triangles is exact and checks input against it.
#pragma once

#include "exactpixels/types.hpp"

#include <cmath>
#include <cstdint>

namespace exactpixels {

/// A screen point in fixed point: x and y in units of 1/256 px (subpixel_scale).
struct FixedPoint2 {
    std::int64_t x = 0; ///< x in 1/256 px
    std::int64_t y = 0; ///< y in 1/256 px
    /// Points are equal when both coordinates are.
    friend constexpr bool operator==(FixedPoint2, FixedPoint2) = default;
};

//> snap
/// The nearest fixed-point value to v pixels (halves round up). v must be finite and
/// within the range chapter 2 documents; callers check it first.
inline std::int64_t snap_to_subpixel(double v) {
    return static_cast<std::int64_t>(std::floor(v * subpixel_scale + 0.5));
}

/// The nearest fixed-point point to p (each coordinate snapped on its own).
inline FixedPoint2 snap_to_subpixel(Point2 p) {
    return {snap_to_subpixel(p.x), snap_to_subpixel(p.y)};
}
//< snap

/// The point in pixels that a fixed-point point stands for (exact in double).
inline Point2 to_pixels(FixedPoint2 p) {
    return {static_cast<double>(p.x) / subpixel_scale,
            static_cast<double>(p.y) / subpixel_scale};
}

} // namespace exactpixels
