// span_mappers.hpp: chapter 3's mappers on one row span, each a plain loop over pixels.
//
// Usage:
//   PerspectiveSpan<double> s{...};   // u/w, v/w, 1/w at the first pixel and per pixel
//   map_span_exact(s, [&](int k, double u, double v) { ... });        // pixel k of span
//   map_span_quadratic(s, [&](int k, double u, double v) { ... });
//   map_span_subdivided_fixed(s, 16, [&](int k, std::int32_t U, std::int32_t V) { ... });
//
// A span is `count` pixels in a row; pixel k (0 <= k < count) is the k-th from the left,
// sampled at its centre. u/w, v/w and 1/w are linear in screen space
// (@eq:linear-in-screen), so a PerspectiveSpan holds each at pixel 0 and its change per
// pixel. w is view-space depth (> 0), u and v are in texels. Every mapper calls emit(k,
// u, v) once per pixel, k = 0, 1, ..., count - 1 in order:
//   - the Real forms (float or double) hand out u and v in texels, computed in Real;
//   - the _fixed forms hand out U = u * 2^16 and V = v * 2^16 as 16.16 integers, their
//     setup done in double, their inner loop in integers.
// The subdivided forms are exact at pixels 0, n, 2n, ... and at the last pixel; the last,
// shorter piece is aimed at the span's last pixel. n >= 2.
#pragma once

#include "exactpixels/base/floor_to_int.hpp"
#include "exactpixels/texture/quadratic.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>

