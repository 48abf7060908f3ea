#include "exactpixels/texture/clipping.hpp"

#include "exactpixels/base/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace exactpixels {

namespace {
void check_clip_input(const std::array<ViewVertex, 3>& v, double near,
                      const char* who = "clip_near") {
    if (!std::isfinite(near) || !(near > 0.0)) {
        throw Error(fmt::format("{}: near = {} (must be finite and > 0)", who, near));
    }
    for (int k = 0; k < 3; ++k) {
        const ViewVertex& p = v[static_cast<std::size_t>(k)];
        for (const double c :
             {p.position.x, p.position.y, p.position.z, p.uv.x, p.uv.y}) {
            if (!std::isfinite(c)) {
                throw Error(fmt::format("{}: vertex {} has a coordinate {} "
                                        "(position and uv must be finite)",
                                        who, k, c));
            }
        }
    }
}
} // namespace

//> near-crossing
ViewVertex near_crossing(const ViewVertex& inside, const ViewVertex& outside,
                         double near) {
    assert(inside.position.z >= near && outside.position.z < near);
    // @eq:clip-t: the denominator is at least inside.z - near >= 0 plus a positive part.
    const double t =
        (inside.position.z - near) / (inside.position.z - outside.position.z);
    ViewVertex p{inside.position + t * (outside.position - inside.position),
                 inside.uv + t * (outside.uv - inside.uv)};
    p.position.z = near; // on the plane exactly, whatever the rounding of t
    return p;
}
//< near-crossing

//> clip-near
ClippedTriangles clip_near(const std::array<ViewVertex, 3>& v, double near) {
    check_clip_input(v, near);
    ClippedTriangles out{};
    //> exercise ch06-clip-near: walk the edges, keep inside corners, add crossings.
    std::array<ViewVertex, 4> polygon{}; // one plane cuts a triangle into <= 4 corners
    int n = 0;
    for (std::size_t k = 0; k < 3; ++k) {
        const ViewVertex& a = v[k];
        const ViewVertex& b = v[(k + 1) % 3];
        const bool a_in = a.position.z >= near, b_in = b.position.z >= near;
        if (a_in) {
            polygon[static_cast<std::size_t>(n++)] = a;
        }
        if (a_in != b_in) { // the edge crosses: always interpolate inside -> outside
            polygon[static_cast<std::size_t>(n++)] =
                a_in ? near_crossing(a, b, near) : near_crossing(b, a, near);
        }
    }
    // A fan from the first corner: 3 corners give 1 triangle, 4 give 2.
    for (int k = 1; k + 1 < n; ++k) {
        out.triangles[static_cast<std::size_t>(out.count++)] = {
            polygon[0], polygon[static_cast<std::size_t>(k)],
            polygon[static_cast<std::size_t>(k + 1)]};
    }
    //| const bool all_in = v[0].position.z >= near && v[1].position.z >= near &&
    //|                     v[2].position.z >= near;
    //| if (all_in) {
    //|     out.triangles[0] = v; // stub: keep whole triangles, drop any that cross
    //|     out.count = 1;
    //| }
    //< exercise ch06-clip-near
    return out;
}
//< clip-near

ViewPlane near_plane(double near) {
    return {{0.0, 0.0, 1.0}, -near};
}

//> plane-crossing
ViewVertex plane_crossing(const ViewVertex& inside, const ViewVertex& outside,
                          const ViewPlane& plane) {
    const double in = plane_value(plane, inside.position);
    const double out = plane_value(plane, outside.position);
    // A corner made by an earlier plane from huge coordinates may be NaN (0 times
    // infinity); it passes here, and project() refuses it, naming the triangle.
    assert(!(in < 0.0) && !(out >= 0.0));
    // @eq:clip-t for any plane: t = in / (in - out), the denominator written as the plane
    // normal times the edge, which for the near plane is clip_near's a.z - b.z bit for
    // bit. Should rounding make it <= 0 or t leave [0, 1] (an edge almost in the plane),
    // in - out (exactly > 0) and the clamp keep the new corner on the edge.
    double denominator = glm::dot(plane.normal, inside.position - outside.position);
    if (!(denominator > 0.0)) {
        denominator = in - out;
    }
    const double t = std::clamp(in / denominator, 0.0, 1.0);
    ViewVertex p{inside.position + t * (outside.position - inside.position),
                 inside.uv + t * (outside.uv - inside.uv)};
    if (plane.normal.x == 0.0 && plane.normal.y == 0.0) { // near or far: z exactly
        p.position.z = -plane.offset / plane.normal.z;
    }
    return p;
}
//< plane-crossing

//> clip-polygon
ClippedPolygon clip_polygon(const ClippedPolygon& polygon, const ViewPlane& plane) {
    assert(polygon.count < max_clipped_corners);
    ClippedPolygon out{};
    for (int k = 0; k < polygon.count; ++k) {
        const ViewVertex& a = polygon.corners[static_cast<std::size_t>(k)];
        const ViewVertex& b =
            polygon.corners[static_cast<std::size_t>((k + 1) % polygon.count)];
        const bool a_in = plane_value(plane, a.position) >= 0.0;
        const bool b_in = plane_value(plane, b.position) >= 0.0;
        if (a_in) {
            out.corners[static_cast<std::size_t>(out.count++)] = a;
        }
        if (a_in != b_in) { // always interpolate inside -> outside, as clip_near does
            out.corners[static_cast<std::size_t>(out.count++)] =
                a_in ? plane_crossing(a, b, plane) : plane_crossing(b, a, plane);
        }
    }
    return out;
}
//< clip-polygon

ClippedPolygon clip_triangle(const std::array<ViewVertex, 3>& v,
                             const std::vector<ViewPlane>& planes) {
    check_clip_input(v, 1.0, "clip_triangle");
    if (planes.size() > static_cast<std::size_t>(max_clip_planes)) { // would overflow
        throw Error(fmt::format("clip_triangle: {} planes (at most {})", planes.size(),
                                max_clip_planes));
    }
    ClippedPolygon polygon{3, {v[0], v[1], v[2]}};
    for (const ViewPlane& plane : planes) {
        polygon = clip_polygon(polygon, plane);
        if (polygon.count < 3) {
            return {};
        }
    }
    return polygon;
}

ProjectedTriangles clip_and_project(const Pinhole& camera,
                                    const std::array<ViewVertex, 3>& v, double near) {
    const ClippedTriangles c = clip_near(v, near);
    ProjectedTriangles out{};
    for (int k = 0; k < c.count; ++k) {
        const auto& t = c.triangles[static_cast<std::size_t>(k)];
        out.triangles[static_cast<std::size_t>(k)] = {
            project(camera, t[0].position, t[0].uv),
            project(camera, t[1].position, t[1].uv),
            project(camera, t[2].position, t[2].uv)};
    }
    out.count = c.count;
    return out;
}

void draw_view_triangle(Framebuffer& frame, const Pinhole& camera,
                        const std::array<ViewVertex, 3>& v, double near,
                        const Texture& texture, const MapperSettings& settings) {
    const ProjectedTriangles p = clip_and_project(camera, v, near);
    for (int k = 0; k < p.count; ++k) { // check every piece before drawing any
        check_textured_triangle(p.triangles[static_cast<std::size_t>(k)], settings);
    }
    for (int k = 0; k < p.count; ++k) {
        draw_textured_triangle(frame, p.triangles[static_cast<std::size_t>(k)], texture,
                               settings);
    }
}

} // namespace exactpixels
