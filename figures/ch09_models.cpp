// Chapter 9 figures for models read from OBJ files (@sec:scene-models): the four
// shipped model scenes rendered (ch09_model_torus.png, ch09_model_room.png,
// ch09_model_terrain.png, and the lit torus ch09_model_lit_torus.png), and a generated
// torus of 102,400 triangles written into the figure folder (big_torus.obj, .mtl, .png
// and big_torus.toml) and rendered at 1280 x 720 (ch09_big_torus.png), with the reports
// of all five as a Markdown fragment (ch09_models.md).
//
// Usage: fig_ch09_models FIGURE_DIR
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/lab/model_generator.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "support/figure_file.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <string>

using namespace exactpixels;

int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    try {
        write_generated_model(big_torus_model(), folder);
        write_figure_file(folder / "big_torus.toml", big_torus_scene());
        std::string reports;
        const std::filesystem::path scenes = shipped_scene_folder();
        for (const std::filesystem::path& path :
             {scenes / "torus.toml", scenes / "room.toml", scenes / "terrain.toml",
              scenes / "lit_torus.toml", folder / "big_torus.toml"}) {
            const Scene scene = load_scene(path);
            const RenderResult result = render_scene(scene);
            const std::string name = path.stem().string();
            write_png(folder / (name == "big_torus" ? "ch09_big_torus.png"
                                                    : "ch09_model_" + name + ".png"),
                      result.image);
            long long triangles = 0;
            for (const SceneMesh& mesh : scene.meshes) {
                triangles += static_cast<long long>(mesh.triangles.size());
            }
            reports += fmt::format("**{}** (`{}`, {} x {} pixels, {} triangles)\n\n"
                                   "```{{.text}}\n{}```\n\n",
                                   name, path.filename().string(), scene.width,
                                   scene.height, triangles, format_report(result.report));
        }
        write_figure_file(folder / "ch09_models.md", reports);
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch09_models: %s\n", error.what());
        return 2;
    }
    return 0;
}
