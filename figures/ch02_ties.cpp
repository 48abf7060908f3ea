// Figure: the tie cases of the fill rule. A 4 x 4 px square with its corners on pixel
// centres is split into two triangles along a diagonal; many centres lie exactly on an
// edge. Left: the top-left rule (edge_rasterize_blocks, fixed point) gives each centre
// to exactly one triangle, and the square's bottom and right sides to neither. Right:
// the naive "all barycentrics >= 0" test gives the diagonal's centres to both (red).
// Writes ch02_ties.svg into the folder argv[1].
#include "exactpixels/base/error.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"
#include "exactpixels/raster/naive_rasterizer.hpp"
#include "support/svg.hpp"

#include <cstdio>
#include <filesystem>
#include <map>
#include <utility>

int main(int argc, char** argv) {
    using namespace exactpixels;
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    const int width = 14, height = 7;
    const Viewport viewport{width, height};
    const char* colours[2] = {"#cfe0f5", "#f5e3c4"};
    const char* centre_colours[2] = {"#1f4e9a", "#b05a00"};
    SvgDiagram d(width, height, 36.0, 28.0);

    // Two copies of the square: at x = 1.5 (top-left rule) and x = 8.5 (naive test).
    std::map<std::pair<int, int>, int> owner[2]; // pixel -> bit mask of triangles
    for (int panel = 0; panel < 2; ++panel) {
        const double x0 = panel == 0 ? 1.5 : 8.5;
        const Point2 a{x0, 1.5}, b{x0 + 4, 1.5}, c{x0 + 4, 5.5}, e{x0, 5.5};
        const std::array<std::array<Point2, 3>, 2> halves{{{a, b, c}, {a, c, e}}};
        for (int t = 0; t < 2; ++t) {
            const auto mark = [&, t](int x, int y) { owner[panel][{x, y}] |= 1 << t; };
            const auto& h = halves[t];
            if (panel == 0) {
                edge_rasterize_blocks(std::array<FixedPoint2, 3>{snap_to_subpixel(h[0]),
                                                                 snap_to_subpixel(h[1]),
                                                                 snap_to_subpixel(h[2])},
                                      viewport, mark);
            } else {
                naive_rasterize(
                    std::array<Point2f, 3>{Point2f(h[0]), Point2f(h[1]), Point2f(h[2])},
                    viewport, mark);
            }
        }
        for (const auto& [pixel, mask] : owner[panel]) {
            d.fill_pixel(pixel.first, pixel.second,
                         mask == 3 ? "#f2b8b8" : colours[mask - 1]);
        }
    }
    d.grid();
    for (int panel = 0; panel < 2; ++panel) {
        const double x0 = panel == 0 ? 1.5 : 8.5;
        const Point2 a{x0, 1.5}, b{x0 + 4, 1.5}, c{x0 + 4, 5.5}, e{x0, 5.5};
        d.polygon({a, b, c}, {.stroke = "#1f4e9a", .width = 1.5});
        d.polygon({a, c, e}, {.stroke = "#b05a00", .width = 1.5, .dashed = true});
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                const auto it = owner[panel].find({x, y});
                const int mask = it == owner[panel].end() ? 0 : it->second;
                const char* colour = mask == 0   ? "#909090"
                                     : mask == 3 ? "#c00000"
                                                 : centre_colours[mask - 1];
                d.circle(pixel_centre(x, y), mask ? 3.5 : 2.5,
                         {.stroke = colour, .fill = mask ? colour : "none"});
            }
        }
        d.text({x0 + 2, 6.8}, panel == 0 ? "top-left rule" : "naive: >= 0 on every edge",
               13, SvgAnchor::middle);
    }
    try {
        d.write(folder / "ch02_ties.svg");
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch02_ties: %s\n", error.what());
        return 1;
    }
}
