// live_scenes.hpp: what two live figures draw, built in code so that the WebAssembly
// module (live_figures.cpp) and the interactive test (tests/interactive_figures.cpp,
// natively) give the library the same input for the same reader's settings.
//
// Chapter 8's tilted floor (ch08-level): two triangles, projected by chapter 3's
// pinhole. Chapter 7's small scene (ch07-scene): a checkered floor of 32 triangles running under the camera, a back-culled box on it
// and a second box, not culled, passing through the first: moving the camera about
// them makes the geometry stage reject, clip and cull triangles and the depth stage
// decide between the boxes. The renderer is the library's (render_scene); this file holds
// only the figures' data.
#pragma once

#include "exactpixels/scene/scene.hpp"
#include "exactpixels/texture/perspective.hpp"

#include <array>
#include <cmath>

namespace exactpixels::live {

/// Chapter 8's figure: a 48 x 32 px pinhole, 60 degrees high.
inline constexpr int floor_width = 48;
inline constexpr int floor_height = 32;
inline constexpr double floor_texels_per_unit = 8.0;

/// Whether the figure's floor may be tilted by `tilt` degrees at `distance` units.
inline bool floor_allowed(double tilt, double distance) {
    return tilt >= 0 && tilt <= 80 && distance >= 4 && distance <= 12;
}

/// The pinhole of chapter 8's figure: centred, its focal length from the 60 degrees.
inline Pinhole floor_lens() {
    return {0.5 * floor_height / std::tan(std::acos(-1.0) / 6),
            {0.5 * floor_width, 0.5 * floor_height}};
}

/// The floor of chapter 8's figure: a square of 6 x 6 units, 8 texels per unit, its
/// centre `distance` units down the view axis, tilted by `tilt` degrees about its
/// horizontal axis with its top edge away from the eye (0: facing the camera); its two
/// triangles as projected by the figure's pinhole (project). floor_allowed must hold.
inline std::array<std::array<TexturedVertex, 3>, 2> tilted_floor(double tilt,
                                                                 double distance) {
    const double a = tilt * std::acos(-1.0) / 180.0, half = 3.0;
    const double s = floor_texels_per_unit;
    const Pinhole lens = floor_lens();
    const auto corner = [&](double x, double t) { // t: up the floor and away
        return project(lens, {x, t * std::cos(a), distance + t * std::sin(a)},
                       {s * (x + half), s * (half - t)});
    };
    const TexturedVertex c00 = corner(-half, -half), c10 = corner(half, -half),
                         c11 = corner(half, half), c01 = corner(-half, half);
    return {{{c00, c10, c11}, {c00, c11, c01}}};
}

/// The image: small, so that a render per triangle costs little in the page.
inline constexpr int scene_width = 64;
inline constexpr int scene_height = 40;
/// The camera's height above the floor and the point it looks at.
inline constexpr double camera_height = 1.5;
inline constexpr glm::dvec3 scene_target = {0.0, 0.8, 0.0};
/// The camera stays within this square of the floor plan and at least this far (in
/// the plan) from the target, where its forward axis would turn vertical.
inline constexpr double camera_reach = 7.0;
inline constexpr double camera_min_distance = 1.0;

/// Whether the camera may stand at (x, z) of the floor plan.
inline bool camera_allowed(double x, double z) {
    return std::isfinite(x) && std::isfinite(z) && std::abs(x) <= camera_reach &&
           std::abs(z) <= camera_reach &&
           std::hypot(x - scene_target.x, z - scene_target.z) >= camera_min_distance;
}

/// Adds the quad a b c d (in order around it) as two triangles facing along `outward`:
/// corners counter-clockwise seen from that side, as back-face culling takes a front
/// face in the left-handed world (x right, y up, z forward; chapter 7's box primitive).
inline void add_face(SceneMesh& mesh, std::array<glm::dvec3, 4> q, glm::dvec3 outward,
                     Colour colour) {
    if (glm::dot(glm::cross(q[1] - q[0], q[2] - q[0]), outward) > 0.0) {
        std::swap(q[1], q[3]); // the other way round
    }
    const auto at = [&](int k) { return SceneVertex{q[k], {0.0, 0.0}, colour}; };
    mesh.triangles.push_back({at(0), at(1), at(2)});
    mesh.triangles.push_back({at(0), at(2), at(3)});
}

/// A box of six faces, each in its own shade of `colour` so that the faces show apart.
inline SceneMesh box_mesh(const char* name, glm::dvec3 centre, glm::dvec3 half,
                          Colour colour, bool cull_back) {
    SceneMesh mesh;
    mesh.name = name;
    mesh.origin = std::string("live_scenes.hpp: ") + name;
    mesh.vertex_colours = true;
    mesh.cull_back = cull_back;
    for (int axis = 0; axis < 3; ++axis) {
        for (const double side : {-1.0, 1.0}) {
            const int a = (axis + 1) % 3, b = (axis + 2) % 3;
            std::array<glm::dvec3, 4> q;
            const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
            for (int k = 0; k < 4; ++k) {
                glm::dvec3 p = centre;
                p[axis] += side * half[axis];
                p[a] += corners[k][0] * half[a];
                p[b] += corners[k][1] * half[b];
                q[static_cast<std::size_t>(k)] = p;
            }
            glm::dvec3 outward{0.0};
            outward[axis] = side;
            const double shade = 0.55 + 0.15 * axis + (side > 0 ? 0.0 : 0.05);
            add_face(mesh, q, outward, colour * shade);
        }
    }
    return mesh;
}

/// The scene seen from (x, camera_height, z): see the top of the file.
inline Scene live_scene(double camera_x, double camera_z) {
    Scene scene;
    scene.file = "live_scenes.hpp";
    scene.width = scene_width;
    scene.height = scene_height;
    scene.background = {0.75, 0.85, 0.95};
    scene.camera.fov_degrees = 60.0;
    scene.camera.position = {camera_x, camera_height, camera_z};
    scene.camera.target = scene_target;
    scene.camera.near = 0.5;
    scene.camera.far = 12.0;
    // The floor: 4 x 4 squares of 3 units, two meshes (light and dark squares).
    for (int shade = 0; shade < 2; ++shade) {
        SceneMesh floor;
        floor.name = shade == 0 ? "light floor" : "dark floor";
        floor.origin = "live_scenes.hpp: " + floor.name;
        floor.colour = shade == 0 ? Colour{0.9, 0.9, 0.85} : Colour{0.45, 0.5, 0.45};
        floor.cull_back = true;
        for (int i = 0; i < 4; ++i) {
            for (int j = 0; j < 4; ++j) {
                if ((i + j) % 2 != shade) {
                    continue;
                }
                const double x = -6.0 + 3.0 * i, z = -6.0 + 3.0 * j;
                add_face(floor, {glm::dvec3{x, 0, z}, {x + 3, 0, z}, {x + 3, 0, z + 3},
                                 {x, 0, z + 3}},
                         {0.0, 1.0, 0.0}, {1.0, 1.0, 1.0});
            }
        }
        scene.meshes.push_back(floor);
    }
    scene.meshes.push_back(
        box_mesh("culled box", {0.0, 1.0, 0.0}, {1.0, 1.0, 1.0}, {0.3, 0.5, 1.0}, true));
    scene.meshes.push_back(box_mesh("box through it, not culled", {1.2, 0.6, 0.8},
                                    {1.4, 0.4, 0.4}, {1.0, 0.6, 0.2}, false));
    return scene;
}

} // namespace exactpixels::live
