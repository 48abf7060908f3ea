// texture_mapper.hpp: textured triangles, drawn by one of chapter 3's mappers.
//
// Usage:
//   std::array<TexturedVertex, 3> tri{{{{10.0, 5.0}, 1.0, {0.0, 0.0}},
//                                      {{90.0, 5.0}, 4.0, {64.0, 0.0}},
//                                      {{10.0, 60.0}, 1.0, {0.0, 64.0}}}};
//   MapperSettings quad{.mapper = {MapperKind::quadratic}};
//   draw_textured_triangle(frame, tri, checkerboard_texture(64, 64, 8), quad);
//
// Units: positions in pixels (origin top-left, y down, pixel centres at x + 0.5), w the
// view-space depth of the vertex (w > 0, any unit; only ratios of w matter), uv in
// texels (texel (i, j) covers [i, i+1) x [j, j+1), see texture.hpp). Coverage is
// chapter 1's fixed-point scanline rasterizer: vertices are snapped to 1/256 px and the
// top-left rule decides pixels on edges, so every mapper covers the same pixels as
// chapter 2's edge-function rasterizer; the mappers differ only in the texel they pick.
//
// The mappers (chapter 3): u/w, v/w and 1/w are linear in screen space (chapter 3,
// @eq:linear-in-screen), so
//   - exact divides u/w by 1/w at every pixel;
//   - affine interpolates u and v themselves (wrong under perspective);
//   - subdivided is exact every `span` pixels and affine in between;
//   - quadratic fits Pursey's parabola through the exact values at both ends and the
//     middle of each row's span, stepped by forward differences;
//   - quadratic_subdivided does the same on pieces of `span` pixels.
// Precision picks the inner loop's arithmetic: float, double, or fixed point with
// texel coordinates held as 16.16 (U = u * 2^16); the fixed loops take the texel index
// floor((U + modifier - 2^15) / 2^16) with the modifier of TexelRounding.
#pragma once

#include "exactpixels/base/floor_to_int.hpp"
#include "exactpixels/base/framebuffer.hpp"
#include "exactpixels/base/types.hpp"
#include "exactpixels/raster/screen_plane.hpp"
#include "exactpixels/raster/span.hpp"
#include "exactpixels/texture/mapper.hpp"
#include "exactpixels/texture/span_mappers.hpp"
#include "exactpixels/texture/texture.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace exactpixels {

/// One corner of a textured triangle.
struct TexturedVertex {
    Point2 position; ///< screen position in pixels
    double w;        ///< view-space depth, > 0
    TexCoord uv;     ///< texture coordinate in texels
};

/// Fixed-point texel coordinates: 16 fraction bits, D = 2^16 units per texel.
inline constexpr int texel_fraction_bits = 16;
/// Units of a 16.16 texel coordinate per texel (D).
inline constexpr std::int32_t texel_scale = std::int32_t{1} << texel_fraction_bits;

/// How a fixed-point inner loop turns U = u * D into a texel index:
/// floor((U + modifier - D/2) / D). modifier = D/2 gives floor(u) (rule 1); chapter 4's
/// rounding_modifier gives the modifier of ceil(u) - 1 (rule 2). Default: rule 1 in both
/// directions. Chapter 4 picks it.
struct TexelRounding {
    std::int32_t u_modifier = 1 << 15; ///< modifier added to U before the floor division
    std::int32_t v_modifier = 1 << 15; ///< modifier added to V before the floor division
};

/// A rounding chosen for each pixel row: given the triangle and the height y of the row's
/// pixel centres, the TexelRounding for that row. Chapter 4 supplies one,
/// choose_rounding_on_row.
using RowRounding = TexelRounding (*)(const std::array<TexturedVertex, 3>& v, double y);

/// Everything that chooses how a textured triangle is drawn.
struct MapperSettings {
    Mapper mapper = {};                       ///< which mapper (kind, piece length)
    Precision precision = Precision::float64; ///< inner-loop arithmetic
    TexelRounding rounding = {};              ///< texel index rounding (all precisions)
    Wrap wrap = Wrap::repeat;                 ///< how indices outside the texture wrap
    /// When set, the rounding of every row comes from it instead of `rounding`: under
    /// perspective the sign of du/dx or dv/dx can change from row to row, and chapter 4's
    /// choose_rounding_on_row picks each row's rule from its own BC - AD numerators.
    RowRounding row_rounding = nullptr;
};

