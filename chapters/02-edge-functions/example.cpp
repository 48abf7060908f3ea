// Chapter 2 example: a mesh of triangles sharing edges, drawn with edge functions in
// 8 x 8 blocks, each pixel coloured by its barycentric weights (red, green and blue at
// the three vertices). Every pixel is drawn exactly once: the example counts and checks.
// Usage: ch02-example [OUTPUT_DIR]   (writes OUTPUT_DIR/ch02_mesh.png; default: .)
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/framebuffer.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <vector>

//> example-main
int main(int argc, char** argv) {
    using namespace exactpixels;
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    const int size = 160;
    Framebuffer frame(size, size, rgba(24, 24, 24));
    std::vector<int> hits(size * size, 0);

    // A fan of 12 triangles around a point between pixel centres, snapped to 1/256 px.
    const Point2 hub{80.3, 79.6};
    const auto rim = [&](int k) {
        const double angle = 2 * std::numbers::pi * k / 12;
        return snap_in_range(hub + 70.0 * Point2{std::cos(angle), std::sin(angle)});
    };
    for (int k = 0; k < 12; ++k) {
        const std::array<FixedPoint2, 3> v{snap_in_range(hub), rim(k), rim(k + 1)};
        edge_rasterize_blocks(v, Viewport{size, size}, [&](int x, int y) {
            const auto l =
                barycentric(v, fixed_pixel_centre(x, y)); // @eq:edge-barycentric
            frame.at(x, y) = to_rgba8({l[0], l[1], l[2]});
            ++hits[y * size + x];
        });
    }
    int twice = 0;
    for (const int h : hits) {
        twice += h > 1;
    }
    try {
        write_png(folder / "ch02_mesh.png", frame);
    } catch (const Error& error) {
        std::fprintf(stderr, "ch02-example: %s\n", error.what());
        return 1;
    }
    std::printf("wrote %s; pixels drawn twice: %d\n", (folder / "ch02_mesh.png").c_str(),
                twice);
    return twice == 0 ? 0 : 1;
}
//< example-main
