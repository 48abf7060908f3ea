// Chapter 5 example: the grazing floor drawn by three mappers, with each one's error.
// Usage: ch05-example [OUTPUT_DIR]   (writes OUTPUT_DIR/ch05_floor_*.png; default: .)
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/lab/accuracy_scenes.hpp"
#include "exactpixels/texture/texel_error.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

using namespace exactpixels;

int main(int argc, char** argv) try {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    const AccuracyScene floor = grazing_floor_scene();
    for (const MapperConfig& mapper : accuracy_mappers()) {
        if (mapper.name != "affine fixed" && mapper.name != "quadratic:8 fixed" &&
            mapper.name != "exact float") {
            continue;
        }
        Framebuffer frame(floor.width, floor.height, rgba(0, 0, 0));
        draw_with(frame, floor, mapper);
        const TexelError e = measure_mapper_error(floor, mapper);
        std::string file = "ch05_floor_" + mapper.name.substr(0, mapper.name.find(' '));
        std::replace(file.begin(), file.end(), ':', '-'); // a file name without a colon
        write_png(folder / (file + ".png"), frame);
        std::printf("%-18s worst %.3f texels, mean %.4f, %.2f %% of texels differ\n",
                    mapper.name.c_str(), e.worst, e.mean, 100.0 * e.differing_share);
    }
} catch (const Error& error) {
    std::fprintf(stderr, "ch05-example: %s\n", error.what());
    return 1;
}
