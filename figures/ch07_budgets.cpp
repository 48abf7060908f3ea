// Figure data for chapter 7's Exercise 5: the horizon scene (horizon.toml) rendered by
// `auto` with error budgets from 0.05 to 4 texels. Writes ch07_budgets.txt into the
// folder argv[1], one fact per line for each budget B:
//   divides_B    every divide of the render (RenderReport::divides, a deterministic
//   count) per_pixel_B  divides per textured pixel exact_B      textured pixels `auto`
//   handed to the exact mapper worst_B      the worst texel error against the exact
//   mapper (check_against_exact) pixels       textured pixels (the same for every budget)
// With `--once B` it only renders the scene once with budget B and writes nothing: what
// chapters/07-scenes/callgrind.sh counts the instructions of (the time question of the
// exercise, answered without a clock).
#include "exactpixels/base/error.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "support/figure_file.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

using namespace exactpixels;

int main(int argc, char** argv) {
    try {
        Scene scene = load_scene(shipped_scene_folder() / "horizon.toml");
        if (argc > 2 && std::string_view(argv[1]) == "--once") {
            scene.options.budget = std::strtod(argv[2], nullptr);
            if (!(scene.options.budget > 0)) {
                std::fprintf(stderr, "fig_ch07_budgets: bad budget '%s'\n", argv[2]);
                return 2;
            }
            const RenderResult r = render_scene(scene);
            std::printf("%lld divides\n", r.report.divides());
            return 0;
        }
        const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
        std::string facts =
            "# chapter 7, Exercise 5: the horizon under auto, by budget\n";
        long long pixels = 0;
        for (const double budget : {0.05, 0.1, 0.25, 0.5, 1.0, 2.0, 4.0}) {
            scene.options.budget = budget;
            const RenderReport report = render_scene(scene).report;
            const TexelError e = check_against_exact(scene);
            pixels = report.texture.pixels;
            const auto exact = static_cast<std::size_t>(MapperKind::exact);
            facts += fmt::format("divides_{0:g} {1}\nper_pixel_{0:g} {2:.4f}\n"
                                 "exact_{0:g} {3}\nworst_{0:g} {4:.4f}\n",
                                 budget, report.divides(),
                                 static_cast<double>(report.divides()) /
                                     static_cast<double>(report.texture.pixels),
                                 report.mappers[exact].pixels, e.worst);
        }
        facts += fmt::format("pixels {}\n", pixels);
        write_figure_file(folder / "ch07_budgets.txt", facts);
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch07_budgets: %s\n", error.what());
        return 1;
    }
}
