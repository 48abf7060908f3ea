// level_of_detail.hpp: how many texels one pixel covers under perspective, and which mip
// level that asks for.
//
// Usage:
//   TexelDerivatives d = derivatives_at(triangle, Point2{160.5, 120.5});
//   double lambda = isotropic_level(d);        // log2 of the longer footprint side
//   Anisotropy a = anisotropy(d, 8);           // probes along the long side, its level
//   TexelDerivatives s = derivatives_per_span(triangle, 120, 40, 90); // once per span
//   double b = level_change_bound(triangle, Point2{65.5, 120.5}, Point2{40.5, 120.5});
//
// Conventions (chapters 1, 3, 4 and 8). Screen positions in pixels (origin top-left, y
// down), u and v in texels of level 0. Under perspective p = u/w, s = v/w and q = 1/w are
// linear on screen (chapter 3), with constant gradients over a triangle (chapter 1), so
// du/dx and du/dy follow from u = p / q by the quotient rule (@eq:derivatives), and the
// same for v with s; chapter 4's numerators (@eq:numerator) appear in them. A
// pixel maps to a parallelogram of texels spanned by (du/dx, dv/dx) and (du/dy, dv/dy);
// the isotropic level is lambda = log2 of the longer of the two sides (@eq:level). Level
// 0 is the full texture, lambda < 0 is magnification. The derivatives are defined
// wherever q > 0 (in front of the eye), which holds at every pixel a triangle covers.
#pragma once

#include "exactpixels/base/types.hpp"
#include "exactpixels/texture/rounding.hpp"
#include "exactpixels/texture/texture_mapper.hpp"

#include <array>

namespace exactpixels {

/// The screen derivatives of the texture coordinate at one pixel, in texels per pixel.
struct TexelDerivatives {
    double du_dx = 0.0; ///< change of u per pixel to the right
    double dv_dx = 0.0; ///< change of v per pixel to the right
    double du_dy = 0.0; ///< change of u per pixel down
    double dv_dy = 0.0; ///< change of v per pixel down
};

//> exact-derivatives
/// The derivatives of u = p / q and v = s / q at a point from the projected coordinates
/// there (@eq:derivatives). q must be nonzero.
inline TexelDerivatives exact_derivatives(const ProjectedCoordinate<double>& u,
                                          const ProjectedCoordinate<double>& v) {
    //> exercise ch08-derivatives: the quotient rule on u = p / q (@eq:derivatives).
    // du/dx is chapter 4's numerator over q^2.
    const double inv_q2 = 1.0 / (u.q * u.q);
    return {numerator_x(u) * inv_q2, numerator_x(v) * inv_q2, numerator_y(u) * inv_q2,
            numerator_y(v) * inv_q2};
    //| (void)u, (void)v;
    //| return {}; // stub: no derivatives, every pixel at level 0
    //< exercise ch08-derivatives
}
//< exact-derivatives

/// The exact derivatives of the triangle's perspective mapping at screen point `at`.
TexelDerivatives derivatives_at(const std::array<TexturedVertex, 3>& triangle, Point2 at);

/// The per-triangle approximation: the exact derivatives at the centroid, used for
/// every pixel of the triangle.
TexelDerivatives derivatives_per_triangle(const std::array<TexturedVertex, 3>& triangle);

/// The per-span approximation: the exact derivatives at the centre of the span's middle
/// pixel (or between its two middle pixels), used for every pixel of the span, which
/// covers the pixels x_first..x_last of row y.
TexelDerivatives derivatives_per_span(const std::array<TexturedVertex, 3>& triangle,
                                      int y, int x_first, int x_last);

/// A bound on |lambda(at) - lambda(from)| for the triangle's exact derivatives
/// (@eq:level-bound): 2 |log2(q(at) / q(from))| + log2 max(g+ / g, g / g-), with g the
/// longer numerator max(|N_x|, |N_y|) at `from` and g+-  = max(|N_x| +- |k| |dy|,
/// |N_y| +- |k| |dx|), k = (p_y q_x - p_x q_y, s_y q_x - s_x q_y) the numerators'
/// change per pixel (chapter 4). Infinity when g- <= 0 (no bound). Levels clamped at 0
/// obey it too.
double level_change_bound(const std::array<TexturedVertex, 3>& triangle, Point2 from,
                          Point2 at);

/// The footprint's two sides in texels: |(du/dx, dv/dx)| and |(du/dy, dv/dy)|.
std::array<double, 2> footprint_sides(const TexelDerivatives& d);

/// The isotropic level lambda = log2(max side) (@eq:level). A zero footprint gives a very
/// negative level (-1000), which every filter treats as magnification.
double isotropic_level(const TexelDerivatives& d);

/// The anisotropic plan: probes along the footprint's longer side and the level of each.
struct Anisotropy {
    int probes = 1;       ///< N, in [1, max_probes]
    double level = 0.0;   ///< log2(longer side / N), the level of each probe
    glm::dvec2 axis{0.0}; ///< the longer side (du, dv), texels; probes spread along it
};

/// N = min(ceil(longer / shorter), max_probes) probes along the longer side, each with
/// the level log2(longer / N) (@eq:anisotropy). max_probes >= 1.
Anisotropy anisotropy(const TexelDerivatives& d, int max_probes);

} // namespace exactpixels
