// Chapter 8 example: the horizon floor through four filters and the reference, side by
// side, with each filter's error.
// Usage: ch08-example [OUTPUT_DIR]   (writes OUTPUT_DIR/ch08_horizon.png; default: .)
// The picture is 2 x 2 frames, each without the sky: nearest (top left), trilinear (top
// right), anisotropic with up to 16 probes (bottom left), the reference (bottom right).
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/lab/filter_measure.hpp"

#include <cstdio>
#include <filesystem>

using namespace exactpixels;

namespace {

/// The first row of a frame that is pasted: the sky above the horizon is left out.
constexpr int first_row = 112;

/// Copies rows first_row.. of `frame` into `sheet` with their top-left corner at (x0,
/// y0).
void paste(Framebuffer& sheet, const Framebuffer& frame, int x0, int y0) {
    for (int y = first_row; y < frame.height(); ++y) {
        for (int x = 0; x < frame.width(); ++x) {
            sheet.at(x0 + x, y0 + y - first_row) = frame.at(x, y);
        }
    }
}

} // namespace

int main(int argc, char** argv) try {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    const AccuracyScene horizon = horizon_floor_scene();
    const FilterScene fs = prepare_filter_scene(horizon); // pixels, uv, derivatives
    const std::vector<LinearTexel> reference = reference_image(fs);
    const std::vector<bool> minified = minified_pixels(fs);
    const int w = horizon.width, h = horizon.height - first_row;
    Framebuffer sheet(2 * w, 2 * h, rgba(0, 0, 0));
    int panel = 0;
    for (const FilterConfig& filter : filter_configs()) {
        if (filter.name != "nearest" && filter.name != "trilinear" &&
            filter.name != "anisotropic-16") {
            continue;
        }
        const std::vector<LinearTexel> image = filter_image(fs, filter);
        paste(sheet, to_frame(fs, image), (panel % 2) * w, (panel / 2) * h);
        ++panel;
        std::printf("%-16s RMS error %.2f codes on the minified pixels, %.2f on all\n",
                    filter.name.c_str(), rms_code_error(image, reference, minified),
                    rms_code_error(image, reference));
    }
    paste(sheet, to_frame(fs, reference), w, h);
    write_png(folder / "ch08_horizon.png", sheet);
} catch (const Error& error) {
    std::fprintf(stderr, "ch08-example: %s\n", error.what());
    return 1;
}
