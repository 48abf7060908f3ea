// corner_quotients.hpp: the scene renderer's texture setup with one divide per quotient
// (chapter 7). Chapter 3's texture planes and chapter 4's rounding each divide u, v and
// 1 by every corner's w; the renderer divides once and hands both the quotients, takes
// the depth stage's 1/w plane as the texture's, and sets up the gradients each needs
// over one triangle at once (chapter 10).
//
// Usage:
//   const CornerQuotients q = corner_quotients(tv);
//   const TexturePlanes planes = texture_planes(p, tv, q, one_w, /*affine=*/false);
//   const TexelRounding r = choose_rounding(tv, q);
//   // the planes of texture_planes(p, tv, false), the rounding of choose_rounding(tv),
//   // value for value
//   const auto [du_w, dv_w] = closed_form_gradients<2>(p, {q.u_w, q.v_w});
//   // closed_form_gradient(p, q.u_w) and (p, q.v_w), bit for bit, set up at once
#pragma once

#include "exactpixels/raster/gradients.hpp"
#include "exactpixels/raster/screen_plane.hpp"
#include "exactpixels/texture/rounding.hpp"
#include "exactpixels/texture/texture_mapper.hpp"

#include <array>
#include <utility>

namespace exactpixels {

/// u/w, v/w and 1/w at each corner of a textured triangle, one divide each.
struct CornerQuotients {
    std::array<double, 3> u_w;   ///< u/w at corners 0, 1, 2
    std::array<double, 3> v_w;   ///< v/w at corners 0, 1, 2
    std::array<double, 3> one_w; ///< 1/w at corners 0, 1, 2
};

/// Chapter 1's closed_form_gradient(p, c[k]) of N <= 4 values over one triangle p at
/// once (the renderer's fast variant): the edges and the doubled area once, then every
/// value's two cross products and two divides side by side in vector lanes, each lane
/// the same IEEE operations in the same order as the one-value function, so each
/// gradient is its bits (zero area: {0, 0}).
template <std::size_t N>
std::array<Gradient<double>, N>
closed_form_gradients(const std::array<Point2, 3>& p,
                      const std::array<std::array<double, 3>, N>& c);

/// The quotients at the corners of `v`.
CornerQuotients corner_quotients(const std::array<TexturedVertex, 3>& v);

/// Chapter 3's texture_planes(corners, v, affine) from the quotients q =
/// corner_quotients(v) and the 1/w plane one_w = plane_through(corners, q.one_w), which
/// the depth stage has already: equal to it, value for value.
TexturePlanes texture_planes(const std::array<Point2, 3>& corners,
                             const std::array<TexturedVertex, 3>& v,
                             const CornerQuotients& q, const ScreenPlane& one_w,
                             bool affine);

/// The planes u and v of chapter 3's texture_planes(corners, v) (the affine mapper's),
/// value for value, their gradients set up at once.
std::pair<ScreenPlane, ScreenPlane> affine_planes(const std::array<Point2, 3>& corners,
                                                  const std::array<TexturedVertex, 3>& v);

/// Chapter 4's choose_rounding(v, MapperKind::affine), its two gradients set up at
/// once: the same rounding.
TexelRounding choose_affine_rounding(const std::array<TexturedVertex, 3>& v);

/// Chapter 4's choose_rounding(v) from the quotients q = corner_quotients(v): the same
/// rounding.
TexelRounding choose_rounding(const std::array<TexturedVertex, 3>& v,
                              const CornerQuotients& q);

} // namespace exactpixels
