// Chapter 6: what a vertex behind the eye does without clipping, and with it.
// Usage: fig_ch06_near_clip FIGURE_DIR  (writes ch06_near_clip.png)
// A floor triangle runs from in front of the camera to behind it. Left: each corner
// divided by its own depth with no clipping; the corner behind the eye (z < 0) lands
// on the wrong side of the screen, and the triangle drawn between the three screen
// points covers the sky instead of the floor (drawn flat red: no mapper accepts w < 0).
// Right: clipped at the near plane first, then projected and textured (the "F").
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/raster/scanline.hpp"
#include "exactpixels/texture/clipping.hpp"

#include <cstdio>
#include <filesystem>

using namespace exactpixels;

int main(int argc, char** argv) try {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    constexpr int w = 240, h = 180;
    const Pinhole camera{150.0, {w / 2.0, h / 2.0}};
    const std::array<ViewVertex, 3> floor{{{{-3.0, -1.0, 6.0}, {0.0, 0.0}},
                                           {{3.0, -1.0, 6.0}, {60.0, 0.0}},
                                           {{0.5, -1.0, -2.0}, {30.0, 80.0}}}};
    //> unsafe-projection
    Framebuffer unsafe(w, h, rgba(20, 20, 40));
    std::array<Point2, 3> naive{};
    for (std::size_t k = 0; k < 3; ++k) { // x / z with z < 0 flips the point over
        const glm::dvec3 p = floor[k].position;
        naive[k] = {camera.centre.x + camera.focal * p.x / p.z,
                    camera.centre.y - camera.focal * p.y / p.z};
    }
    scanline_spans(naive, Viewport{w, h}, [&](Span s) {
        for (int x = s.x_begin; x < s.x_end; ++x) {
            unsafe.at(x, s.y) = rgba(220, 40, 40);
        }
    });
    //< unsafe-projection
    Framebuffer safe(w, h, rgba(20, 20, 40));
    draw_view_triangle(safe, camera, floor, 0.1, f_texture(4), {});
    Framebuffer both(2 * w + 8, h, rgba(255, 255, 255));
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            both.at(x, y) = unsafe.at(x, y);
            both.at(x + w + 8, y) = safe.at(x, y);
        }
    }
    write_png(folder / "ch06_near_clip.png", both);
    std::printf("wrote ch06_near_clip.png\n");
} catch (const Error& error) {
    std::fprintf(stderr, "fig_ch06_near_clip: %s\n", error.what());
    return 1;
}
