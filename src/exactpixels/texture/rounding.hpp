// rounding.hpp: which texel a sample picks when it lands exactly on a texel boundary.
//
// Usage:
//   RoundingRule r = choose_rule(du.dx, du.dy);          // from the gradient's signs
//   std::int64_t m = rounding_modifier(r, 16);            // in units of 1/D, D = 2^16
//   std::int64_t i = round_with_modifier(C, m, 16);       // floor((C + m) / D)
//   TexelRounding t = choose_rounding(triangle, MapperKind::exact); // for chapter 3
//
// Conventions (chapters 3 and 4). Texel i covers [i, i+1) in texel units; u is measured
// from texel edges, c = u - 1/2 from texel centres. The nearest texel is
//   rule 1: floor(c + 1/2) = floor(u)        (a tie goes to the larger index)
//   rule 2: ceil(c - 1/2)  = ceil(u) - 1     (a tie goes to the smaller index)
// and the two differ only when u is an integer (c is half way between two centres).
// In fixed point a coordinate is an integer C = c * D with D = 2^k, 1 <= k <= 30, and
// |C| <= 2^61; both rules are one floor, floor((C + m) / D), each with its own modifier
// m (@eq:modifier; m = D/2 for rule 1). chapter 3's 16.16 inner loops
// hold U = u * D = C + D/2, so TexelRounding holds exactly this modifier.
//
// The rule is chosen like the top-left fill rule: a sample on the boundary between two
// texels belongs to the texel on its right on screen (+x), or, where the boundary is
// horizontal (dc/dx = 0), to the texel below it (+y). That is rule 1 when c grows to
// the right (or, with dc/dx = 0, downwards or not at all) and rule 2 otherwise.
// Under perspective, u = p / q with p = u/w and q = 1/w linear on screen; the sign of
// du/dx, which is that of dc/dx, is the sign of the numerator dp/dx * q - p * dq/dx,
// which is the same at every point of a row, even where q changes sign
// (@eq:numerator-constant), but not from row to row.
#pragma once

#include "exactpixels/base/error.hpp"
#include "exactpixels/base/integer_division.hpp"
#include "exactpixels/base/types.hpp"
#include "exactpixels/raster/gradients.hpp"
#include "exactpixels/texture/texture_mapper.hpp"

#include <array>
#include <cstdint>
#include <string>