/// The texel index a mapper picks from a 16.16 coordinate U:
/// floor((U + modifier - D/2) / D).
constexpr int fixed_texel_index(std::int32_t U, std::int32_t modifier) {
    const std::int64_t shifted = std::int64_t{U} + modifier - texel_scale / 2;
    return static_cast<int>(shifted >> texel_fraction_bits); // >> floors (C++20)
}

/// The texel index for a real coordinate u under one modifier, with the modifier's part
/// worked out once: floor(u) for modifier = D/2, ceil(u) - 1 for rule 2's modifier.
/// Agrees with fixed_texel_index(u * D, modifier) whenever u * D is an integer. Within
/// |u| < 2^30 it rounds with floor_to_int and ceil_to_int (base/floor_to_int.hpp), which
/// are exact and need no call into the maths library; beyond, std::floor and std::ceil,
/// held to int's range.
class RealTexelIndex {
  public:
    /// The rule for `modifier` (chapter 4's u_modifier or v_modifier).
    explicit RealTexelIndex(std::int32_t modifier)
        : floor_(modifier >= texel_scale / 2),
          // b' = modifier - D/2 in floor((U + b') / D); for integer U that floor is
          // ceil((U + b' + 1) / D) - 1, which with rule 2's modifier is ceil(u) - 1.
          bias_(double(floor_ ? modifier - texel_scale / 2
                              : modifier - texel_scale / 2 + 1) /
                texel_scale) {}
    /// The texel index of coordinate u (texels), held to int's range.
    int operator()(double u) const {
        const bool small = std::abs(u) < 0x1p30; // false for NaN too
        const double x = u + bias_;
        if (floor_) {
            return small ? floor_to_int(x) : saturated_int(std::floor(x));
        }
        return small ? ceil_to_int(x) - 1 : saturated_int(std::ceil(x) - 1.0);
    }

  private:
    bool floor_;  ///< floor(u + bias), else ceil(u + bias) - 1
    double bias_; ///< the modifier's offset in texels
};

/// RealTexelIndex(modifier)(u): every real mapper calls it for every pixel, twice.
/// Always inlined: where a file instantiates the mappers twice (chapter 7's renderer
/// with its lean drawing path), GCC otherwise calls it, two calls per pixel.
[[gnu::always_inline]] inline int real_texel_index(double u, std::int32_t modifier) {
    return RealTexelIndex(modifier)(u);
}

/// The texel indices a mapper chose for each pixel of a frame (before wrapping).
struct TexelMap {
    /// An empty map of width x height pixels (no pixel covered).
    TexelMap(int width, int height);
    int width;                 ///< columns
    int height;                ///< rows
    std::vector<bool> covered; ///< true where a triangle wrote the pixel (row-major)
    std::vector<int> i;        ///< texel column chosen at each covered pixel
    std::vector<int> j;        ///< texel row chosen at each covered pixel
    std::vector<double> u;     ///< the u the mapper computed there, texels (fixed: U / D)
    std::vector<double> v;     ///< the v the mapper computed there, texels (fixed: V / D)
};

/// The bound on |u| and |v| (texels, exclusive) that check_textured_triangle sets in
/// `precision`: 2^14 for fixed point, where U = u D must fit, else 1e30.
inline double texture_coordinate_limit(Precision precision) {
    return precision == Precision::fixed ? 16384.0 : 1e30;
}

/// Checks the triangle and settings: finite positions within chapter 2's fixed-point
/// range, w > 0 and finite, finite uv (|u|, |v| < 2^14 for Precision::fixed), span in
/// [2, 4096]. Throws Error naming the offending value; returns when all is well.
void check_textured_triangle(const std::array<TexturedVertex, 3>& v,
                             const MapperSettings& settings);

/// Records, for every pixel the triangle covers inside the map, the texel indices the
/// mapper chose. Checks its input first (Error, nothing written).
void map_textured_triangle(TexelMap& target, const std::array<TexturedVertex, 3>& v,
                           const MapperSettings& settings);

