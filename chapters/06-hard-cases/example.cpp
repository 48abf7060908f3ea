// Chapter 6 example: a textured floor that runs behind the camera, clipped at the near
// plane, projected and drawn; prints what the clip made of each triangle.
// Usage: ch06-example [OUTPUT_DIR]   (writes OUTPUT_DIR/ch06_floor.png; default: .)
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/texture/clipping.hpp"

#include <cstdio>
#include <filesystem>

using namespace exactpixels;

//> example-main
int main(int argc, char** argv) try {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    const Pinhole camera{200.0, {160.0, 120.0}};
    const double near = 0.1;
    // A floor one unit below the eye from 3 units behind it to 12 in front.
    const ViewVertex a{{-4.0, -1.0, -3.0}, {0.0, 120.0}},
        b{{4.0, -1.0, -3.0}, {64.0, 120.0}}, c{{4.0, -1.0, 12.0}, {64.0, 0.0}},
        d{{-4.0, -1.0, 12.0}, {0.0, 0.0}};
    Framebuffer frame(320, 240, rgba(0, 0, 0));
    for (const std::array<ViewVertex, 3>& t :
         {std::array{a, b, c}, std::array{a, c, d}}) {
        std::printf("triangle -> %d piece(s) in front of z = %.1f\n",
                    clip_near(t, near).count, near);
        draw_view_triangle(frame, camera, t, near, f_texture(4), {});
    }
    write_png(folder / "ch06_floor.png", frame);
    std::printf("wrote %s\n", (folder / "ch06_floor.png").c_str());
} catch (const Error& error) {
    std::fprintf(stderr, "ch06-example: %s\n", error.what());
    return 1;
}
//< example-main
