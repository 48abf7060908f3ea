// Chapter 9 figures: the screen path's colour error on the Gouraud scene against the
// perspective-correct colours (ch09_colours.md), and what lighting costs on the lit scene
// (ch09_lighting_cost.md).
// Usage: fig_ch09_shading FIGURE_DIR
#include "exactpixels/base/error.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "support/figure_file.hpp"
#include "support/render_time.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>

using namespace exactpixels;

int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    try {
        // The screen path's colour error on the Gouraud scene, against the corrected one.
        std::string colours =
            "| scene | colours | worst (levels) | mean (levels) | "
            "bound (levels) | divides |\n|---|---|---:|---:|---:|---:|\n";
        {
            Scene scene = load_scene(shipped_scene_folder() / "gouraud.toml");
            scene.options.colours = ColourInterpolation::perspective;
            const RenderResult exact = render_scene(scene);
            for (const auto& [word, mode] :
                 {std::pair{"screen", ColourInterpolation::screen},
                  std::pair{"auto", ColourInterpolation::automatic},
                  std::pair{"perspective", ColourInterpolation::perspective}}) {
                scene.options.colours = mode;
                const RenderResult r = render_scene(scene);
                int worst = 0;
                double sum = 0.0;
                for (std::size_t k = 0; k < r.image.pixels().size(); ++k) {
                    const Rgba8 a = r.image.pixels()[k], b = exact.image.pixels()[k];
                    for (const int d : {int(a.r) - int(b.r), int(a.g) - int(b.g),
                                        int(a.b) - int(b.b)}) {
                        worst = std::max(worst, std::abs(d));
                        sum += std::abs(d);
                    }
                }
                colours +=
                    fmt::format("| gouraud | {} | {} | {:.4f} | {:.2f} | {} |\n", word,
                                worst, sum / (3.0 * double(r.image.pixels().size())),
                                r.report.colour_bound, r.report.divides());
            }
        }
        write_figure_file(folder / "ch09_colours.md", colours);
        // What lighting costs on the lit scene: without its lights, every mesh per
        // vertex, as shipped, every mesh per pixel.
        {
            const Scene shipped = load_scene(shipped_scene_folder() / "lit.toml");
            std::string cost = "| lit.toml | lighting stage | corners lit | pixels lit | "
                               "lighting divides | lighting ms | render ms |\n"
                               "|---|---|---:|---:|---:|---:|---:|\n";
            const auto all = [&](std::optional<Shading> shading) {
                Scene scene = shipped;
                for (SceneMesh& mesh : scene.meshes) {
                    mesh.shading = shading ? shading : mesh.shading;
                }
                return scene;
            };
            Scene unlit = shipped;
            unlit.lights.clear();
            for (const auto& [word, scene] :
                 {std::pair{"no lights", unlit},
                  std::pair{"all Gouraud", all(Shading::gouraud)},
                  std::pair{"as shipped", shipped},
                  std::pair{"all Phong", all(Shading::phong)}}) {
                const RenderReport r = render_scene(scene).report;
                double lighting_ms = 1e300;
                for (int k = 0; k < 7; ++k) {
                    lighting_ms = std::min(
                        lighting_ms, 1e3 * render_scene(scene).report.lighting.seconds);
                }
                cost += fmt::format("| {} | {} | {} | {} | {} | {:.3f} | {:.2f} |\n",
                                    word, r.lighting_on ? "on" : "off", r.lit_vertices,
                                    r.lighting.pixels, r.lighting.divides, lighting_ms,
                                    best_ms(scene, 7));
            }
            cost += "\n: The lit scene four ways: corners lit per vertex, pixels lit per "
                    "pixel and their divides (counts), and the fastest of 7 renders "
                    "(this build's quick figures, ms). {#tbl:lighting-cost}\n";
            write_figure_file(folder / "ch09_lighting_cost.md", cost);
        }
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch09_shading: %s\n", error.what());
        return 1;
    }
}