/// The screen-linear values of a textured triangle that chapter 3's mappers step: u/w,
/// v/w and 1/w (linear on screen, @eq:linear-in-screen) and, for the affine mapper, u and
/// v themselves. Set up once per triangle through its snapped corners.
struct TexturePlanes {
    ScreenPlane u_w;   ///< u/w
    ScreenPlane v_w;   ///< v/w
    ScreenPlane one_w; ///< 1/w
    ScreenPlane u;     ///< u (affine mapper)
    ScreenPlane v;     ///< v (affine mapper)
};

/// The planes of the triangle whose corners, snapped to 1/256 px, are at `corners`.
/// Without `affine` the planes u and v are left zero: a caller whose spans never run
/// the affine mapper need not set them up.
TexturePlanes texture_planes(const std::array<Point2, 3>& corners,
                             const std::array<TexturedVertex, 3>& v, bool affine = true);

/// One row span's setup for the perspective mappers: the planes at the first pixel's
/// centre (x_begin + 0.5, y + 0.5) and their steps per pixel. (Inline: the scene
/// renderer sets one up per span.)
inline PerspectiveSpan<double> perspective_span(const TexturePlanes& planes, Span s) {
    const double x = s.x_begin + 0.5, y = s.y + 0.5; // the first pixel's centre
    return {planes.u_w.at(x, y), planes.v_w.at(x, y), planes.one_w.at(x, y),
            planes.u_w.g.dx,     planes.v_w.g.dx,     planes.one_w.g.dx,
            s.x_end - s.x_begin};
}

/// The same for the affine mapper.
inline AffineSpan<double> affine_span(const TexturePlanes& planes, Span s) {
    const double x = s.x_begin + 0.5, y = s.y + 0.5;
    return {planes.u.at(x, y), planes.v.at(x, y), planes.u.g.dx, planes.v.g.dx,
            s.x_end - s.x_begin};
}

/// Runs `mapper` on one span in the inner-loop arithmetic `precision` and calls
/// texel(k, i, j, u, v) for its pixel k = 0, 1, ...: the texel indices picked with the
/// rounding `r` (before wrapping) and the coordinate computed there, texels. The one
/// dispatch from a mapper to chapter 3's span loops, for the textured triangle below
/// and for the scene renderer.
template <class TexelFn>
void map_span(Mapper mapper, Precision precision, TexelRounding r,
              const PerspectiveSpan<double>& ps, const AffineSpan<double>& as,
              TexelFn&& texel) {
    const auto real = [&](int k, auto u, auto v) {
        texel(k, real_texel_index(u, r.u_modifier), real_texel_index(v, r.v_modifier),
              double(u), double(v));
    };
    const auto fixed = [&](int k, std::int32_t U, std::int32_t V) {
        texel(k, fixed_texel_index(U, r.u_modifier), fixed_texel_index(V, r.v_modifier),
              double(U) / texel_scale, double(V) / texel_scale);
    };
    const auto run = [&](const auto& p, const auto& a, auto&& emit) {
        switch (mapper.kind) {
        case MapperKind::exact:
            return map_span_exact(p, emit);
        case MapperKind::affine:
            return map_span_affine(a, emit);
        case MapperKind::subdivided:
            return map_span_subdivided(p, mapper.piece, emit);
        case MapperKind::quadratic:
            return map_span_quadratic(p, emit);
        case MapperKind::quadratic_subdivided:
            return map_span_quadratic_subdivided(p, mapper.piece, emit);
        }
    };
    switch (precision) {
    case Precision::float32:
        return run(converted<float>(ps), converted<float>(as), real);
    case Precision::float64:
        return run(ps, as, real);
    case Precision::fixed:
        switch (mapper.kind) {
        case MapperKind::exact:
            return map_span_exact_fixed(ps, fixed);
        case MapperKind::affine:
            return map_span_affine_fixed(as, fixed);
        case MapperKind::subdivided:
            return map_span_subdivided_fixed(ps, mapper.piece, fixed);
        case MapperKind::quadratic:
            return map_span_quadratic_fixed(ps, fixed);
        case MapperKind::quadratic_subdivided:
            return map_span_quadratic_subdivided_fixed(ps, mapper.piece, fixed);
        }
    }
}

/// Draws the triangle into `target`, each covered pixel taking the colour of the texel
/// the mapper picks (wrapped by settings.wrap). Checks its input first: on Error nothing
/// is drawn.
void draw_textured_triangle(Framebuffer& target, const std::array<TexturedVertex, 3>& v,
                            const Texture& texture, const MapperSettings& settings);

} // namespace exactpixels
