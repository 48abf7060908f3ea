#include "exactpixels/scene/scene_pipeline.hpp"

#include "exactpixels/texture/perspective_error.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <fmt/format.h>

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

namespace {

/// The depths' extremes and the larger corner range of u and v.
struct TriangleSpread {
    double w_min, w_max, extent;
};

TriangleSpread spread(const std::array<TexturedVertex, 3>& c) {
    const auto range = [](double a, double b, double d) {
        return std::max({a, b, d}) - std::min({a, b, d});
    };
    return {std::min({c[0].w, c[1].w, c[2].w}), std::max({c[0].w, c[1].w, c[2].w}),
            std::max(range(c[0].uv.x, c[1].uv.x, c[2].uv.x),
                     range(c[0].uv.y, c[1].uv.y, c[2].uv.y))};
}

} // namespace

double triangle_affine_error_bound(const std::array<TexturedVertex, 3>& corners) {
    const TriangleSpread t = spread(corners);
    assert(t.w_min > 0.0);
    return t.extent * affine_error_bound(t.w_max / t.w_min);
}

//> triangle-affine-fits
bool triangle_affine_fits(const std::array<TexturedVertex, 3>& corners, double budget) {
    assert(budget > 0.0);
    const TriangleSpread t = spread(corners);
    // D (s - 1) / (s + 1) <= B with s = sqrt(w_max / w_min) >= 1: always when D <= B,
    // else exactly when s <= (D + B) / (D - B), that is
    // w_max (D - B)^2 <= w_min (D + B)^2.
    const double d = t.extent, b = budget;
    return d <= b || t.w_max * (d - b) * (d - b) <= t.w_min * (d + b) * (d + b);
}
//< triangle-affine-fits

//> mapper-divides
long long mapper_divides(Mapper mapper, int count) {
    const long long pieces = (count + mapper.piece - 1) / mapper.piece;
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

//> colour-bound
double colour_error_bound(const std::array<double, 3>& w,
                          const std::array<Colour, 3>& c) {
    const double w_min = std::min({w[0], w[1], w[2]});
    const double w_max = std::max({w[0], w[1], w[2]});
    assert(w_min > 0.0);
    double range = 0.0; // the largest change of one channel over the triangle
    for (int k = 0; k < 3; ++k) {
        range = std::max(range, std::max({c[0][k], c[1][k], c[2][k]}) -
                                    std::min({c[0][k], c[1][k], c[2][k]}));
    }
    return 2.0 * affine_error_bound(w_max / w_min) * range * 255.0;
}
//< colour-bound

ScreenBox ScreenBox::clipped(Viewport viewport) const {
    return {std::max(x0, 0.0), std::max(y0, 0.0), std::min(x1, double(viewport.width)),
            std::min(y1, double(viewport.height))};
}

bool ScreenBox::intersects(const ScreenBox& o) const {
    return !empty() && !o.empty() && x0 <= o.x1 && o.x0 <= x1 && y0 <= o.y1 && o.y0 <= y1;
}

namespace {

/// Beyond this many corner-against-plane checks, convexity is not tested (the mesh is
/// taken as able to overlap itself).
constexpr std::size_t max_convexity_checks = 1'000'000;

/// Which sides of the plane of triangle t the mesh's corners lie on, within a tolerance
/// relative to the mesh's size: bit 1 some corner in front, bit 2 some behind.
int sides_of_plane(const SceneMesh& mesh, const std::array<SceneVertex, 3>& t,
                   double size) {
    const glm::dvec3 n =
        glm::cross(t[1].position - t[0].position, t[2].position - t[0].position);
    const double tolerance = 1e-9 * glm::length(n) * size;
    int sides = 0;
    for (const auto& other : mesh.triangles) {
        for (const SceneVertex& v : other) {
            const double d = glm::dot(n, v.position - t[0].position);
            sides |= d > tolerance ? 1 : d < -tolerance ? 2 : 0;
        }
    }
    return sides;
}

} // namespace

bool can_overlap_itself(const SceneMesh& mesh) {
    if (mesh.triangles.size() < 2) {
        return false;
    }
    glm::dvec3 lo = mesh.triangles[0][0].position, hi = lo;
    for (const auto& t : mesh.triangles) {
        for (const SceneVertex& v : t) {
            lo = glm::min(lo, v.position);
            hi = glm::max(hi, v.position);
        }
    }
    const double size = glm::length(hi - lo);
    if (sides_of_plane(mesh, mesh.triangles[0], size) == 0) {
        return false; // planar
    }
    const std::size_t corners = 3 * mesh.triangles.size();
    if (!mesh.cull_back || corners * mesh.triangles.size() > max_convexity_checks) {
        return true;
    }
    for (const auto& t : mesh.triangles) {
        if (sides_of_plane(mesh, t, size) == 3) {
            return true; // not convex: front faces may overlap
        }
    }
    return false;
}

DepthPlan plan_depth(DepthMode mode, const std::vector<MeshFootprint>& meshes,
                     Viewport viewport) {
    if (mode != DepthMode::automatic) {
        const bool on = mode == DepthMode::on;
        return {on, on ? "depth = true" : "depth = false"};
    }
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        const ScreenBox a = meshes[i].box.clipped(viewport);
        if (meshes[i].can_overlap_itself && !a.empty()) {
            return {true, fmt::format("auto: {} can overlap itself", meshes[i].name)};
        }
        for (std::size_t j = i + 1; j < meshes.size(); ++j) {
            if (a.intersects(meshes[j].box.clipped(viewport))) {
                return {true, fmt::format("auto: {} and {} overlap on screen",
                                          meshes[i].name, meshes[j].name)};
            }
        }
    }
    return {false, "auto: no two meshes overlap on screen"};
}

} // namespace exactpixels
