// Chapter 1 example: a Gouraud-shaded triangle, drawn by the scanline rasterizer with
// red, green and blue stepped across it from the three vertices.
// Usage: ch01-example [OUTPUT_DIR]   (writes OUTPUT_DIR/ch01_gouraud.png; default: .)
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/raster/scanline.hpp"

#include <cstdio>
#include <filesystem>

//> example-main
int main(int argc, char** argv) {
    using namespace exactpixels;
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    Framebuffer frame(160, 120, rgba(32, 32, 32));
    const std::array<Point2, 3> v{{{80.3, 6.7}, {152.6, 110.2}, {9.1, 84.5}}};
    const std::array<Attributes<3>, 3> rgb{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    const Viewport viewport{frame.width(), frame.height()};
    scanline_interpolate(v, rgb, viewport, [&](int x, int y, const Attributes<3>& c) {
        frame.at(x, y) = to_rgba8({c[0], c[1], c[2]});
    });
    try {
        write_png(folder / "ch01_gouraud.png", frame);
    } catch (const Error& error) {
        std::fprintf(stderr, "ch01-example: %s\n", error.what());
        return 1;
    }
    std::printf("wrote %s\n", (folder / "ch01_gouraud.png").c_str());
}
//< example-main
