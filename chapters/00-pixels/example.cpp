// Chapter 0 example: draw the asymmetric "F" test pattern and write it as a PNG.
// Usage: ch00-example [OUTPUT_DIR]   (writes OUTPUT_DIR/ch00_f.png; default: .)
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/base/test_pattern.hpp"

#include <cstdio>
#include <filesystem>

//> example-main
int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    const exactpixels::Framebuffer f = exactpixels::draw_f_pattern(8); // 40 x 56 pixels
    try {
        exactpixels::write_png(folder / "ch00_f.png", f);
    } catch (const exactpixels::Error& error) {
        std::fprintf(stderr, "ch00-example: %s\n", error.what());
        return 1;
    }
    std::printf("wrote %s\n", (folder / "ch00_f.png").c_str());
}
//< example-main
