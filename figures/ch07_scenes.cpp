// Chapter 7 figures: the report of every shipped scene, and for the perspective scenes
// the time, divides and texel error of `auto` against `exact` and `affine`, as Markdown
// fragments pulled into the chapter (ch07_reports.md, ch07_auto_vs_exact.md, with the
// least and most of exact's divides auto removes in ch07_auto_facts.txt), and the
// error of Gouraud colours against perspective-correct ones (ch07_gouraud_error.md), and
// the depth stage's resolution and cost (ch07_depth_resolution.md, ch07_depth_cost.md).
// Usage: fig_ch07_scenes FIGURE_DIR
#include "exactpixels/base/error.hpp"
#include "exactpixels/scene/depth_buffer.hpp"
#include "exactpixels/scene/gouraud_error.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "support/figure_file.hpp"
#include "support/render_time.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>

using namespace exactpixels;

int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    try {
        std::string reports;
        std::string table =
            "| scene | mapper | divides | time (ms) | worst error (texels) "
            "| mean error (texels) |\n|---|---|---:|---:|---:|---:|\n";
        double removed_least = 100.0, removed_most = 0.0; // percent of exact's divides
        std::string worst; // auto's worst texel error per scene, by triangle and by span
        double worst_any = 0.0, budget = 1e300; // the smallest budget of those scenes
        for (const std::filesystem::path& path : shipped_scenes()) {
            const Scene scene = load_scene(path);
            const std::string name = path.stem().string();
            reports += fmt::format("**{}** (`{}`)\n\n```{{.text}}\n{}```\n\n", name,
                                   path.filename().string(),
                                   format_report(render_scene(scene).report));
            if (scene.camera.projection == Projection::perspective) {
                budget = std::min(budget, scene.options.budget);
            }
            if (scene.camera.projection != Projection::perspective ||
                render_scene(scene).report.texture.pixels == 0) {
                continue;
            }
            double divides[2] = {0, 0}; // auto, exact
            for (const char* mapper : {"auto", "auto per span", "exact", "affine"}) {
                Scene variant = scene;
                const std::string word = mapper;
                const bool automatic = word.starts_with("auto");
                variant.options.mapper = {
                    automatic, parse_mapper(word).value_or(Mapper{}), word == "auto"};
                const TexelError e = check_against_exact(variant);
                const auto count = render_scene(variant).report.divides();
                table +=
                    fmt::format("| {} | {} | {} | {:.2f} | {:.3f} | {:.4f} |\n", name,
                                mapper, count, best_ms(variant, 7), e.worst, e.mean);
                if (word == "auto" || word == "exact") {
                    divides[word == "exact"] = double(count);
                }
                if (automatic) { // the worst error with and without the triangle test
                    worst +=
                        fmt::format("worst_{}_{} {}\n",
                                    word == "auto" ? "triangle" : "span", name, e.worst);
                    worst_any = std::max(worst_any, e.worst);
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
        write_figure_file(folder / "ch07_reports.md", reports);
        write_figure_file(folder / "ch07_auto_vs_exact.md", table);
        write_figure_file(folder / "ch07_auto_facts.txt",
                          fmt::format("# auto against exact on the perspective scenes "
                                      "(divides: deterministic counts)\n"
                                      "auto_divides_removed_least_percent {}\n"
                                      "auto_divides_removed_most_percent {}\n"
                                      "budget {}\nworst_auto_any {}\n{}",
                                      removed_least, removed_most, budget, worst_any,
                                      worst));
        std::printf("wrote %s and %s\n", (folder / "ch07_reports.md").c_str(),
                    (folder / "ch07_auto_vs_exact.md").c_str());
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch07_scenes: %s\n", error.what());
        return 1;
    }
}
