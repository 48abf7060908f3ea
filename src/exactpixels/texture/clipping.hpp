// clipping.hpp: cutting a view-space triangle at the near plane before it is projected,
// so that no vertex at or behind the eye is ever divided by its depth.
//
// Usage:
//   std::array<ViewVertex, 3> t{{{{-1.0, -1.0, 4.0}, {0.0, 0.0}},
//                                {{1.0, -1.0, -2.0}, {64.0, 0.0}},     // behind the eye
//                                {{0.0, 1.0, 4.0}, {32.0, 64.0}}}};
//   ClippedTriangles c = clip_near(t, 0.5);              // 0, 1 or 2 triangles
//   draw_view_triangle(frame, camera, t, 0.5, texture, settings); // clip, project, draw
//
// View space is perspective.hpp's: the eye at the origin looking along +z, x right, y
// up; z is the depth that becomes the mapper's w. The near plane is z = near (near > 0,
// any unit of view space). clip_near keeps the part of the triangle with z >= near: a
// vertex exactly on the plane counts as in front. Every vertex it returns has z >= near
// (new vertices have z = near exactly), so projecting them divides by at least `near`.
// A new vertex on the edge from an inside corner a to an outside corner b is
// a + t (b - a) with t = (a.z - near) / (a.z - b.z) (chapter 6, @eq:clip-t): the
// denominator is > 0 whenever the edge crosses, and the position and the texture
// coordinate are interpolated with the same t, which is right because both are linear
// along a view-space edge. The winding of the input is kept. Non-finite coordinates
// and a near that is not finite and > 0 throw Error naming the value.
//
// clip_polygon generalises clip_near to any plane a x + b y + c z + d >= 0 (ViewPlane):
// the near plane is {0, 0, 1, -near}, the far plane {0, 0, -1, far}, and the guard-band
// planes of chapter 7 pass through the eye. It too always interpolates from the inside
// corner to the outside one, so an edge shared by two triangles is cut at the same point
// whichever way each walks it, plane after plane (@sec:scene-clipping). A plane whose
// normal is (0, 0, +-1) puts the new corner's z on the plane exactly, as clip_near does.
#pragma once

#include "exactpixels/base/framebuffer.hpp"
#include "exactpixels/base/types.hpp"
#include "exactpixels/texture/perspective.hpp"
#include "exactpixels/texture/texture.hpp"
#include "exactpixels/texture/texture_mapper.hpp"

#include <glm/glm.hpp>

#include <array>
#include <vector>

namespace exactpixels {

/// A triangle corner in view space, before projection.
struct ViewVertex {
    glm::dvec3 position; ///< view space: x right, y up, z the depth along the view axis
    TexCoord uv;         ///< texture coordinate in texels
};

/// What is left of one triangle in front of the near plane: 0, 1 or 2 triangles.
struct ClippedTriangles {
    int count = 0;                                      ///< triangles used, 0 .. 2
    std::array<std::array<ViewVertex, 3>, 2> triangles; ///< the first `count` are valid
};

/// The point where the edge from `inside` (z >= near) to `outside` (z < near) meets the
/// plane z = near: z is set to near exactly, uv interpolated with the same parameter.
ViewVertex near_crossing(const ViewVertex& inside, const ViewVertex& outside,
                         double near);

/// The part of the triangle with z >= near, as 0 to 2 triangles of the same winding.
/// Throws Error for a non-finite coordinate or a near that is not finite and > 0.
ClippedTriangles clip_near(const std::array<ViewVertex, 3>& v, double near);

/// A plane of view space, a x + b y + c z + d = 0; its inside is where the sum is >= 0.
struct ViewPlane {
    glm::dvec3 normal; ///< (a, b, c), not necessarily of length 1
    double offset;     ///< d
};

/// a x + b y + c z + d at p: >= 0 inside the plane, < 0 outside.
/// (Inline: the geometry stage tests every corner of every triangle against six planes.)
inline double plane_value(const ViewPlane& plane, glm::dvec3 p) {
    return plane.normal.x * p.x + plane.normal.y * p.y + plane.normal.z * p.z +
           plane.offset;
}

/// The near plane z = near as a ViewPlane: {0, 0, 1, -near}.
ViewPlane near_plane(double near);

/// The point where the edge from `inside` (plane_value >= 0) to `outside` (< 0) meets the
/// plane, uv interpolated with the same parameter; for the near plane it equals
/// near_crossing bit for bit.
ViewVertex plane_crossing(const ViewVertex& inside, const ViewVertex& outside,
                          const ViewPlane& plane);

/// The most corners a triangle keeps after clipping at max_clip_planes planes: each
/// plane adds at most one corner to a convex polygon.
inline constexpr int max_clip_planes = 6;
/// 3 + max_clip_planes.
inline constexpr int max_clipped_corners = 3 + max_clip_planes;

/// A convex polygon in view space, what is left of a triangle after clipping.
struct ClippedPolygon {
    int count = 0;                                         ///< corners used
    std::array<ViewVertex, max_clipped_corners> corners{}; ///< the first `count`
};

/// The part of `polygon` inside `plane` (the Sutherland-Hodgman step of chapter 6's
/// clip_near, for any plane). Requires polygon.count < max_clipped_corners.
ClippedPolygon clip_polygon(const ClippedPolygon& polygon, const ViewPlane& plane);

/// The part of the triangle inside every plane, in order, as a polygon of the same
/// winding. Throws Error for a non-finite coordinate or more than max_clip_planes
/// planes (the polygon could outgrow ClippedPolygon).
ClippedPolygon clip_triangle(const std::array<ViewVertex, 3>& v,
                             const std::vector<ViewPlane>& planes);

/// The triangles of clip_near(v, near) projected by the camera (perspective.hpp): the
/// TexturedVertex triangles chapter 3's mappers draw, every w >= near.
struct ProjectedTriangles {
    int count = 0;                                          ///< triangles used, 0 .. 2
    std::array<std::array<TexturedVertex, 3>, 2> triangles; ///< the first `count`
};

/// Clips at the near plane, then projects each remaining triangle.
ProjectedTriangles clip_and_project(const Pinhole& camera,
                                    const std::array<ViewVertex, 3>& v, double near);

/// Clips, projects and draws the view-space triangle with a mapper of chapter 3.
/// Checks all input first: on Error nothing is drawn.
void draw_view_triangle(Framebuffer& frame, const Pinhole& camera,
                        const std::array<ViewVertex, 3>& v, double near,
                        const Texture& texture, const MapperSettings& settings);

} // namespace exactpixels
