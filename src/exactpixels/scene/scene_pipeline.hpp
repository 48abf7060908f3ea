// scene_pipeline.hpp: which stages a mesh needs, and which mapper `auto` picks for a
// triangle or a span.
//
// Usage:
//   MeshStages stages = plan_mesh(mesh);                // what this mesh pays for
//   bool whole = triangle_affine_fits(corners, 0.5);    // auto: affine on all of it
//   AutoChoice c = choose_span_mapper(span, 0.5);       // auto: cheapest within 0.5
//   long long d = mapper_divides(c.mapper, span.count); // divides that mapper performs
//
// A stage runs only when the mesh calls for it (chapter 7, @sec:only-what-is-needed):
// no texture, no texture coordinates and no sampling; no vertex colours, no colour
// interpolation; depth w constant over a triangle, the affine mapper, which is exact
// there and divides nothing; every corner inside the view volume and the guard band,
// no clipping.
// Spans are chapter 3's PerspectiveSpan: u/w, v/w and 1/w at the first pixel centre and
// their change per pixel; errors are in texels of texture coordinate.
#pragma once

#include "exactpixels/raster/span.hpp"
#include "exactpixels/scene/scene.hpp"
#include "exactpixels/texture/span_mappers.hpp"
#include "exactpixels/texture/texture_mapper.hpp"

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

namespace exactpixels {

/// The stages a mesh's pipeline is built from.
struct MeshStages {
    bool texture = false; ///< texture coordinates are interpolated and sampled
    bool colour = false;  ///< vertex colours are interpolated
    bool tint = false;    ///< a flat colour other than white multiplies the texels
};

/// The stages `mesh` calls for (the per-triangle choices, perspective or not and
/// clipping or not, are made per triangle by the renderer).
MeshStages plan_mesh(const SceneMesh& mesh);

/// True when the three depths are equal: u and v are then linear on screen and the
/// affine mapper is exact (@eq:scene-constant-w).
bool constant_depth(double w0, double w1, double w2);

/// The worst error of the quadratic mapper over a span of depth ratio r, as a fraction
/// of the span's texel extent: the bound of @eq:scene-quadratic-bound, the smaller of
/// (sqrt 3 / 18) (s - 1)^2 / (s + 1) and (s - 1)^2 / (4 (s + 1) sqrt s), s = max(r, 1/r).
/// r > 0. Never below the true worst error (quadratic_error_max of chapter 3), and
/// within a factor 3.1 of it for r in [1/64, 64].
double quadratic_error_bound(double r);

/// The worst texel error of the chord from pixel k0 to pixel k1 of the span (the exact
/// values at both ends joined by a straight line), from chapter 3's affine bound
/// (@eq:affine-bound): the larger of the bounds for u and for v.
double chord_error_bound(const PerspectiveSpan<double>& s, int k0, int k1);

/// The same for Pursey's parabola from pixel k0 to pixel k1 (@eq:scene-quadratic-bound).
double parabola_error_bound(const PerspectiveSpan<double>& s, int k0, int k1);

/// The result of the auto choice for one span: the mapper and the divides spent
/// choosing it (the bounds need the exact values at the ends).
struct AutoChoice {
    Mapper mapper;         ///< the cheapest mapper within the budget
    long long divides = 0; ///< divides the choice itself performed
};

/// `auto` for one span whose depth varies: the mapper with the fewest divides whose
/// derived error bound is within `budget` texels, trying in order the chord (one
/// subdivided piece), the quadratic, subdivided pieces of halving length, and exact.
/// budget > 0.
AutoChoice choose_span_mapper(const PerspectiveSpan<double>& s, double budget);

/// The worst texel error of the affine mapper over a whole triangle whose corners have
/// depths w > 0 and texture coordinates uv, against the perspective-correct
/// coordinates (@eq:scene-triangle-bound): the larger corner range of u and of v times
/// (sqrt r - 1) / (sqrt r + 1), r = w_max / w_min.
double triangle_affine_error_bound(const std::array<TexturedVertex, 3>& corners);

/// Whether triangle_affine_error_bound(corners) <= budget, decided without a divide or
/// a square root. budget > 0.
bool triangle_affine_fits(const std::array<TexturedVertex, 3>& corners, double budget);

/// How many divides chapter 3's mapper performs on a span of `count` pixels (the same
/// for every precision): exact count; affine 0; subdivided 1 + 3 P; quadratic 10;
/// quadratic subdivided 10 P; P = ceil(count / span) pieces (@eq:scene-divides).
long long mapper_divides(Mapper mapper, int count);

/// The worst error, in 8-bit levels (1/255), of a colour interpolated linearly on
/// screen over a triangle whose corners have depths w (> 0) and colours c, against the
/// perspective-correct colour: 2 affine_error_bound(w_max / w_min) times the largest
/// channel range, times 255 (@eq:scene-colour-bound). Zero when the depths are equal.
double colour_error_bound(const std::array<double, 3>& w, const std::array<Colour, 3>& c);

//> depth-plan
/// The smallest screen rectangle holding some points, pixels (empty until a point is
/// added).
struct ScreenBox {
    double x0 = std::numeric_limits<double>::infinity();  ///< left
    double y0 = std::numeric_limits<double>::infinity();  ///< top
    double x1 = -std::numeric_limits<double>::infinity(); ///< right
    double y1 = -std::numeric_limits<double>::infinity(); ///< bottom
    /// Grows the box to hold p. (Inline: the geometry stage calls it at every corner.)
    void add(Point2 p) {
        x0 = std::min(x0, p.x);
        y0 = std::min(y0, p.y);
        x1 = std::max(x1, p.x);
        y1 = std::max(y1, p.y);
    }
    /// The part of the box inside the viewport [0, width] x [0, height] (may be empty).
    ScreenBox clipped(Viewport viewport) const;
    /// True when the box holds no point.
    bool empty() const { return x0 > x1 || y0 > y1; }
    /// True when the two closed boxes share a point.
    bool intersects(const ScreenBox& other) const;
};

/// What the depth plan needs to know of a mesh after the geometry stage.
struct MeshFootprint {
    std::string name;                ///< for the report: its key path, mesh[k]
    ScreenBox box;                   ///< around its projected, unculled triangles
    bool can_overlap_itself = false; ///< can_overlap_itself(mesh)
};

/// True unless the mesh provably cannot cover a pixel twice at different depths: one
/// triangle; all its corners in one plane (overlaps there are ties, which go to the
/// later triangle as without depth); or back-culled and convex (every corner on one side
/// of every triangle's plane, so the faces left after culling do not overlap).
bool can_overlap_itself(const SceneMesh& mesh);

/// The depth stage's decision and the reason the report shows.
struct DepthPlan {
    bool on = false;    ///< run the depth stage
    std::string reason; ///< e.g. "auto: mesh[0] and mesh[2] overlap on screen"
};

/// `depth = true` and `false` decide alone; `auto` turns the stage on when a mesh can
/// overlap itself or two meshes' screen boxes (inside the viewport) intersect, the only
/// ways two surfaces can reach the same pixel.
DepthPlan plan_depth(DepthMode mode, const std::vector<MeshFootprint>& meshes,
                     Viewport viewport);
//< depth-plan

} // namespace exactpixels
