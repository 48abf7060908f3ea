// quadratic.hpp: Pursey's quadratic approximation of perspective texture coordinates,
// Thellier's simplified coefficients, and stepping the parabola by forward differences.
//
// Usage:
//   // A span of n + 1 pixels, u0 at the first pixel (depth w0), u2 at the last (w2).
//   Quadratic<double> q = thellier_quadratic(0.0, 1.0, 64.0, 3.0, 31.0);
//   ForwardDifferences<double> f = forward_differences(q);
//   for (int t = 0; t <= 31; ++t) { use(f.u); step(f); }   // two additions per pixel
//
// t counts pixels from the first pixel of the span (t = 0 .. n); u(t) = a t^2 + b t + u0
// in texels. w0 and w2 are view-space depths (> 0, any unit: only their ratio matters).
// The parabola passes through the exact perspective values at t = 0, t = n / 2 and
// t = n (chapter 3, @eq:midpoint, @eq:pursey, @eq:thellier). Every function is a template
// on the number type, so the chapter's tests run the same formulas in exact rational
// arithmetic.
#pragma once

namespace exactpixels {

/// The parabola u(t) = a t^2 + b t + u0 over one span, t in pixels from its start.
template <class T> struct Quadratic {
    T a;  ///< texels per pixel squared
    T b;  ///< texels per pixel (the slope at t = 0)
    T u0; ///< texels at t = 0
};

/// The exact u at the screen midpoint of a span from (u0, depth w0) to (u2, depth w2):
/// u0 + w0 (u2 - u0) / (w0 + w2) (@eq:midpoint).
template <class T> T perspective_midpoint(T u0, T w0, T u2, T w2) {
    return u0 + w0 * (u2 - u0) / (w0 + w2);
}

//> pursey
/// Pursey's parabola through (0, u0), (n/2, u1), (n, u2), u1 the exact midpoint value
/// (@eq:pursey). n > 0 is the number of pixel steps from the first to the last pixel.
template <class T> Quadratic<T> pursey_quadratic(T u0, T w0, T u2, T w2, T n) {
    const T u1 = perspective_midpoint(u0, w0, u2, w2);
    const T a = (T(2) * u0 - T(4) * u1 + T(2) * u2) / (n * n);
    const T b = (T(-3) * u0 + T(4) * u1 - u2) / n;
    return {a, b, u0};
}
//< pursey

//> thellier
/// Thellier's form of the same parabola (@eq:thellier): one ratio 4 w0 / (w0 + w2) and
/// the span's texel extent du = u2 - u0 give both coefficients.
template <class T> Quadratic<T> thellier_quadratic(T u0, T w0, T u2, T w2, T n) {
    const T du = u2 - u0;                   // the span's extent in texels
    const T k = T(4) * du * w0 / (w0 + w2); // 4 (u1 - u0), @eq:midpoint
    return {(T(2) * du - k) / (n * n), (k - du) / n, u0};
}
//< thellier

//> quarter-point
/// A parabola over the same span through the exact values at its first pixel, at a
/// quarter of the way (t = n/4) and at its last pixel (exercise ch03-quarter-point),
/// in Thellier's manner: from the extent du = u2 - u0 and one ratio of the depths.
template <class T> Quadratic<T> quarter_point_quadratic(T u0, T w0, T u2, T w2, T n) {
    //> exercise ch03-quarter-point: the exact u at t = n/4, then a and b from three points.
    // At a quarter, 1/w is (3/w0 + 1/w2)/4, so u - u0 = du w0 / (w0 + 3 w2);
    // with k = 16 (u(n/4) - u0), a n^2 + b n = du and a n^2/16 + b n/4 = k/16
    // give a and b.
    const T du = u2 - u0;
    const T k = T(16) * du * w0 / (w0 + T(3) * w2);
    return {(T(4) * du - k) / (T(3) * n * n), (k - du) / (T(3) * n), u0};
    //| (void)w0, (void)w2;
    //| return {T(0), (u2 - u0) / n, u0}; // stub: the affine line
    //< exercise ch03-quarter-point
}
//< quarter-point

//> pursey-overshoot
/// Pursey's parabola is monotonic over its span exactly when the depth ratio
/// r = w2 / w0 lies in [1/3, 3]: its slope is (3 - r) / (1 + r) times du / n at the
/// first pixel and (3 r - 1) / (1 + r) times du / n at the last (@eq:pursey-slopes).
template <class T> bool pursey_is_monotonic(T r) {
    return T(1) <= T(3) * r && r <= T(3);
}

/// How far Pursey's parabola leaves the range between its end values, as a fraction of
/// the span's extent |u2 - u0|, for depth ratio r = w2 / w0 > 0: zero for r in [1/3, 3],
/// (r - 3)^2 / (8 (r^2 - 1)) before u0 for r > 3, the same with 1/r past u2 for r < 1/3
/// (@eq:pursey-overshoot).
template <class T> T pursey_overshoot(T r) {
    if (pursey_is_monotonic(r)) {
        return T(0);
    }
    const T s = r > T(1) ? r : T(1) / r; // the far end's ratio, > 3
    return (s - T(3)) * (s - T(3)) / (T(8) * (s * s - T(1)));
}
//< pursey-overshoot

/// The state of forward differencing: the value at the current pixel, the first
/// difference to the next pixel, and the (constant) second difference.
template <class T> struct ForwardDifferences {
    T u;   ///< u(t) at the current pixel
    T du;  ///< u(t + 1) - u(t)
    T ddu; ///< du(t + 1) - du(t) = 2 a, the same at every step
};

//> forward-differences
/// The forward-difference state at t = 0: u(0) = u0, u(1) - u(0) = a + b, and the
/// second difference 2 a (@eq:forward-differences).
template <class T> ForwardDifferences<T> forward_differences(const Quadratic<T>& q) {
    return {q.u0, q.a + q.b, q.a + q.a};
}

/// Moves the state one pixel right: two additions.
template <class T> void step(ForwardDifferences<T>& f) {
    f.u += f.du;
    f.du += f.ddu;
}
//< forward-differences

/// The parabola evaluated directly at t: a t^2 + b t + u0 (the reference for stepping).
template <class T> T evaluate(const Quadratic<T>& q, T t) {
    return (q.a * t + q.b) * t + q.u0;
}

} // namespace exactpixels
