// Chapter 10 example: 2000 overlapping, depth-tested triangles of every size drawn by the
// tiled renderer with 1, 2 and 4 threads and by the teaching path (pixel by pixel); the
// four pictures must be identical, bit for bit, and the example checks it.
// Usage: ch10-example [OUTPUT_DIR]   (writes OUTPUT_DIR/ch10_tiles.png; default: .)
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/framebuffer.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/fast/tiled_rasterizer.hpp"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <random>
#include <vector>

//> example-main
int main(int argc, char** argv) {
    using namespace exactpixels;
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    const int width = 320, height = 200;

    // Triangles from slivers to a third of the frame, with random colours (a few
    // triangles share one) and random depth planes.
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> x(-20.0, width + 20.0),
        y(-20.0, height + 20.0);
    std::uniform_real_distribution<double> size(-40.0, 40.0);
    std::uniform_real_distribution<float> z(0.0f, 1.0f);
    std::vector<FlatTriangle> tris;
    for (int n = 0; n < 2000; ++n) {
        const Point2 c{x(rng), y(rng)};
        const double s = n % 10 == 0 ? 3.0 : 1.0;
        const std::array<FixedPoint2, 3> v{
            snap_in_range(c + s * Point2{size(rng), size(rng)}),
            snap_in_range(c + s * Point2{size(rng), size(rng)}),
            snap_in_range(c + s * Point2{size(rng), size(rng)})};
        const auto shade = static_cast<std::uint8_t>(rng() % 200 + 40);
        tris.push_back({v, depth_plane(v, {z(rng), z(rng), z(rng)}),
                        rgba(shade, static_cast<std::uint8_t>(255 - shade),
                             static_cast<std::uint8_t>((n * 37) % 256))});
    }

    // The teaching path, then the tiled renderer with 1, 2 and 4 threads.
    const auto draw = [&](int threads) {
        Framebuffer frame(width, height, rgba(16, 16, 16));
        std::vector<float> depth(static_cast<std::size_t>(width * height), 1.0f);
        const RenderTarget target{&frame.at(0, 0), depth.data(), width, height};
        if (threads == 0) {
            draw_reference(target, tris);
        } else {
            draw_tiled(target, tris, threads);
        }
        return frame;
    };
    const Framebuffer reference = draw(0);
    int differing = 0;
    for (const int threads : {1, 2, 4}) {
        differing += draw(threads) != reference;
    }
    try {
        write_png(folder / "ch10_tiles.png", reference);
    } catch (const Error& error) {
        std::fprintf(stderr, "ch10-example: %s\n", error.what());
        return 1;
    }
    std::printf("wrote %s; thread counts whose picture differs: %d\n",
                (folder / "ch10_tiles.png").c_str(), differing);
    return differing == 0 ? 0 : 1;
}
//< example-main
