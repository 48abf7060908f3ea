// camera.hpp: the camera and the projection of chapter 7's renderer: the camera's axes,
// chapter 3's pinhole (or the orthographic scale) from view space to the screen, the eye
// direction lighting needs, and the planes of view space that bound what the camera
// draws. Inline: the geometry stage calls these on every corner and every triangle.
//
// Usage:
//   const CameraFrame camera = camera_frame(scene.camera);
//   const Pinhole lens = pinhole(scene);
//   const TexturedVertex corner = project_vertex(scene, lens, view_vertex);
//   const ViewVolume volume = view_volume(scene, lens);
//   if (outside_one(volume.reject, view)) { /* covers no pixel */ }
#pragma once

#include "exactpixels/scene/scene.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "exactpixels/texture/clipping.hpp"
#include "exactpixels/texture/perspective.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace exactpixels {

/// The camera's axes in world space (@eq:scene-look-at).
struct CameraFrame {
    glm::dvec3 eye;     ///< the camera's position
    glm::dvec3 right;   ///< the view x axis (unit)
    glm::dvec3 up;      ///< the view y axis (unit)
    glm::dvec3 forward; ///< the view z axis, towards the target (unit)
};

/// The axes of `camera`: forward towards the target, right = up x forward normalised,
/// up = forward x right.
inline CameraFrame camera_frame(const SceneCamera& camera) {
    const glm::dvec3 forward = glm::normalize(camera.target - camera.position);
    const glm::dvec3 right = glm::normalize(glm::cross(camera.up, forward));
    return {camera.position, right, glm::cross(forward, right), forward};
}

//> project-vertex
/// Chapter 3's pinhole for a perspective camera: the focal length in pixels from the
/// vertical field of view, the view axis through the image centre (@eq:scene-focal).
inline Pinhole pinhole(const Scene& scene) {
    const double half_angle = 0.5 * scene.camera.fov_degrees * std::acos(-1.0) / 180.0;
    return {0.5 * scene.height / std::tan(half_angle),
            {0.5 * scene.width, 0.5 * scene.height}};
}

/// View space to screen: pixels (origin top-left, y down) and the depth w. The
/// orthographic camera keeps x and y (scaled) and gives every point w = 1.
inline TexturedVertex project_vertex(const Scene& scene, const Pinhole& camera,
                                     const ViewVertex& v) {
    if (scene.camera.projection == Projection::perspective) {
        return project(camera, v.position, v.uv); // w = z >= near > 0
    }
    const double scale = scene.height / scene.camera.view_height; // pixels per unit
    return {camera.centre + scale * Point2{v.position.x, -v.position.y}, 1.0, v.uv};
}
//< project-vertex

/// The unit vector from a view-space point to the eye: towards the origin for a
/// pinhole, along -z everywhere for parallel rays.
inline glm::dvec3 to_eye(const Scene& scene, glm::dvec3 p) {
    return scene.camera.projection == Projection::perspective
               ? glm::normalize(-p)
               : glm::dvec3{0.0, 0.0, -1.0};
}

//> view-volume
/// The planes of view space that bound what a camera draws (@eq:scene-guard-band).
struct ViewVolume {
    /// The screen's four edges, then near and far: a triangle wholly outside any one
    /// covers no pixel.
    std::vector<ViewPlane> reject;
    /// Near, far, then the guard band's four planes: the planes a triangle is cut at.
    std::vector<ViewPlane> clip;
};

/// The view volume of the scene's camera. A screen line x = s is the view-space plane
/// (cx - s) z + f x = 0 under perspective (multiplied by z > 0, which keeps the sign),
/// (cx - s) + k x = 0 orthographic; y = s likewise with y pointing up in view space.
/// An orthographic camera has no near or far plane (it never had).
inline ViewVolume view_volume(const Scene& scene, const Pinhole& lens) {
    const bool perspective = scene.camera.projection == Projection::perspective;
    const double scale =
        perspective ? lens.focal : scene.height / scene.camera.view_height;
    const auto plane = [&](glm::dvec2 axis, double offset) { // offset times z or 1
        return perspective ? ViewPlane{{scale * axis.x, scale * axis.y, offset}, 0.0}
                           : ViewPlane{{scale * axis.x, scale * axis.y, 0.0}, offset};
    };
    const double cx = lens.centre.x, cy = lens.centre.y;
    const auto x_at_least = [&](double s) { return plane({1.0, 0.0}, cx - s); };
    const auto x_at_most = [&](double s) { return plane({-1.0, 0.0}, s - cx); };
    const auto y_at_least = [&](double s) { return plane({0.0, -1.0}, cy - s); };
    const auto y_at_most = [&](double s) { return plane({0.0, 1.0}, s - cy); };
    ViewVolume volume;
    volume.reject = {x_at_least(0.0), x_at_most(scene.width), y_at_least(0.0),
                     y_at_most(scene.height)};
    if (perspective) {
        volume.clip.push_back(near_plane(scene.camera.near)); // first: then z > 0
        if (std::isfinite(scene.camera.far)) {
            volume.clip.push_back({{0.0, 0.0, -1.0}, scene.camera.far});
        }
        volume.reject.insert(volume.reject.end(), volume.clip.begin(), volume.clip.end());
    }
    const double band = guard_band_px;
    for (const ViewPlane& p :
         {x_at_least(-band), x_at_most(band), y_at_least(-band), y_at_most(band)}) {
        volume.clip.push_back(p);
    }
    return volume;
}

/// Whether all three corners lie outside one plane (each plane_value < 0).
inline bool outside_one(const std::vector<ViewPlane>& planes,
                        const std::array<ViewVertex, 3>& v) {
    return std::any_of(planes.begin(), planes.end(), [&](const ViewPlane& p) {
        return plane_value(p, v[0].position) < 0.0 &&
               plane_value(p, v[1].position) < 0.0 && plane_value(p, v[2].position) < 0.0;
    });
}

/// Whether some corner lies outside some plane.
inline bool any_outside(const std::vector<ViewPlane>& planes,
                        const std::array<ViewVertex, 3>& v) {
    return std::any_of(planes.begin(), planes.end(), [&](const ViewPlane& p) {
        return plane_value(p, v[0].position) < 0.0 ||
               plane_value(p, v[1].position) < 0.0 || plane_value(p, v[2].position) < 0.0;
    });
}
//< view-volume

} // namespace exactpixels
