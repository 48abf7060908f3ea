#include "exactpixels/scene/scene_pipeline.hpp"

#include "exactpixels/texture/perspective_error.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace exactpixels {

MeshStages plan_mesh(const SceneMesh& mesh) {
    MeshStages stages;
    //> exercise ch07-plan-mesh: turn on a stage for each effect the mesh uses, no other.
    stages.texture = mesh.texture.has_value();
    stages.colour = mesh.vertex_colours;
    stages.tint = !mesh.vertex_colours && mesh.colour != Colour{1.0, 1.0, 1.0};
    //| (void)mesh; // stub: no stage at all, every mesh drawn in white
    //< exercise ch07-plan-mesh
    return stages;
}

bool constant_depth(double w0, double w1, double w2) {
    return w0 == w1 && w1 == w2;
}

//> quadratic-bound
double quadratic_error_bound(double r) {
    assert(r > 0.0);
    // The error is the same for r and 1 / r (the span seen from its other end): take
    // s = max(r, 1/r) >= 1, k = s - 1. Two bounds of the error, each simple:
    //  (a) |t (t - 1/2) (1 - t)| <= sqrt 3 / 36 and s - k t >= 1;
    //  (b) |t - 1/2| <= 1/2 and s (1 - t) + t >= 2 sqrt(s t (1 - t)), so
    //      t (1 - t) / (s - k t) <= 1 / (4 sqrt s).
    const double s = std::max(r, 1.0 / r), k = s - 1.0;
    const double a = 2.0 * (std::sqrt(3.0) / 36.0) * k * k / (s + 1.0);
    const double b = k * k / (4.0 * (s + 1.0) * std::sqrt(s));
    return std::min(a, b);
}
//< quadratic-bound

namespace {

/// The exact values at both ends, the depth ratio r = w(k1) / w(k0) and the extent.
struct Piece {
    double r;      // depth ratio, > 0
    double extent; // the larger of |u(k1) - u(k0)| and |v(k1) - v(k0)|, texels
};

Piece piece(const PerspectiveSpan<double>& s, int k0, int k1) {
    const UV<double> a = exact_at(s, k0), b = exact_at(s, k1); // two divides
    const double q0 = s.one_w + k0 * s.done_w, q1 = s.one_w + k1 * s.done_w;
    return {q0 / q1, std::max(std::abs(b.u - a.u), std::abs(b.v - a.v))}; // one more
}

constexpr long long divides_per_bound = 3;

/// Whether Pursey's parabola over pixels k0..k1 stays between its end values: the depth
/// ratio q(k0) / q(k1) lies in [1/3, 3] (@eq:pursey-slopes), tested without a divide.
bool parabola_monotonic(const PerspectiveSpan<double>& s, int k0, int k1) {
    const double q0 = s.one_w + k0 * s.done_w, q1 = s.one_w + k1 * s.done_w;
    return q1 <= 3.0 * q0 && q0 <= 3.0 * q1;
}

} // namespace

double chord_error_bound(const PerspectiveSpan<double>& s, int k0, int k1) {
    const Piece p = piece(s, k0, k1);
    return affine_error_bound(p.r) * p.extent;
}

double parabola_error_bound(const PerspectiveSpan<double>& s, int k0, int k1) {
    const Piece p = piece(s, k0, k1);
    return quadratic_error_bound(p.r) * p.extent;
}

//> choose-span-mapper
AutoChoice choose_span_mapper(const PerspectiveSpan<double>& s, double budget) {
    assert(budget > 0.0 && s.count >= 1);
    const int last = s.count - 1;
    AutoChoice choice{{MapperKind::exact, 2}, 0};
    // Subdivided pieces of n pixels: the worst piece is at one end of the span, where
    // the depth ratio and the texel extent are both largest (@eq:scene-worst-piece).
    const auto pieces_fit = [&](int n) {
        choice.divides += divides_per_bound;
        if (n >= last) {
            return chord_error_bound(s, 0, last) <= budget;
        }
        choice.divides += divides_per_bound;
        return chord_error_bound(s, 0, n) <= budget &&
               chord_error_bound(s, last - n, last) <= budget;
    };
    //> exercise ch07-choose-mapper: try mappers cheapest first, keep the first that fits.
    const long long exact_cost = mapper_divides({MapperKind::exact, 2}, s.count);
    bool quadratic_tried = false;
    for (int n = std::max(s.count, 2); n >= 2; n = (n + 1) / 2) {
        const Mapper subdivided{MapperKind::subdivided, n};
        const Mapper quadratic{MapperKind::quadratic, 2};
        if (mapper_divides(subdivided, s.count) >= exact_cost) {
            break;
        }
        // A parabola that turns back inside the span samples texels beyond its ends
        // (@eq:pursey-overshoot): never chosen.
        if (!quadratic_tried && parabola_monotonic(s, 0, last) &&
            mapper_divides(quadratic, s.count) <= mapper_divides(subdivided, s.count)) {
            quadratic_tried = true;
            choice.divides += divides_per_bound;
            if (parabola_error_bound(s, 0, last) <= budget) {
                choice.mapper = quadratic;
                return choice;
            }
        }
        if (pieces_fit(n)) {
            choice.mapper = subdivided;
            return choice;
        }
        if (n == 2) {
            break;
        }
    }
    //| (void)budget, (void)pieces_fit, (void)parabola_monotonic; // stub: always exact
    //< exercise ch07-choose-mapper
    return choice; // exact: nothing cheaper is within the budget
}
//< choose-span-mapper

//> mapper-divides
long long mapper_divides(Mapper mapper, int count) {
    const long long pieces = (count + mapper.span - 1) / mapper.span;
    switch (mapper.kind) {
    case MapperKind::exact:
        return count; // one per pixel
    case MapperKind::affine:
        return 0;
    case MapperKind::subdivided:
        return 1 + 3 * pieces; // the first pixel, then each piece's end and 2 slopes
    case MapperKind::quadratic:
        return 10; // 2 ends, 2 depths, 3 per coefficient pair (u and v)
    case MapperKind::quadratic_subdivided:
        return 10 * pieces;
    }
    return 0;
}
//< mapper-divides

} // namespace exactpixels