namespace exactpixels {

/// The two nearest-texel rules; they differ only for a sample exactly on a texel edge.
enum class RoundingRule {
    ties_up,  ///< rule 1: floor(c + 1/2) = floor(u); a tie picks the larger index
    ties_down ///< rule 2: ceil(c - 1/2) = ceil(u) - 1; a tie picks the smaller index
};

/// Throws Error unless 1 <= k <= 30 (D = 2^k must be even and small enough for int64).
constexpr void check_fraction_bits(int k) {
    if (k < 1 || k > 30) {
        throw Error("rounding.hpp: fraction bits k = " + std::to_string(k) +
                    " outside [1, 30]");
    }
}

//> two-rules
/// Rule 1 straight from its definition: floor(C/D + 1/2) = floor((2C + D) / 2D), D = 2^k.
constexpr std::int64_t round_ties_up(std::int64_t C, int k) {
    const std::int64_t D = std::int64_t{1} << k;
    return floor_div(2 * C + D, 2 * D);
}

/// Rule 2 straight from its definition: ceil(C/D - 1/2) = ceil((2C - D) / 2D), D = 2^k.
constexpr std::int64_t round_ties_down(std::int64_t C, int k) {
    const std::int64_t D = std::int64_t{1} << k;
    return ceil_div(2 * C - D, 2 * D);
}
//< two-rules

//> modifier
/// The modifier m that makes floor((C + m) / D) follow `rule` (@eq:modifier), in units of
/// 1/D with D = 2^k. Error unless 1 <= k <= 30.
constexpr std::int64_t rounding_modifier(RoundingRule rule, int k) {
    check_fraction_bits(k);
    const std::int64_t D = std::int64_t{1} << k;
    //> exercise ch04-modifier: rule 1's m is D/2; rule 2's follows from @eq:ceil-to-floor.
    // Rule 2 is rule 1 with the modifier one unit (1/D) smaller.
    return rule == RoundingRule::ties_up ? D / 2 : D / 2 - 1;
    //| (void)rule;
    //| return D / 2; // stub: rule 1 for both
    //< exercise ch04-modifier
}

/// Either rule as one floor: floor((C + m) / D), D = 2^k, with m from rounding_modifier.
/// The shift is a floor for negative values too (C++20 defines >> as arithmetic).
constexpr std::int64_t round_with_modifier(std::int64_t C, std::int64_t m, int k) {
    return (C + m) >> k;
}
//< modifier

/// The modifier of chapter 3's 16.16 loops for `rule` (rounding_modifier with k = 16).
constexpr std::int32_t texel_modifier(RoundingRule rule) {
    return static_cast<std::int32_t>(rounding_modifier(rule, texel_fraction_bits));
}

/// The same rule in both texture directions' modifiers.
constexpr TexelRounding texel_rounding(RoundingRule u_rule, RoundingRule v_rule) {
    return {texel_modifier(u_rule), texel_modifier(v_rule)};
}

//> choose-rule
/// The rule for a coordinate c with screen gradient (dc/dx, dc/dy): a sample on a texel
/// edge goes to the texel on its right, or below it when the edge is horizontal.
template <class Real> RoundingRule choose_rule(Real dc_dx, Real dc_dy) {
    //> exercise ch04-choose-rule: the sign of dc/dx decides; dc/dy only when dc/dx is 0.
    if (dc_dx != Real(0)) {
        return dc_dx > Real(0) ? RoundingRule::ties_up : RoundingRule::ties_down;
    }
    return dc_dy < Real(0) ? RoundingRule::ties_down : RoundingRule::ties_up;
    //| (void)dc_dx, (void)dc_dy;
    //| return RoundingRule::ties_up; // stub: always rule 1 (the texture direction bug)
    //< exercise ch04-choose-rule
}
//< choose-rule

//> choose-rule-left-up
/// The rule for the opposite convention (exercise ch04-choose-rule-left-up):
/// a sample on a texel edge goes to the texel on its left on screen (-x),
/// or above it when the edge is horizontal; a constant coordinate takes rule 1.
template <class Real> RoundingRule choose_rule_left_up(Real dc_dx, Real dc_dy) {
    //> exercise ch04-choose-rule-left-up: which texel lies to the left, or above?
    // Left of a tie at u = n lies u - t dc/dx (small t > 0): texel n
    // when c falls to the right (rule 1), n - 1 when it grows (rule 2);
    // above it, the same with dc/dy.
    if (dc_dx != Real(0)) {
        return dc_dx < Real(0) ? RoundingRule::ties_up : RoundingRule::ties_down;
    }
    return dc_dy > Real(0) ? RoundingRule::ties_down : RoundingRule::ties_up;
    //| (void)dc_dx, (void)dc_dy;
    //| return RoundingRule::ties_up; // stub: always rule 1
    //< exercise ch04-choose-rule-left-up
}
//< choose-rule-left-up

/// A texture coordinate u (or v) under perspective, around one screen point: p = u/w
/// and q = 1/w there, and their screen gradients (both are linear in x and y).
template <class Real> struct ProjectedCoordinate {
    Real p;            ///< u/w at the point
    Real q;            ///< 1/w at the point
    Gradient<Real> dp; ///< d(u/w)/dx and d(u/w)/dy, per pixel
    Gradient<Real> dq; ///< d(1/w)/dx and d(1/w)/dy, per pixel
};

//> numerator
/// The numerator of du/dx = (dp/dx q - p dq/dx) / q^2 (@eq:numerator): its sign is the
/// sign of du/dx (and of dc/dx, c = u - 1/2), and it does not change along the row
/// through the point (@eq:numerator-constant).
template <class Real> Real numerator_x(const ProjectedCoordinate<Real>& c) {
    return c.dp.dx * c.q - c.p * c.dq.dx;
}

/// The same for du/dy: constant along the column through the point.
template <class Real> Real numerator_y(const ProjectedCoordinate<Real>& c) {
    return c.dp.dy * c.q - c.p * c.dq.dy;
}
//< numerator

/// The same coordinate around the point moved by (dx, dy) pixels.
template <class Real>
ProjectedCoordinate<Real> moved_by(const ProjectedCoordinate<Real>& c, Real dx, Real dy) {
    return {c.p + c.dp.dx * dx + c.dp.dy * dy, c.q + c.dq.dx * dx + c.dq.dy * dy, c.dp,
            c.dq};
}

/// The rule for a perspective coordinate at its point: the signs of the numerators
/// stand for the signs of du/dx and du/dy (q^2 > 0 wherever q != 0).
template <class Real> RoundingRule choose_rule(const ProjectedCoordinate<Real>& c) {
    return choose_rule(numerator_x(c), numerator_y(c));
}

/// u (index 0) and v (index 1) of a textured triangle as projected coordinates around
/// the screen point `at` (any point; the planes extend beyond the triangle). A
/// triangle of zero area has zero gradients.
std::array<ProjectedCoordinate<double>, 2>
projected_coordinates(const std::array<TexturedVertex, 3>& v, Point2 at);

/// The same from the quotients at the corners, divided already: u_w[k] = u/w, v_w[k] =
/// v/w and one_w[k] = 1/w at v[k].
std::array<ProjectedCoordinate<double>, 2>
projected_coordinates(const std::array<TexturedVertex, 3>& v,
                      const std::array<double, 3>& u_w, const std::array<double, 3>& v_w,
                      const std::array<double, 3>& one_w, Point2 at);

/// The rounding for an affine mapping from the gradients of u and of v.
TexelRounding choose_rounding(const Gradient<double>& du, const Gradient<double>& dv);

/// The centroid of the triangle's corners: where choose_rounding reads the numerators.
Point2 centroid(const std::array<TexturedVertex, 3>& v);

/// The rounding for a perspective-correct mapping of the triangle, from the numerators
/// at its centroid. Exact for every row when the numerators keep their sign over the
/// triangle (always when w is constant); see choose_rounding_on_row otherwise.
TexelRounding choose_rounding(const std::array<TexturedVertex, 3>& v);

/// The rounding a mapper of `kind` needs for the triangle: the affine gradients of u
/// and v for MapperKind::affine (it interpolates u and v themselves), the perspective
/// numerators for the others (they follow u = (u/w) / (1/w)).
TexelRounding choose_rounding(const std::array<TexturedVertex, 3>& v, MapperKind kind);

/// The perspective rounding for the pixel row whose centres lie at height y: exact for
/// every pixel of that row, because the x numerator is constant along it.
TexelRounding choose_rounding_on_row(const std::array<TexturedVertex, 3>& v, double y);

} // namespace exactpixels
