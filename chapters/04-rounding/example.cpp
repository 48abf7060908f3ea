// Chapter 4 example: the F drawn 1:1 on quads offset by half a pixel (every sample a
// tie), forwards and mirrored in u, in v and in both. Top row: the rounding chosen per
// triangle; bottom row: rule 1 everywhere. Writes ch04_mirrors.png, enlarged 8 times.
// Usage: ch04-example [OUTPUT_DIR]   (default: .)
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/texture/rounding.hpp"
#include "exactpixels/texture/texture.hpp"
#include "exactpixels/texture/texture_mapper.hpp"

#include <cstdio>
#include <filesystem>

using namespace exactpixels;

namespace {

/// Each pixel of `small` as a zoom x zoom block: pixels stay visible in the book.
Framebuffer enlarged(const Framebuffer& small, int zoom) {
    Framebuffer big(small.width() * zoom, small.height() * zoom);
    for (int y = 0; y < big.height(); ++y) {
        for (int x = 0; x < big.width(); ++x) {
            big.at(x, y) = small.at(x / zoom, y / zoom);
        }
    }
    return big;
}

} // namespace

//> example-main
int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    const Texture f = f_texture(2); // 10 x 14 texels
    const double W = f.width(), H = f.height();
    Framebuffer frame(4 * 13 + 1, 2 * 17 + 1, rgba(0, 160, 0));
    for (int row = 0; row < 2; ++row) {              // 0: chosen rule, 1: rule 1 always
        for (int mirror = 0; mirror < 4; ++mirror) { // bit 0: u backwards, bit 1: v
            const double x0 = 2.5 + 13 * mirror, y0 = 2.5 + 17 * row; // half-pixel offset
            const double ul = (mirror & 1) ? W : 0, ur = W - ul;
            const double vt = (mirror & 2) ? H : 0, vb = H - vt;
            const TexturedVertex a{{x0, y0}, 1.0, {ul, vt}},
                b{{x0 + W, y0}, 1.0, {ur, vt}};
            const TexturedVertex c{{x0 + W, y0 + H}, 1.0, {ur, vb}};
            const TexturedVertex d{{x0, y0 + H}, 1.0, {ul, vb}};
            for (const auto& triangle : {std::array{a, b, c}, std::array{a, c, d}}) {
                MapperSettings settings{.precision = Precision::fixed,
                                        .wrap = Wrap::clamp};
                if (row == 0) {
                    settings.rounding = choose_rounding(triangle, settings.mapper.kind);
                }
                draw_textured_triangle(frame, triangle, f, settings);
            }
        }
    }
    try {
        write_png(folder / "ch04_mirrors.png", enlarged(frame, 8));
    } catch (const Error& error) {
        std::fprintf(stderr, "ch04-example: %s\n", error.what());
        return 1;
    }
    std::printf("wrote %s\n", (folder / "ch04_mirrors.png").c_str());
}
//< example-main