namespace exactpixels {

/// One span in the perspective-correct form: the linear quantities at pixel 0's centre
/// and their change per pixel to the right.
template <class Real> struct PerspectiveSpan {
    Real u_w;    ///< u/w at pixel 0 (texels per unit depth)
    Real v_w;    ///< v/w at pixel 0
    Real one_w;  ///< 1/w at pixel 0 (> 0)
    Real du_w;   ///< change of u/w per pixel
    Real dv_w;   ///< change of v/w per pixel
    Real done_w; ///< change of 1/w per pixel
    int count;   ///< pixels in the span, >= 1
};

/// One span in the affine form: u and v at pixel 0's centre and their change per pixel.
template <class Real> struct AffineSpan {
    Real u;    ///< u at pixel 0, texels
    Real v;    ///< v at pixel 0, texels
    Real du;   ///< change of u per pixel
    Real dv;   ///< change of v per pixel
    int count; ///< pixels in the span, >= 1
};

/// The same span with every quantity converted to Real (a float inner loop set up in
/// double).
template <class Real> PerspectiveSpan<Real> converted(const PerspectiveSpan<double>& s) {
    return {Real(s.u_w),  Real(s.v_w),    Real(s.one_w), Real(s.du_w),
            Real(s.dv_w), Real(s.done_w), s.count};
}

/// The same span with every quantity converted to Real.
template <class Real> AffineSpan<Real> converted(const AffineSpan<double>& s) {
    return {Real(s.u), Real(s.v), Real(s.du), Real(s.dv), s.count};
}

/// A texture coordinate in the Real type of a mapper.
template <class Real> struct UV {
    Real u; ///< texels
    Real v; ///< texels
};

/// The pixel a piece starting at pixel k0 is aimed at: k0 + n while that is inside the
/// span, else the span's last pixel (the last piece is aimed at its own last pixel).
inline int piece_target(int k0, int n, int count) {
    return k0 + n < count ? k0 + n : count - 1;
}

//> exact-at
/// The exact (u, v) at pixel k of the span: the linear quantities evaluated at k, then
/// one divide (@eq:exact-divide). k may be any pixel of the row, inside the span or not.
template <class Real> UV<Real> exact_at(const PerspectiveSpan<Real>& s, int k) {
    const Real t = static_cast<Real>(k);
    const Real w = Real(1) / (s.one_w + t * s.done_w); // the depth at pixel k
    return {(s.u_w + t * s.du_w) * w, (s.v_w + t * s.dv_w) * w};
}
//< exact-at

//> pixel-of-u
/// Where on the span's row the exact mapper reaches texture coordinate u (exercise
/// ch03-pixel-of-u): the pixel position t, counted from pixel 0 and fractional in
/// general, at which exact_at's u would be u, so that a renderer can cut a span where
/// it crosses a texel edge. u must be a value the row reaches: a u at which
/// du_w = u done_w (the row's u at infinity, or a u constant along it) has no t.
template <class Real> Real pixel_of_u(const PerspectiveSpan<Real>& s, Real u) {
    //> exercise ch03-pixel-of-u: u = (u/w)(t) / (1/w)(t); both are linear in t: solve.
    // u (one_w + t done_w) = u_w + t du_w, linear in t: one division.
    return (u * s.one_w - s.u_w) / (s.du_w - u * s.done_w);
    //| (void)s, (void)u;
    //| return Real(0); // stub: always the span's first pixel
    //< exercise ch03-pixel-of-u
}
//< pixel-of-u

//> map-span-exact
/// The exact mapper: a divide at every pixel.
template <class Real, class Emit>
void map_span_exact(const PerspectiveSpan<Real>& s, Emit&& emit) {
    for (int k = 0; k < s.count; ++k) {
        const UV<Real> uv = exact_at(s, k);
        emit(k, uv.u, uv.v);
    }
}
//< map-span-exact

//> map-span-affine
/// The affine mapper: u and v step by a constant amount per pixel.
template <class Real, class Emit>
void map_span_affine(const AffineSpan<Real>& s, Emit&& emit) {
    Real u = s.u, v = s.v;
    for (int k = 0; k < s.count; ++k) {
        emit(k, u, v);
        u += s.du;
        v += s.dv;
    }
}
//< map-span-affine

/// The affine mapper evaluated afresh at every pixel, u0 + k du, instead of stepped:
/// the same straight line without chapter 6's drift (@eq:drift-bound); one multiply
/// more per pixel and coordinate, and no sum carried from pixel to pixel.
template <class Real, class Emit>
void map_span_affine_fresh(const AffineSpan<Real>& s, Emit&& emit) {
    for (int k = 0; k < s.count; ++k) {
        const Real t = static_cast<Real>(k);
        emit(k, s.u + t * s.du, s.v + t * s.dv);
    }
}

//> map-span-subdivided
/// Subdivided affine: exact at pixels 0, n, 2n, ..., affine between them; the last
/// piece runs to the span's last pixel and is aimed at it.
template <class Real, class Emit>
void map_span_subdivided(const PerspectiveSpan<Real>& s, int n, Emit&& emit) {
    assert(n >= 2);
    UV<Real> start = exact_at(s, 0);
    for (int k0 = 0; k0 < s.count; k0 += n) {
        const int length = std::min(n, s.count - k0); // pixels in this piece
        const int target = piece_target(k0, n, s.count);
        const UV<Real> end = exact_at(s, target);
        const Real steps = static_cast<Real>(std::max(target - k0, 1));
        const Real du = (end.u - start.u) / steps, dv = (end.v - start.v) / steps;
        Real u = start.u, v = start.v;
        for (int k = k0; k < k0 + length; ++k) {
            emit(k, u, v);
            u += du;
            v += dv;
        }
        start = end; // the next piece starts where this one was aimed
    }
}
//< map-span-subdivided

//> map-span-quadratic-piece
/// Pursey's parabola (Thellier's coefficients) from pixel k0 to pixel k1 >= k0 of the
/// span, stepped by forward differences: emits pixels k0 .. k0 + length - 1.
template <class Real, class Emit>
void map_quadratic_piece(const PerspectiveSpan<Real>& s, int k0, int k1, int length,
                         Emit&& emit) {
    const UV<Real> a = exact_at(s, k0), b = exact_at(s, k1);
    const Real n = static_cast<Real>(std::max(k1 - k0, 1));
    // Depths at both ends: only their ratio enters the coefficients.
    const Real w0 = Real(1) / (s.one_w + static_cast<Real>(k0) * s.done_w);
    const Real w1 = Real(1) / (s.one_w + static_cast<Real>(k1) * s.done_w);
    ForwardDifferences<Real> fu =
        forward_differences(thellier_quadratic(a.u, w0, b.u, w1, n));
    ForwardDifferences<Real> fv =
        forward_differences(thellier_quadratic(a.v, w0, b.v, w1, n));
    for (int k = k0; k < k0 + length; ++k) {
        emit(k, fu.u, fv.u);
        step(fu); // two additions per coordinate per pixel
        step(fv);
    }
}
//< map-span-quadratic-piece

/// The quadratic mapper over the whole span: one parabola per coordinate through the
/// exact values at the first pixel, the middle and the last pixel.
template <class Real, class Emit>
void map_span_quadratic(const PerspectiveSpan<Real>& s, Emit&& emit) {
    map_quadratic_piece(s, 0, s.count - 1, s.count, emit);
}

/// The quadratic mapper on pieces of n pixels, placed like map_span_subdivided's: each
/// parabola runs from pixel k0 to k0 + n (the last one to the span's last pixel).
template <class Real, class Emit>
void map_span_quadratic_subdivided(const PerspectiveSpan<Real>& s, int n, Emit&& emit) {
    assert(n >= 2);
    for (int k0 = 0; k0 < s.count; k0 += n) {
        const int length = std::min(n, s.count - k0);
        const int target = piece_target(k0, n, s.count);
        map_quadratic_piece(s, k0, target, length, emit);
    }
}

/// u in texels as a 16.16 integer, rounded to nearest (halves away from zero). |u| must
/// be < 2^15.
inline std::int32_t to_fixed_texel(double u) {
    assert(std::abs(u) < 32768.0);
    return round_to_int(u * 65536.0);
}

/// The exact mapper with a 16.16 result: the divide in double, U rounded to nearest.
template <class Emit>
void map_span_exact_fixed(const PerspectiveSpan<double>& s, Emit&& emit) {
    map_span_exact(s, [&](int k, double u, double v) {
        emit(k, to_fixed_texel(u), to_fixed_texel(v));
    });
}

//> map-span-affine-fixed
/// The affine mapper in 16.16 fixed point: one integer addition per coordinate per pixel.
template <class Emit>
void map_span_affine_fixed(const AffineSpan<double>& s, Emit&& emit) {
    std::int32_t U = to_fixed_texel(s.u), V = to_fixed_texel(s.v);
    const std::int32_t dU = to_fixed_texel(s.du), dV = to_fixed_texel(s.dv);
    for (int k = 0; k < s.count; ++k) {
        emit(k, U, V);
        U += dU;
        V += dV;
    }
}
//< map-span-affine-fixed

/// Subdivided affine in 16.16 fixed point: exact anchors from double, integer steps.
template <class Emit>
void map_span_subdivided_fixed(const PerspectiveSpan<double>& s, int n, Emit&& emit) {
    assert(n >= 2);
    UV<double> start = exact_at(s, 0);
    for (int k0 = 0; k0 < s.count; k0 += n) {
        const int length = std::min(n, s.count - k0);
        const int target = piece_target(k0, n, s.count);
        const UV<double> end = exact_at(s, target);
        const double steps = static_cast<double>(std::max(target - k0, 1));
        std::int32_t U = to_fixed_texel(start.u), V = to_fixed_texel(start.v);
        const std::int32_t dU = to_fixed_texel((end.u - start.u) / steps);
        const std::int32_t dV = to_fixed_texel((end.v - start.v) / steps);
        for (int k = k0; k < k0 + length; ++k) {
            emit(k, U, V);
            U += dU;
            V += dV;
        }
        start = end;
    }
}

/// Forward differences in 32.32 fixed point (64-bit), so that the rounding of the tiny
/// second difference does not pile up over long spans; U hands out the 16.16 part.
struct FixedForwardDifferences {
    std::int64_t u;   ///< u * 2^32
    std::int64_t du;  ///< first difference * 2^32
    std::int64_t ddu; ///< second difference * 2^32

