// fixed_point.hpp: screen coordinates snapped to 8 sub-pixel bits.
//
// Usage:
//   FixedPoint2 p = snap_to_subpixel({10.3, 4.0});  // {2637, 1024}: units of 1/256 px
//
// A fixed-point coordinate X stands for the real coordinate X / 256 in pixels (origin
// top-left, y down). Snapping rounds to the nearest 1/256 px, halves rounding up
// (towards +infinity), so a shift of the whole input by a multiple of 1/256 px never
// changes how it snaps. The rounding is exact (not floor(256 v + 0.5), whose sum can
// round up to the next integer), and a value that is not finite or too large for int64
// is refused with an Error, never converted. Chapter 2 derives the coordinate range for
// which rasterizing snapped triangles is exact (@eq:edge-range): |x|, |y| <=
// max_fixed_coordinate (2^28 units = 2^20 px = 1048576 px). check_pixel_range rejects
// anything outside with an Error naming the value, for every rasterizer; nothing is
// ever wrapped around.
#pragma once

#include "exactpixels/base/error.hpp"
#include "exactpixels/base/types.hpp"

#include <fmt/format.h>

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
/// The largest |v| in 1/256 px that snap_to_subpixel accepts: 2^62 units (2^54 px), so
/// its result always fits in int64 and a double is never converted out of range.
inline constexpr double max_snap_units = 0x1p62;

/// The nearest fixed-point value to v pixels (halves round up), computed exactly.
/// Throws Error naming v when v is not finite or |v| * 256 >= max_snap_units; the
/// rasterizers' own range (snap_in_range) is much smaller.
inline std::int64_t snap_to_subpixel(double v) {
    const double units = v * subpixel_scale;   // exact: a power of two, no overflow here
    if (!(std::abs(units) < max_snap_units)) { // false for NaN and infinity too
        throw Error(fmt::format("coordinate {} px cannot be snapped: not finite or "
                                "beyond 2^54 px",
                                v));
    }
    if (std::abs(units) >= 0x1p52) {
        return static_cast<std::int64_t>(units); // a double this large is an integer
    }
    const double below = std::floor(units); // exact
    // below + 1/2 is exact for |below| < 2^52, so this comparison is the exact test
    // "units - below >= 1/2", which units + 0.5 rounded to double is not.
    return static_cast<std::int64_t>(below) + (units >= below + 0.5 ? 1 : 0);
}

/// The nearest fixed-point point to p (each coordinate snapped on its own).
inline FixedPoint2 snap_to_subpixel(Point2 p) {
    return {snap_to_subpixel(p.x), snap_to_subpixel(p.y)};
}
//< snap

//> fixed-range
/// The largest |x| or |y| in 1/256 px for which the fixed-point rasterizers are exact:
/// 2^28 (2^20 px). Every edge function value is then below 2^60 in magnitude and the
/// sum of all three below 2^62, inside int64 (@eq:edge-range).
inline constexpr std::int64_t max_fixed_coordinate = std::int64_t{1} << 28;
/// max_fixed_coordinate in pixels: 1048576 px.
inline constexpr double max_fixed_coordinate_px =
    static_cast<double>(max_fixed_coordinate) / subpixel_scale;
//< fixed-range

/// Throws Error unless `value` (px) is finite and within +-max_fixed_coordinate_px: the
/// one check of chapter 2's exact range, and its one message.
inline void check_pixel_range(double value) {
    if (!(std::abs(value) <= max_fixed_coordinate_px)) { // false for NaN too
        throw Error(fmt::format("coordinate {} px is outside the exact range "
                                "[-1048576, 1048576]",
                                value));
    }
}

/// check_pixel_range for a fixed-point value (1/256 px), named in pixels: exact, as
/// value / 256 rounds only beyond 2^53 units, far outside the range either way.
inline void check_pixel_range(std::int64_t units) {
    check_pixel_range(static_cast<double>(units) / subpixel_scale);
}

/// Throws Error (check_pixel_range) unless |p.x| and |p.y| are at most
/// max_fixed_coordinate.
inline void check_fixed_range(FixedPoint2 p) {
    check_pixel_range(p.x);
    check_pixel_range(p.y);
}

/// snap_to_subpixel(p) after checking p (check_pixel_range): throws Error naming the
/// value when a coordinate is not finite or its magnitude exceeds
/// max_fixed_coordinate_px.
inline FixedPoint2 snap_in_range(Point2 p) {
    check_pixel_range(p.x);
    check_pixel_range(p.y);
    // snap_to_subpixel's rounding for |v| <= 2^20 px, its floor without a call: there
    // 256 v fits an int64, whose conversion truncates towards zero, one too high for a
    // negative fraction (every scene triangle's six snaps called floor: 4.7M
    // instructions of the big torus's frame).
    const auto snap = [](double v) {
        const double units = v * subpixel_scale; // exact, |units| <= 2^28
        const auto truncated = static_cast<std::int64_t>(units);
        const std::int64_t below =
            truncated - (static_cast<double>(truncated) > units ? 1 : 0); // floor
        // below + 1/2 is exact, so this is "units - below >= 1/2" exactly
        return below + (units >= static_cast<double>(below) + 0.5 ? 1 : 0);
    };
    return {snap(p.x), snap(p.y)};
}

/// The point in pixels that a fixed-point point stands for (exact in double).
inline Point2 to_pixels(FixedPoint2 p) {
    return {static_cast<double>(p.x) / subpixel_scale,
            static_cast<double>(p.y) / subpixel_scale};
}

} // namespace exactpixels
