// gradients.hpp: dc/dx and dc/dy of a value c interpolated linearly over a triangle.
//
// Usage:
//   std::array<glm::dvec2, 3> p{{{0.5, 0.5}, {8.5, 2.5}, {3.5, 6.5}}};  // pixels
//   std::array<double, 3> c{0.0, 1.0, 0.25};                              // c at p[i]
//   Gradient<double> g = closed_form_gradient(p, c);   // c grows g.dx per pixel right
//   double s = edge_slope_from_gradient(g, p[0], p[2]); // c per pixel down edge p0-p2
//
// c stands for anything a rasterizer interpolates linearly in screen space: a colour
// channel, u and v of an affine texture mapper, 1/w, u/w and v/w of a perspective one.
// Coordinates are in pixels (origin top-left, y down); a gradient is "units of c per
// pixel". Chapter 1 derives both methods:
//   - split_edge_gradient: sort by y, find the point on the long edge at the middle
//     vertex's height, dc/dx between it and the middle vertex (@eq:split-point to
//     @eq:split-dcdy);
//   - closed_form_gradient: the ratio of two cross products, any vertex order
//   (@eq:closed-form).
// Every function is a template on the number type: float and double for rasterizers,
// the exact Rational of exactpixels/base/exact.hpp in the chapter's tests (any type with
// + - * /, < and construction from int works). A triangle of zero area (three collinear
// or coincident points) has no gradient: both methods return {0, 0}, never NaN or
// infinity from 0/0.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <array>

