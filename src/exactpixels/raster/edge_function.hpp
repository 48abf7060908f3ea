// edge_function.hpp: the edge function of a triangle edge, its top-left bias, and how it
// steps from one pixel centre to the next.
//
// Usage:
//   std::array<FixedPoint2, 3> v = {snap_to_subpixel({0.5, 0.5}), ...}; // 1/256 px
//   std::int64_t e = edge_function(v[1], v[2], fixed_pixel_centre(3, 2));
//   EdgeSetup<std::int64_t> edges = setup_edges(v);   // the three edges, inside >= 0
//   bool covered = edges.covers(edges.edge[0].at(3, 2)) && ...;
//
// Conventions (chapter 0): origin top-left, y down, pixel (x, y) sampled at its centre
// (x + 1/2, y + 1/2). Fixed point: coordinates in 1/256 px (FixedPoint2), edge function
// values in 1/65536 px^2, exact in 64-bit integers for coordinates within
// +-max_fixed_coordinate (@eq:edge-range). Float: single precision, pixels, rounded.
//
// Edge i is the edge opposite vertex i: from v[i+1] to v[i+2] (indices mod 3), so that
// E_i / (E_0 + E_1 + E_2) is the barycentric weight of vertex i (@eq:edge-barycentric).
// setup_edges orients the edges so that the inside is where every edge function is
// positive, whatever the winding; a centre exactly on an edge is inside only for a top or
// a left edge (the top-left rule).
#pragma once

#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/base/types.hpp"
#include "exactpixels/raster/gradients.hpp"

#include <array>
#include <cstdint>

