// section_camera.cpp: a scene's [camera]: the projection, the near and far planes, and
// where it stands and looks (chapter 7, @eq:scene-look-at).
#include "exactpixels/scene/scene_sections.hpp"

namespace exactpixels::scene_format {

void read_camera(const Context& c, const toml::table& table, SceneCamera& camera) {
    const TableReader t(
        c, table, "camera",
        {"projection", "fov", "view_height", "near", "far", "position", "target", "up"});
    if (const auto* n = t.find("projection")) {
        camera.projection = read_choice(c, *n, t.child("projection"),
                                        {"perspective", "orthographic"}) == 0
                                ? Projection::perspective
                                : Projection::orthographic;
    }
    if (const auto* n = t.find("fov")) {
        camera.fov_degrees = read_positive(c, *n, t.child("fov"), 0.0, 179.0);
    }
    if (const auto* n = t.find("view_height")) {
        camera.view_height =
            read_positive(c, *n, t.child("view_height"), 0.0, world_limit);
    }
    if (const auto* n = t.find("near")) {
        camera.near = read_number(c, *n, t.child("near"), min_camera_near, world_limit);
    }
    if (const auto* n = t.find("far")) { // finite (read_number), and beyond near
        camera.far = read_number(c, *n, t.child("far"), min_camera_near, world_limit);
        if (!(camera.far > camera.near)) {
            c.fail(n->source(), t.child("far"),
                   fmt::format("{} must be greater than near ({})", camera.far,
                               camera.near));
        }
    }
    if (const auto* n = t.find("position")) {
        camera.position = read_point(c, *n, t.child("position"));
    }
    if (const auto* n = t.find("target")) {
        camera.target = read_point(c, *n, t.child("target"));
    }
    if (const auto* n = t.find("up")) {
        camera.up = read_point(c, *n, t.child("up"));
    }
    // The view direction and up must span a plane (chapter 7, @eq:scene-look-at).
    const glm::dvec3 forward = camera.target - camera.position;
    if (glm::length(glm::cross(forward, camera.up)) <=
            1e-12 * glm::length(forward) * glm::length(camera.up) ||
        glm::length(forward) == 0.0) {
        c.fail(t.table().source(), t.path(),
               "the camera looks along its up direction, or at its own position");
    }
    t.finish();
}

} // namespace exactpixels::scene_format
