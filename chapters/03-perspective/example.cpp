// Chapter 3 example: a perspective floor drawn by the exact mapper and by the affine one,
// side by side. Usage: ch03-example OUTPUT_DIR [TEXTURE.png]
// Writes OUTPUT_DIR/ch03_example.png (640 x 240). With TEXTURE.png the floor wears that
// image instead of the checkerboard; a missing or unreadable texture is an error, and
// then nothing is written.
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/lab/perspective_scenes.hpp"

#include <cstdio>
#include <filesystem>

using namespace exactpixels;

//> example-main
int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    try {
        PerspectiveScene floor = floor_scene(320, 240);
        if (argc > 2) {
            floor.texture = load_texture(argv[2]); // throws Error naming the file
        }
        Framebuffer exact(320, 240, rgba(20, 30, 60)), affine = exact;
        draw_scene(exact, floor, MapperSettings{.mapper = {MapperKind::exact}});
        draw_scene(affine, floor, MapperSettings{.mapper = {MapperKind::affine}});

        Framebuffer both(640, 240);
        for (int y = 0; y < 240; ++y) {
            for (int x = 0; x < 320; ++x) {
                both.at(x, y) = exact.at(x, y);
                both.at(320 + x, y) = affine.at(x, y);
            }
        }
        write_png(folder / "ch03_example.png", both);
    } catch (const Error& error) {
        std::fprintf(stderr, "ch03-example: %s\n", error.what());
        return 1;
    }
    std::printf("wrote %s\n", (folder / "ch03_example.png").c_str());
}
//< example-main
