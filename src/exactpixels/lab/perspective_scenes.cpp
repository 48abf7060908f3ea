#include "exactpixels/lab/perspective_scenes.hpp"

#include "exactpixels/texture/perspective.hpp"

#include <cassert>
#include <cmath>

namespace exactpixels {

namespace {
Pinhole camera_for(int width, int height) {
    assert(width >= 1 && height >= 1);
    return {0.625 * width, {0.5 * width, 0.5 * height}};
}

/// Two triangles covering the quad a b c d (in that order around it).
std::vector<std::array<TexturedVertex, 3>> quad(TexturedVertex a, TexturedVertex b,
                                                TexturedVertex c, TexturedVertex d) {
    return {{a, b, c}, {a, c, d}};
}
} // namespace

//> floor-scene
PerspectiveScene floor_scene(int width, int height) {
    const Pinhole eye = camera_for(width, height);
    constexpr double near = 1.2, far = 40.0, half_width = 4.0, texels_per_unit = 16.0;
    constexpr double roll = 0.35; // radians: the camera banks 20 degrees
    const double c = std::cos(roll), s = std::sin(roll);
    const auto corner = [&](double x, double z) { // a floor point, one unit below the eye
        const glm::dvec3 seen{c * x + s, -s * x - c,
                              z}; // (x, -1, z) rolled about the view axis
        return project(eye, seen,
                       {(x + half_width) * texels_per_unit, (far - z) * texels_per_unit});
    };
    return {quad(corner(-half_width, near), corner(half_width, near),
                 corner(half_width, far), corner(-half_width, far)),
            checkerboard_texture(64, 64, 8), Wrap::repeat};
}
//< floor-scene

PerspectiveScene wall_scene(int width, int height) {
    const Pinhole eye = camera_for(width, height);
    constexpr double near = 1.0, far = 60.0, bottom = -1.0, top = 2.0;
    const auto corner = [&](double y, double z) { // a wall point, 1.5 units to the right
        return project(eye, {1.5, y, z}, {z * 4.0, (top - y) * 16.0});
    };
    return {quad(corner(bottom, near), corner(bottom, far), corner(top, far),
                 corner(top, near)),
            f_texture(4), Wrap::repeat};
}

void draw_scene(Framebuffer& frame, const PerspectiveScene& scene,
                MapperSettings settings) {
    settings.wrap = scene.wrap;
    for (const auto& triangle : scene.triangles) {
        draw_textured_triangle(frame, triangle, scene.texture, settings);
    }
}

void map_scene(TexelMap& map, const PerspectiveScene& scene,
               const MapperSettings& settings) {
    for (const auto& triangle : scene.triangles) {
        map_textured_triangle(map, triangle, settings);
    }
}

} // namespace exactpixels