    /// The state for a parabola given in double.
    explicit FixedForwardDifferences(const Quadratic<double>& q)
        : u(std::llround(q.u0 * 0x1p32)), du(std::llround((q.a + q.b) * 0x1p32)),
          ddu(std::llround((q.a + q.a) * 0x1p32)) {}
    /// The current u as 16.16, rounded to nearest from 32.32.
    std::int32_t U() const { return static_cast<std::int32_t>((u + (1 << 15)) >> 16); }
    /// One pixel right: two integer additions.
    void step() {
        u += du;
        du += ddu;
    }
};

/// The quadratic mapper on pixels k0 .. k0 + length - 1, parabola from k0 to k1, with a
/// fixed-point inner loop.
template <class Emit>
void map_quadratic_piece_fixed(const PerspectiveSpan<double>& s, int k0, int k1,
                               int length, Emit&& emit) {
    const UV<double> a = exact_at(s, k0), b = exact_at(s, k1);
    const double n = static_cast<double>(std::max(k1 - k0, 1));
    const double w0 = 1.0 / (s.one_w + k0 * s.done_w);
    const double w1 = 1.0 / (s.one_w + k1 * s.done_w);
    FixedForwardDifferences fu(thellier_quadratic(a.u, w0, b.u, w1, n));
    FixedForwardDifferences fv(thellier_quadratic(a.v, w0, b.v, w1, n));
    for (int k = k0; k < k0 + length; ++k) {
        emit(k, fu.U(), fv.U());
        fu.step();
        fv.step();
    }
}

/// The quadratic mapper over the whole span with a fixed-point inner loop.
template <class Emit>
void map_span_quadratic_fixed(const PerspectiveSpan<double>& s, Emit&& emit) {
    map_quadratic_piece_fixed(s, 0, s.count - 1, s.count, emit);
}

/// The quadratic mapper on pieces of n pixels with a fixed-point inner loop.
template <class Emit>
void map_span_quadratic_subdivided_fixed(const PerspectiveSpan<double>& s, int n,
                                         Emit&& emit) {
    assert(n >= 2);
    for (int k0 = 0; k0 < s.count; k0 += n) {
        const int length = std::min(n, s.count - k0);
        const int target = piece_target(k0, n, s.count);
        map_quadratic_piece_fixed(s, k0, target, length, emit);
    }
}

} // namespace exactpixels
