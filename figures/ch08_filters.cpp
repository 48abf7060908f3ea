// Chapter 8's filters side by side (@sec:trilinear): one crop of the horizon floor below
// the horizon, through nearest, bilinear, mip-nearest, trilinear and anisotropic (16
// probes) and the reference, left to right in one row (ch08_filters_row.png); and the
// tilted floor of the live figure ch08-level at three tilts, each pixel coloured by the
// level chapter 8 reads there (ch08_filters_levels.png).
// Usage: fig_ch08_filters FIGURE_DIR
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/lab/filter_measure.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"
#include "exactpixels/texture/level_of_detail.hpp"
#include "../web/live_scenes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

using namespace exactpixels;

namespace {

/// The crop of the horizon (320 x 240, horizon at row 120): the floor from just below
/// the horizon down to where level 0 begins, across the middle, so that mip-nearest's
/// jumps between levels show as bands.
constexpr int crop_x = 100, crop_y = 122, crop_width = 120, crop_height = 56;

/// Each image pixel is drawn as a square of this many pixels, and panels stand this far
/// apart.
constexpr int zoom = 2, gap = 6;

/// Copies the crop of `frame`, enlarged by `zoom`, into `sheet` at column x0.
void paste_crop(Framebuffer& sheet, const Framebuffer& frame, int x0) {
    for (int y = 0; y < crop_height * zoom; ++y) {
        for (int x = 0; x < crop_width * zoom; ++x) {
            sheet.at(x0 + x, y) = frame.at(crop_x + x / zoom, crop_y + y / zoom);
        }
    }
}

/// The row: every filter the chapter teaches and the reference, on the same crop.
void filters_row(const std::filesystem::path& folder) {
    const AccuracyScene horizon = horizon_floor_scene();
    const FilterScene fs = prepare_filter_scene(horizon);
    const std::vector<std::string> shown = {"nearest", "bilinear", "mip-nearest",
                                            "trilinear", "anisotropic-16"};
    const int panel = crop_width * zoom + gap;
    Framebuffer sheet(6 * panel - gap, crop_height * zoom, rgba(255, 255, 255));
    int column = 0;
    for (const std::string& name : shown) {
        for (const FilterConfig& config : filter_configs()) {
            if (config.name == name) {
                paste_crop(sheet, to_frame(fs, filter_image(fs, config)), column);
                column += panel;
            }
        }
    }
    if (column != 5 * panel) {
        throw Error("fig_ch08_filters: a filter the row shows is not in filter_configs");
    }
    paste_crop(sheet, to_frame(fs, reference_image(fs)), column);
    write_png(folder / "ch08_filters_row.png", sheet);
}

/// The colours of the live figure's level bands: magnified (level < 0), then levels
/// [0, 1), [1, 2), ... and 5 or more.
constexpr std::array<Rgba8, 7> bands = {
    rgba(236, 240, 244), rgba(44, 123, 182), rgba(171, 217, 233), rgba(255, 255, 191),
    rgba(253, 174, 97),  rgba(215, 25, 28),  rgba(123, 50, 148)};

Rgba8 band_of(double level) {
    return level < 0.0 ? bands[0]
                       : bands[std::size_t(std::min(6.0, 1.0 + std::floor(level)))];
}

/// The tilted floor at 0, 60 and 80 degrees, 6 units away, as the live figure covers
/// and colours it (web/live_figures.cpp, ep_level), each pixel enlarged 8 times.
void level_colours(const std::filesystem::path& folder) {
    constexpr int width = live::floor_width, height = live::floor_height, scale = 8;
    constexpr int panel = width * scale + 3 * gap;
    Framebuffer sheet(3 * panel - 3 * gap, height * scale, rgba(255, 255, 255));
    int left = 0;
    for (const double tilt : {0.0, 60.0, 80.0}) {
        for (const auto& t : live::tilted_floor(tilt, 6.0)) {
            const std::array<FixedPoint2, 3> v = {snap_to_subpixel(t[0].position),
                                                  snap_to_subpixel(t[1].position),
                                                  snap_to_subpixel(t[2].position)};
            edge_rasterize_pixels(v, Viewport{width, height}, [&](int x, int y) {
                const Rgba8 c =
                    band_of(isotropic_level(derivatives_at(t, Point2{x + 0.5, y + 0.5})));
                for (int dy = 0; dy < scale; ++dy) {
                    for (int dx = 0; dx < scale; ++dx) {
                        sheet.at(left + x * scale + dx, y * scale + dy) = c;
                    }
                }
            });
        }
        left += panel;
    }
    write_png(folder / "ch08_filters_levels.png", sheet);
}

} // namespace

int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    try {
        filters_row(folder);
        level_colours(folder);
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch08_filters: %s\n", error.what());
        return 1;
    }
}
