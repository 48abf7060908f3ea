// Chapter 8's filter stage in the scene renderer (@sec:scene-filtering): the horizon
// scene under each value of `filter`, against an 8 x 8 supersampled reference, with its
// cost (ch08_scene_filters.md, the errors and counts as facts in ch08_scene_filters.txt),
// and nearest beside auto (ch08_scene_filters.png).
// Usage: fig_ch08_scene_filters FIGURE_DIR
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/lab/filter_measure.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "exactpixels/scene/supersampled_reference.hpp"
#include "support/figure_file.hpp"
#include "support/render_time.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

using namespace exactpixels;

int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    try {
        // The filter stage on the horizon: each filter against an 8 x 8 supersampled
        // reference, its cost, and nearest beside auto.
        {
            Scene scene = load_scene(shipped_scene_folder() / "horizon_filtered.toml");
            const std::vector<LinearTexel> reference = supersampled_reference(scene, 8);
            std::string filters =
                "| filter | bilinear | trilinear | anisotropic | mip chains | "
                "render ms | RMS error (8-bit codes) |\n"
                "|---|---:|---:|---:|---:|---:|---:|\n";
            std::string facts = "# the horizon under each filter: RMS error against the "
                                "8 x 8 reference, triangles, mip chains\n";
            Framebuffer pair(2 * scene.width, scene.height);
            for (const auto& [word, filter] :
                 {std::pair{"nearest", SceneFilter::nearest},
                  std::pair{"bilinear", SceneFilter::bilinear},
                  std::pair{"trilinear", SceneFilter::trilinear},
                  std::pair{"anisotropic", SceneFilter::anisotropic},
                  std::pair{"auto", SceneFilter::automatic}}) {
                scene.options.filter = filter;
                const RenderResult r = render_scene(scene);
                const double error = rms_code_error(linear_pixels(r.image), reference);
                filters += fmt::format("| {} | {} | {} | {} | {} | {:.2f} | {:.2f} |\n",
                                       word, r.report.filter_triangles[0],
                                       r.report.filter_triangles[1],
                                       r.report.filter_triangles[2], r.report.mip_chains,
                                       best_ms(scene, 7), error);
                facts +=
                    fmt::format("{0}_error {1:.4f}\n{0}_bilinear {2}\n{0}_trilinear {3}\n"
                                "{0}_anisotropic {4}\n{0}_chains {5}\n",
                                word, error, r.report.filter_triangles[0],
                                r.report.filter_triangles[1],
                                r.report.filter_triangles[2], r.report.mip_chains);
                if (filter == SceneFilter::nearest || filter == SceneFilter::automatic) {
                    const int left = filter == SceneFilter::nearest ? 0 : scene.width;
                    for (int y = 0; y < scene.height; ++y) {
                        for (int x = 0; x < scene.width; ++x) {
                            pair.at(left + x, y) = r.image.at(x, y);
                        }
                    }
                }
            }
            filters += "\n: The horizon scene (`horizon_filtered.toml`) under each value "
                       "of `filter`: triangles per filter, mip chains built, the fastest "
                       "of 7 renders (this build's quick figures), and the RMS error "
                       "against the scene supersampled 8 x 8 per pixel "
                       "(`supersampled_reference`). {#tbl:scene-filters}\n";
            write_figure_file(folder / "ch08_scene_filters.md", filters);
            write_figure_file(folder / "ch08_scene_filters.txt", facts);
            write_png(folder / "ch08_scene_filters.png", pair);
        }
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch08_scene_filters: %s\n", error.what());
        return 1;
    }
}