namespace exactpixels {

//> edge-function
/// The edge function of p against the directed edge a -> b (@eq:edge-function): twice the
/// signed area of the triangle a, b, p; positive when p lies to the right of a -> b on
/// screen (y down). Fixed point: exact, in 1/65536 px^2, for coordinates within
/// +-max_fixed_coordinate.
constexpr std::int64_t edge_function(FixedPoint2 a, FixedPoint2 b, FixedPoint2 p) {
    return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}
//< edge-function

/// The edge function (@eq:edge-function) in single precision, in px^2: rounded at every
/// step.
inline float edge_function(Point2f a, Point2f b, Point2f p) {
    return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

/// The centre of pixel (x, y) in fixed point: (256 x + 128, 256 y + 128), exact.
constexpr FixedPoint2 fixed_pixel_centre(int x, int y) {
    return {std::int64_t{x} * subpixel_scale + subpixel_scale / 2,
            std::int64_t{y} * subpixel_scale + subpixel_scale / 2};
}

//> top-left
/// True when the edge a -> b, of a triangle oriented so that its inside is to the right
/// of every edge (y down), is a top edge (horizontal, the inside below it) or a left edge
/// (the inside to its right). (dx, dy) = b - a.
template <class T> constexpr bool is_top_left(T dx, T dy) {
    //> exercise ch02-edge-bias: which signs of dx and dy make a top edge, and a left one?
    // A top edge goes right along the row; a left edge goes up the screen.
    return dy < 0 || (dy == 0 && dx > 0);
    //| (void)dx, (void)dy;
    //| return false; // stub: no edge owns its centres, so shared edges leave gaps
    //< exercise ch02-edge-bias
}
//< top-left

//> fixed-edge
/// One edge of a snapped triangle as a function of the pixel (x, y):
/// w(x, y) = E(centre of (x, y)) + bias, with bias 0 on a top or left edge and -1 on any
/// other, so that "w >= 0" is the top-left rule for integer E (@eq:edge-bias).
struct FixedEdge {
    FixedPoint2 a;         ///< the edge starts here (1/256 px)
    std::int64_t dx = 0;   ///< b.x - a.x (1/256 px)
    std::int64_t dy = 0;   ///< b.y - a.y (1/256 px)
    std::int64_t bias = 0; ///< 0 (top or left edge) or -1
    /// w one pixel to the right: the change of E per pixel in x (@eq:edge-steps).
    std::int64_t step_x() const { return -dy * subpixel_scale; }
    /// w one pixel down: the change of E per pixel in y (@eq:edge-steps).
    std::int64_t step_y() const { return dx * subpixel_scale; }
    /// w at the centre of pixel (x, y), evaluated directly (@eq:edge-function plus the
    /// bias).
    std::int64_t at(int x, int y) const {
        const FixedPoint2 p = fixed_pixel_centre(x, y);
        return dx * (p.y - a.y) - dy * (p.x - a.x) + bias;
    }
};
//< fixed-edge

/// One edge of a float triangle: w(x, y) = E(centre of (x, y)) in px^2, rounded. The
/// top-left rule cannot be a bias here (there is no "next value below zero" that is the
/// same everywhere), so the edge keeps a flag instead.
struct FloatEdge {
    Point2f a;             ///< the edge starts here (px)
    float dx = 0;          ///< b.x - a.x (px, rounded)
    float dy = 0;          ///< b.y - a.y (px, rounded)
    bool top_left = false; ///< whether a centre exactly on the edge is inside
    /// w one pixel to the right (@eq:edge-steps).
    float step_x() const { return -dy; }
    /// w one pixel down (@eq:edge-steps).
    float step_y() const { return dx; }
    /// w at the centre of pixel (x, y), evaluated directly (@eq:edge-function).
    float at(int x, int y) const {
        const float px = static_cast<float>(x) + 0.5f, py = static_cast<float>(y) + 0.5f;
        return dx * (py - a.y) - dy * (px - a.x);
    }
};

/// The three edges of a triangle, oriented so that the inside is where every w is
/// positive. Edge i is opposite vertex i.
template <class Edge> struct EdgeSetup {
    std::array<Edge, 3> edge; ///< edge[i] runs between the two vertices other than i
    bool empty = true;        ///< zero area (or no pixel can be inside): draw nothing
};

/// Whether a pixel whose value for one edge is w passes that edge's test (@eq:edge-bias).
inline bool covers(const FixedEdge&, std::int64_t w) {
    return w >= 0;
}

/// Whether a pixel whose value for one float edge is w passes that edge's test: inside
/// strictly, or exactly on a top or left edge.
inline bool covers(const FloatEdge& e, float w) {
    return w > 0 || (w == 0 && e.top_left);
}

//> setup-fixed
/// The three edges of the snapped triangle v, oriented and biased (@eq:edge-bias). Either
/// winding; zero area gives an empty setup. Coordinates must be within
/// +-max_fixed_coordinate (the rasterizers check; see check_fixed_range).
inline EdgeSetup<FixedEdge> setup_edges(const std::array<FixedPoint2, 3>& v) {
    EdgeSetup<FixedEdge> s;
    const std::int64_t area2 = edge_function(v[0], v[1], v[2]); // twice the signed area
    s.empty = area2 == 0;
    for (int i = 0; i < 3; ++i) {
        // Edge i runs v[i+1] -> v[i+2]; reversed when the triangle winds the other way,
        // so that the inside is always to the right (E > 0).
        FixedPoint2 a = v[(i + 1) % 3], b = v[(i + 2) % 3];
        if (area2 < 0) {
            std::swap(a, b);
        }
        const std::int64_t dx = b.x - a.x, dy = b.y - a.y;
        s.edge[i] = {a, dx, dy, is_top_left(dx, dy) ? 0 : -1};
    }
    return s;
}
//< setup-fixed

/// The three edges of the float triangle v, oriented and flagged top-left.
/// Either winding; zero area (as computed in float) gives an empty setup.
inline EdgeSetup<FloatEdge> setup_edges(const std::array<Point2f, 3>& v) {
    EdgeSetup<FloatEdge> s;
    const float area2 = edge_function(v[0], v[1], v[2]);
    s.empty = !(area2 != 0); // zero (or NaN): nothing to draw
    for (int i = 0; i < 3; ++i) {
        Point2f a = v[(i + 1) % 3], b = v[(i + 2) % 3];
        if (area2 < 0) {
            std::swap(a, b);
        }
        const float dx = b.x - a.x, dy = b.y - a.y;
        s.edge[i] = {a, dx, dy, is_top_left(dx, dy)};
    }
    return s;
}

//> barycentric
/// The barycentric weights of the centre of pixel (x, y) in the snapped triangle v
/// (@eq:edge-barycentric), in double. They sum to 1 (up to one rounding each) and are 1
/// at vertex i, 0 at the other two. Zero area: {0, 0, 0}.
inline std::array<double, 3> barycentric(const std::array<FixedPoint2, 3>& v,
                                         FixedPoint2 p) {
    //> exercise ch02-barycentric: scale the edge functions of @eq:edge-sum to sum to one.
    // lambda_i = E_i / (E_0 + E_1 + E_2), E_i the edge opposite vertex i.
    const std::int64_t e0 = edge_function(v[1], v[2], p);
    const std::int64_t e1 = edge_function(v[2], v[0], p);
    const std::int64_t e2 = edge_function(v[0], v[1], p);
    const std::int64_t area2 = e0 + e1 + e2; // the same at every p (@eq:edge-sum)
    if (area2 == 0) {
        return {0.0, 0.0, 0.0};
    }
    const auto weight = [&](std::int64_t e) {
        return static_cast<double>(e) / static_cast<double>(area2);
    };
    return {weight(e0), weight(e1), weight(e2)};
    //| (void)v, (void)p;
    //| return {0.0, 0.0, 0.0}; // stub: no weights
    //< exercise ch02-barycentric
}
//< barycentric

//> edge-gradient
/// dc/dx and dc/dy from the edge functions' steps (@eq:edge-gradient): c_i times the
/// change of lambda_i per pixel, summed. The same plane as chapter 1's closed form
/// (@eq:closed-form), in any number type T (double, or an exact rational in the tests).
/// Zero area: {0, 0}.
template <class T> Gradient<T> edge_function_gradient(const PlaneSamples<T>& s) {
    // E_0 at vertex 0 (@eq:edge-function with a = v1, b = v2, p = v0): twice the signed
    // area.
    const T area2 =
        (s.x[2] - s.x[1]) * (s.y[0] - s.y[1]) - (s.y[2] - s.y[1]) * (s.x[0] - s.x[1]);
    if (area2 == T(0)) {
        return {T(0), T(0)};
    }
    T dcdx = T(0), dcdy = T(0);
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, k = (i + 2) % 3; // edge i runs v[j] -> v[k]
        dcdx = dcdx + s.c[i] * -(s.y[k] - s.y[j]);  // c_i dE_i/dx
        dcdy = dcdy + s.c[i] * (s.x[k] - s.x[j]);   // c_i dE_i/dy
    }
    return {dcdx / area2, dcdy / area2};
}
//< edge-gradient

} // namespace exactpixels
