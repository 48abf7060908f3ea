// Figure: a triangle on a 12 x 9 pixel grid. Covered pixels are shaded and their centres
// drawn solid, uncovered centres hollow; the split edge's point 4 and the gradient of a
// value c are drawn as arrows. Writes ch01_grid.svg into the folder argv[1].
#include "exactpixels/base/error.hpp"
#include "exactpixels/raster/gradients.hpp"
#include "exactpixels/raster/scanline.hpp"
#include "support/svg.hpp"

#include <cstdio>
#include <filesystem>
#include <set>
#include <utility>

int main(int argc, char** argv) {
    using namespace exactpixels;
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    const int width = 12, height = 9;
    // Vertices 1, 2, 3 sorted by y; c = 0 at vertex 1, 1 at vertex 2, 0.5 at vertex 3.
    const std::array<Point2, 3> v{{{4.3, 0.6}, {11.2, 3.9}, {1.4, 8.3}}};
    const std::array<double, 3> c{0.0, 1.0, 0.5};

    SvgDiagram d(width, height, 40.0, 28.0);
    std::set<std::pair<int, int>> covered;
    scanline_spans(v, Viewport{width, height}, [&](Span s) {
        for (int x = s.x_begin; x < s.x_end; ++x) {
            covered.insert({x, s.y});
            d.fill_pixel(x, s.y, "#cfe0f5");
        }
    });
    d.grid();
    d.grid_labels();
    d.polygon({v[0], v[1], v[2]}, {.stroke = "black", .width = 1.5});
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const bool in = covered.count({x, y}) > 0;
            d.circle(
                pixel_centre(x, y), in ? 3.5 : 2.5,
                {.stroke = in ? "#1f4e9a" : "#909090", .fill = in ? "#1f4e9a" : "none"});
        }
    }
    // The split edge: point 4 on the long edge 1-3 at the height of vertex 2.
    const double t = (v[1].y - v[0].y) / (v[2].y - v[0].y);
    const Point2 p4 = v[0] + t * (v[2] - v[0]);
    d.line(v[1], p4, {.stroke = "#b03030", .width = 1.5, .dashed = true});
    d.circle(p4, 4.0, {.stroke = "#b03030", .fill = "white", .width = 1.5});
    const char* names[] = {"1 (c = 0)", "2 (c = 1)", "3 (c = 0.5)"};
    const Point2 offsets[] = {{0.25, -0.15}, {-0.2, -0.35}, {0.3, 0.45}};
    for (int i = 0; i < 3; ++i) {
        d.circle(v[i], 4.0, {.stroke = "black", .fill = "black"});
        d.text(v[i] + offsets[i], names[i], 13);
    }
    d.text(p4 + Point2{-0.35, 0.1}, "4", 13, SvgAnchor::end, "#b03030");
    // The gradient (dc/dx, dc/dy), drawn from the centroid, scaled to be visible.
    const Gradient<double> g = closed_form_gradient<double>(v, c);
    const Point2 centroid = (v[0] + v[1] + v[2]) / 3.0;
    const double scale = 3.0 / std::hypot(g.dx, g.dy);
    d.arrow(centroid, centroid + scale * Point2{g.dx, 0},
            {.stroke = "#2a8a2a", .width = 2});
    d.arrow(centroid, centroid + scale * Point2{0, g.dy},
            {.stroke = "#2a8a2a", .width = 2});
    d.arrow(centroid, centroid + scale * Point2{g.dx, g.dy},
            {.stroke = "#b05a00", .width = 2.5});
    d.text(centroid + scale * Point2{g.dx, 0} + Point2{0.15, 0.1}, "dc/dx", 13,
           SvgAnchor::start, "#2a8a2a");
    d.text(centroid + scale * Point2{0, g.dy} + Point2{0.15, 0.2}, "dc/dy", 13,
           SvgAnchor::start, "#2a8a2a");
    d.text(centroid + scale * Point2{g.dx, g.dy} + Point2{0.2, 0.35}, "gradient", 13,
           SvgAnchor::start, "#b05a00");
    try {
        d.write(folder / "ch01_grid.svg");
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch01_grid: %s\n", error.what());
        return 1;
    }
}