namespace exactpixels {

/// The gradient of a linearly interpolated value c: dc/dx and dc/dy, in c per pixel.
template <class Real> struct Gradient {
    Real dx; ///< dc/dx: change of c per pixel to the right
    Real dy; ///< dc/dy: change of c per pixel down
};

/// Three vertices and the value of c at each, as plain numbers of type T (so that the
/// same formulas run in float, double and exact rational arithmetic).
template <class T> struct PlaneSamples {
    std::array<T, 3> x; ///< vertex x in pixels
    std::array<T, 3> y; ///< vertex y in pixels
    std::array<T, 3> c; ///< the value at each vertex
};

//> closed-form
/// dc/dx and dc/dy as ratios of two cross products (@eq:closed-form): no sorting, any
/// vertex order, flat tops and bottoms need no special case. Zero area gives {0, 0}.
template <class T> Gradient<T> closed_form_gradient(const PlaneSamples<T>& s) {
    const T dx2 = s.x[1] - s.x[0], dy2 = s.y[1] - s.y[0], dc2 = s.c[1] - s.c[0];
    const T dx3 = s.x[2] - s.x[0], dy3 = s.y[2] - s.y[0], dc3 = s.c[2] - s.c[0];
    const T area2 = dx2 * dy3 - dx3 * dy2; // 2A: > 0 when clockwise on screen (y down)
    if (area2 == T(0)) {
        return {T(0), T(0)}; // collinear or coincident vertices: no plane
    }
    return {(dc2 * dy3 - dc3 * dy2) / area2, (dc3 * dx2 - dc2 * dx3) / area2};
}
//< closed-form

/// A point or a vector in space, as three numbers of type T (float, double or exact).
template <class T> using Vector3 = std::array<T, 3>;

//> gradient-3d
/// The gradient of c over a triangle in space (exercise ch01-gradient-3d): the
/// vector g in the triangle's plane along which c changes fastest, so that on the
/// triangle c(p) = c[0] + g . (p - p[0]), as chapter 1's (dc/dx, dc/dy) is on the
/// screen (where z = 0). Any vertex order; zero area gives {0, 0, 0}.
template <class T>
Vector3<T> closed_form_gradient_3d(const std::array<Vector3<T>, 3>& p,
                                   const std::array<T, 3>& c) {
    //> exercise ch01-gradient-3d: g . e2 = c[1] - c[0], g . e3 = c[2] - c[0], g . n = 0.
    // Cross products build, from the edges e2 and e3 and the normal n = e2 x e3,
    // one vector in the plane at right angles to e3 and one at right angles to e2.
    const auto difference = [](const Vector3<T>& a, const Vector3<T>& b) {
        return Vector3<T>{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    };
    const auto cross = [](const Vector3<T>& a, const Vector3<T>& b) {
        return Vector3<T>{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                          a[0] * b[1] - a[1] * b[0]};
    };
    const Vector3<T> e2 = difference(p[1], p[0]), e3 = difference(p[2], p[0]);
    const Vector3<T> n = cross(e2, e3); // normal to the plane, |n| = 2A
    const T n2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if (n2 == T(0)) {
        return {T(0), T(0), T(0)}; // collinear or coincident vertices: no plane
    }
    // along2 . e2 = |n|^2, along2 . e3 = 0; along3 . e3 = |n|^2, along3 . e2 = 0.
    const Vector3<T> along2 = cross(e3, n), along3 = cross(n, e2);
    const T dc2 = c[1] - c[0], dc3 = c[2] - c[0];
    return {(dc2 * along2[0] + dc3 * along3[0]) / n2,
            (dc2 * along2[1] + dc3 * along3[1]) / n2,
            (dc2 * along2[2] + dc3 * along3[2]) / n2};
    //| (void)p, (void)c;
    //| return {T(0), T(0), T(0)}; // stub: c the same everywhere
    //< exercise ch01-gradient-3d
}
//< gradient-3d

/// The indices of the vertices sorted by y (ties keep their input order): the top
/// vertex first, the bottom vertex last.
template <class T> std::array<int, 3> sorted_by_y(const std::array<T, 3>& y) {
    std::array<int, 3> order{0, 1, 2}; // three compare-and-swaps: stable, no allocation
    const auto order_pair = [&](std::size_t a, std::size_t b) {
        if (y[static_cast<std::size_t>(order[b])] <
            y[static_cast<std::size_t>(order[a])]) {
            std::swap(order[a], order[b]);
        }
    };
    order_pair(0, 1); // a swap only when strictly smaller keeps ties in input order
    order_pair(1, 2);
    order_pair(0, 1);
    return order;
}

//> split-edge
/// dc/dx from the point on the long edge at the middle vertex's height (@eq:split-point,
/// @eq:split-dcdx), dc/dy from the long edge's slope (@eq:split-dcdy). Sorts the vertices
/// by y first. Zero area gives {0, 0}.
template <class T> Gradient<T> split_edge_gradient(const PlaneSamples<T>& s) {
    const auto [i1, i2, i3] = sorted_by_y(s.y); // y1 <= y2 <= y3
    const T x1 = s.x[i1], y1 = s.y[i1], c1 = s.c[i1];
    const T x2 = s.x[i2], y2 = s.y[i2], c2 = s.c[i2];
    const T x3 = s.x[i3], y3 = s.y[i3], c3 = s.c[i3];
    if (y3 - y1 == T(0)) {
        return {T(0), T(0)}; // all three on one row: no area
    }
    const T t = (y2 - y1) / (y3 - y1); // how far down the long edge vertex 2 lies
    const T x4 = x1 + (x3 - x1) * t;   // the point 4 on the long edge, at y = y2
    const T c4 = c1 + (c3 - c1) * t;
    if (x4 - x2 == T(0)) {
        return {T(0), T(0)}; // vertex 2 on the long edge: collinear
    }
    const T dcdx = (c4 - c2) / (x4 - x2);
    const T long_dcdy = (c3 - c1) / (y3 - y1); // c per pixel down the long edge
    const T long_dxdy = (x3 - x1) / (y3 - y1); // x per pixel down the long edge
    return {dcdx, long_dcdy - dcdx * long_dxdy};
}
//< split-edge

//> edge-slopes
/// dc/dy along the edge a-b, from its end values: (cb - ca) / (yb - ya)
/// (@eq:edge-slope-direct). A horizontal edge is never walked down; it gives 0.
template <class T> T edge_slope_direct(T xa, T ya, T ca, T xb, T yb, T cb) {
    (void)xa, (void)xb; // the direct form needs no x
    return yb - ya == T(0) ? T(0) : (cb - ca) / (yb - ya);
}

/// dc/dy along the edge a-b, from the gradient: dc/dx * dx/dy + dc/dy
/// (@eq:edge-slope-gradient). A step down the edge moves dx/dy pixels right and one pixel
/// down. Horizontal edge: 0.
template <class T> T edge_slope_from_gradient(Gradient<T> g, T xa, T ya, T xb, T yb) {
    return yb - ya == T(0) ? T(0) : g.dx * ((xb - xa) / (yb - ya)) + g.dy;
}
//< edge-slopes

/// The closed-form gradient (@eq:closed-form) of c over the triangle p.
/// Zero area: {0, 0}.
template <class Real>
Gradient<Real> closed_form_gradient(const std::array<glm::vec<2, Real>, 3>& p,
                                    const std::array<Real, 3>& c) {
    return closed_form_gradient(
        PlaneSamples<Real>{{p[0].x, p[1].x, p[2].x}, {p[0].y, p[1].y, p[2].y}, c});
}

/// The split-edge gradient (@eq:split-point to @eq:split-dcdy) of c over the triangle p,
/// any vertex order (it sorts by y itself). Zero area: {0, 0}.
template <class Real>
Gradient<Real> split_edge_gradient(const std::array<glm::vec<2, Real>, 3>& p,
                                   const std::array<Real, 3>& c) {
    return split_edge_gradient(
        PlaneSamples<Real>{{p[0].x, p[1].x, p[2].x}, {p[0].y, p[1].y, p[2].y}, c});
}

/// dc/dy along the edge from a (value ca) to b (value cb), from the end values
/// (@eq:edge-slope-direct).
template <class Real>
Real edge_slope_direct(glm::vec<2, Real> a, Real ca, glm::vec<2, Real> b, Real cb) {
    return edge_slope_direct(a.x, a.y, ca, b.x, b.y, cb);
}

/// dc/dy along the edge from a to b, from the gradient g (@eq:edge-slope-gradient).
template <class Real>
Real edge_slope_from_gradient(Gradient<Real> g, glm::vec<2, Real> a,
                              glm::vec<2, Real> b) {
    return edge_slope_from_gradient(g, a.x, a.y, b.x, b.y);
}

} // namespace exactpixels
