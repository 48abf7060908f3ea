// Chapter 7 figures: the report of every shipped scene, and for the perspective scenes
// the time, divides and texel error of `auto` against `exact` and `affine`, as Markdown
// fragments pulled into the chapter (ch07_reports.md, ch07_auto_vs_exact.md), and the
// error of Gouraud colours against perspective-correct ones (ch07_gouraud_error.md).
// Usage: fig_ch07_scenes FIGURE_DIR
#include "exactpixels/base/error.hpp"
#include "exactpixels/scene/gouraud_error.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

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
            for (const char* mapper : {"auto", "exact", "affine"}) {
                Scene variant = scene;
                const std::string word = mapper;
                variant.options.mapper = {word == "auto",
                                          parse_mapper(word).value_or(Mapper{})};
                const TexelError e = check_against_exact(variant);
                table += fmt::format("| {} | {} | {} | {:.2f} | {:.3f} | {:.4f} |\n",
                                     name, mapper, render_scene(variant).report.divides(),
                                     best_ms(variant, 7), e.worst, e.mean);
            }
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
        if (!(std::ofstream(folder / "ch07_gouraud_error.md") << gouraud)) {
            throw Error((folder / "ch07_gouraud_error.md").string() + ": cannot write");
        }
        std::ofstream(folder / "ch07_reports.md") << reports;
        std::ofstream(folder / "ch07_auto_vs_exact.md") << table;
        std::printf("wrote %s and %s\n", (folder / "ch07_reports.md").c_str(),
                    (folder / "ch07_auto_vs_exact.md").c_str());
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch07_scenes: %s\n", error.what());
        return 1;
    }
}
