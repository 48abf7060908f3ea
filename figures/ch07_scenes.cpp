// Chapter 7 figures: the report of every shipped scene, and for the perspective scenes
// the time, divides and texel error of `auto` against `exact` and `affine`, as Markdown
// fragments pulled into the chapter (ch07_reports.md, ch07_auto_vs_exact.md, with the
// least and most of exact's divides auto removes in ch07_auto_facts.txt), and the
// error of Gouraud colours against perspective-correct ones (ch07_gouraud_error.md), and
// the depth stage's resolution and cost (ch07_depth_resolution.md, ch07_depth_cost.md),
// and the filter stage on the horizon: nearest beside auto (ch07_horizon_filters.png)
// with every filter's error and cost (ch07_scene_filters.md), and what lighting costs on
// the lit scene (ch07_lighting_cost.md).
// Usage: fig_ch07_scenes FIGURE_DIR
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/lab/filter_measure.hpp"
#include "exactpixels/scene/depth_buffer.hpp"
#include "exactpixels/scene/gouraud_error.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "exactpixels/scene/supersampled_reference.hpp"
#include "support/figure_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

using namespace exactpixels;

namespace {

/// The fastest of a few renders, in milliseconds (the least disturbed by other work).
double best_ms(const Scene& scene, int runs) {
    double best = 1e300;
    for (int k = 0; k < runs; ++k) {
        best = std::min(best, 1e3 * render_scene(scene).report.seconds);
    }
    return best;
}

} // namespace

int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    try {
        std::string reports;
        std::string table =
            "| scene | mapper | divides | time (ms) | worst error (texels) "
            "| mean error (texels) |\n|---|---|---:|---:|---:|---:|\n";
        double removed_least = 100.0, removed_most = 0.0; // percent of exact's divides
        for (const std::filesystem::path& path : shipped_scenes()) {
            const Scene scene = load_scene(path);
            const std::string name = path.stem().string();
            reports += fmt::format("**{}** (`{}`)\n\n```{{.text}}\n{}```\n\n", name,
                                   path.filename().string(),
                                   format_report(render_scene(scene).report));
            if (scene.camera.projection != Projection::perspective ||
                render_scene(scene).report.texture.pixels == 0) {
                continue;
            }
            double divides[2] = {0, 0}; // auto, exact
            for (const char* mapper : {"auto", "exact", "affine"}) {
                Scene variant = scene;
                const std::string word = mapper;
                variant.options.mapper = {word == "auto",
                                          parse_mapper(word).value_or(Mapper{})};
                const TexelError e = check_against_exact(variant);
                const auto count = render_scene(variant).report.divides();
                table +=
                    fmt::format("| {} | {} | {} | {:.2f} | {:.3f} | {:.4f} |\n", name,
                                mapper, count, best_ms(variant, 7), e.worst, e.mean);
                if (word != "affine") {
                    divides[word == "exact"] = double(count);
                }
            }
            // The share of exact's divides that auto removes, smallest and largest.
            const double removed = 100.0 * (1.0 - divides[0] / divides[1]);
            removed_least = std::min(removed_least, removed);
            removed_most = std::max(removed_most, removed);
        }
        std::string gouraud = "| scene | camera | pixels | worst (channel range) | worst "
                              "(8-bit levels) | mean (8-bit levels) |\n"
                              "|---|---|---:|---:|---:|---:|\n";
        for (const std::filesystem::path& path : shipped_scenes()) {
            const Scene scene = load_scene(path);
            const GouraudError e = gouraud_perspective_error(scene);
            if (e.pixels == 0) {
                continue; // no vertex colours
            }
            gouraud += fmt::format(
                "| {} | {} | {} | {:.4f} | {:.1f} | {:.2f} |\n", path.stem().string(),
                scene.camera.projection == Projection::perspective ? "perspective"
                                                                   : "orthographic",
                e.pixels, e.worst, 255.0 * e.worst, 255.0 * e.mean);
        }
        gouraud += "\n: Gouraud colours (linear on screen) against perspective-correct "
                   "colours on the shipped scenes with vertex colours, measured by "
                   "`gouraud_perspective_error`. {#tbl:gouraud-error}\n";
        write_figure_file(folder / "ch07_gouraud_error.md", gouraud);
        // The depth buffer's relative resolution near and far (near plane at 0.1).
        std::string resolution = "| depth $w$ | float $1/w$ | 24-bit fixed $1/w$ |\n"
                                 "|---:|---:|---:|\n";
        for (const double w : {0.1, 1.0, 10.0, 100.0, 1000.0}) {
            resolution +=
                fmt::format("| {} | {:.2e} | {:.2e} |\n", w, depth_resolution(w),
                            fixed_depth_resolution(w, 0.1, 24));
        }
        write_figure_file(folder / "ch07_depth_resolution.md", resolution);
        // What the depth stage costs: every shipped scene with the stage forced on and
        // forced off (off may be wrong; it is the time without the stage).
        std::string cost = "| scene | auto turns it | pixels tested | hidden | "
                           "ms with depth | ms without | depth stage ms |\n"
                           "|---|---|---:|---:|---:|---:|---:|\n";
        for (const std::filesystem::path& path : shipped_scenes()) {
            Scene scene = load_scene(path);
            const bool automatic = render_scene(scene).report.depth_on;
            scene.options.depth = DepthMode::on;
            const RenderReport on = render_scene(scene).report;
            const double with_ms = best_ms(scene, 7);
            double stage_ms = 1e300;
            for (int k = 0; k < 7; ++k) {
                stage_ms =
                    std::min(stage_ms, 1e3 * render_scene(scene).report.depth.seconds);
            }
            scene.options.depth = DepthMode::off;
            cost += fmt::format("| {} | {} | {} | {} | {:.2f} | {:.2f} | {:.3f} |\n",
                                path.stem().string(), automatic ? "on" : "off",
                                on.depth.pixels, on.hidden.pixels, with_ms,
                                best_ms(scene, 7), stage_ms);
        }
        write_figure_file(folder / "ch07_depth_cost.md", cost);
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
        write_figure_file(folder / "ch07_colours.md", colours);
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
            write_figure_file(folder / "ch07_scene_filters.md", filters);
            write_figure_file(folder / "ch07_scene_filters.txt", facts);
            write_png(folder / "ch07_horizon_filters.png", pair);
        }
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
            write_figure_file(folder / "ch07_lighting_cost.md", cost);
        }
        write_figure_file(folder / "ch07_reports.md", reports);
        write_figure_file(folder / "ch07_auto_vs_exact.md", table);
        write_figure_file(folder / "ch07_auto_facts.txt",
                          fmt::format("# auto against exact on the perspective scenes "
                                      "(divides: deterministic counts)\n"
                                      "auto_divides_removed_least_percent {}\n"
                                      "auto_divides_removed_most_percent {}\n",
                                      removed_least, removed_most));
        std::printf("wrote %s and %s\n", (folder / "ch07_reports.md").c_str(),
                    (folder / "ch07_auto_vs_exact.md").c_str());
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch07_scenes: %s\n", error.what());
        return 1;
    }
}
