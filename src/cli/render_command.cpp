#include "commands.hpp"

#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/fast/worker_pool.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace exactpixels::cli {

void add_render_command(CLI::App& app, int& exit_code) {
    struct Options {
        std::string scene;  // empty: the first shipped scene
        std::string output; // the PNG to write (not given: the scene's name with .png)
        bool report = false;
        bool check = false;
        int threads = 1; // FastPaths::threads
    };
    auto options = std::make_shared<Options>();
    CLI::App* command = app.add_subcommand(
        "render", "Render a TOML scene file (chapter 7) to a PNG, running only the "
                  "stages the scene calls for");
    command->add_option("scene", options->scene,
                        "Scene file (default: the first scene shipped with chapter 7)");
    const CLI::Option* output_option = command->add_option(
        "-o,--output", options->output, "PNG file to write (default: SCENE-NAME.png)");
    command->add_flag("--report", options->report,
                      "Print what ran: triangles, pixels, divides and time per stage");
    command->add_flag("--check", options->check,
                      "Also render the exact reference and print the texel error");
    command->add_option("--threads", options->threads,
                        fmt::format("Draw with this many threads (1 .. {}; default 1): "
                                    "the same picture and report counts for any number",
                                    max_threads));
    command->callback([options, output_option, &exit_code] {
        report_errors("render", exit_code, [&] {
            check_thread_count(options->threads); // before the scene is read
            const std::filesystem::path scene_path =
                options->scene.empty() ? shipped_scenes().front()
                                       : std::filesystem::path(options->scene);
            Scene scene = load_scene(scene_path); // Error: file:line:column: key
            const std::filesystem::path output =
                output_option->count() > 0 // "-o ''" is an error, not the default
                    ? std::filesystem::path(options->output)
                    : std::filesystem::path(scene_path.stem().string() + ".png");
            const std::vector<std::filesystem::path> inputs = scene_inputs(scene);
            check_output(output, "PNG", inputs); // not a scene, texture or device
            FastPaths fast;
            fast.threads = options->threads;
            const RenderResult result = render_scene(scene, nullptr, fast);
            if (options->report) {
                write_standard_output(format_report(result.report));
            }
            if (options->check) {
                // The scene is not needed after the check: moved in, its textures are
                // not copied (max_check_peak_bytes).
                const TexelError e = check_against_exact(std::move(scene));
                write_standard_output(
                    fmt::format("texel error against exact: worst {:.6f}, mean {:.6f} "
                                "over {} pixels\n",
                                e.worst, e.mean, e.pixels));
                if (e.not_finite > 0) { // NaN or infinity: a failure, not a large error
                    throw Error(fmt::format("--check: {} pixels have texel coordinates "
                                            "that are not finite",
                                            e.not_finite));
                }
            }
            // All or nothing, with what it prints: the PNG is written beside its target,
            // the last line must reach standard output, and only then is it renamed.
            PendingFile png = prepare_png(output, result.image, inputs);
            write_standard_output(fmt::format("wrote {}\n", output.string()));
            png.commit();
        });
    });
}

} // namespace exactpixels::cli
