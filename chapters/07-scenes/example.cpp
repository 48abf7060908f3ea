// Chapter 7 example: render every shipped scene and print what each one ran.
// Usage: ch07-example [OUTPUT_DIR]   (writes OUTPUT_DIR/ch07_<scene>.png; default: .)
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"

#include <cstdio>
#include <filesystem>

//> example-main
int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    try {
        for (const std::filesystem::path& path : exactpixels::shipped_scenes()) {
            const exactpixels::Scene scene = exactpixels::load_scene(path); // load
            const exactpixels::RenderResult result = exactpixels::render_scene(scene);
            const auto png = folder / ("ch07_" + path.stem().string() + ".png");
            exactpixels::write_png(png, result.image); // write
            std::printf("%s\n%s\n", png.c_str(),
                        exactpixels::format_report(result.report).c_str());
        }
    } catch (const exactpixels::Error& error) {
        std::fprintf(stderr, "ch07-example: %s\n", error.what());
        return 1;
    }
}
//< example-main
