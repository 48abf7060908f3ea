// Chapter 7 benchmark: rendering the shipped perspective scenes with `auto` against
// `exact` (and `affine`, the cheapest and wrong). Run pinned to one core for real
// numbers: taskset -c 1 build/bin/bench_ch07_scenes
#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/lab/model_generator.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>
#include <unistd.h>

using namespace exactpixels;

namespace {

void render(benchmark::State& state, const std::string& name, const std::string& mapper) {
    Scene scene = load_scene(shipped_scene_folder() / (name + ".toml"));
    if (mapper != "auto") {
        scene.options.mapper = {false, parse_mapper(mapper).value()};
    }
    long long pixels = 0, divides = 0;
    for (auto _ : state) {
        const RenderResult result = render_scene(scene);
        benchmark::DoNotOptimize(result.image.pixels().data());
        pixels = result.report.texture.pixels;
        divides = result.report.divides();
    }
    state.counters["textured_pixels"] = static_cast<double>(pixels);
    state.counters["divides"] = static_cast<double>(divides);
    state.SetItemsProcessed(state.iterations() * pixels);
}

/// The 102,400-triangle torus at 1280 x 720 (model_generator.hpp), written to a
/// temporary folder and read back through the OBJ reader, then rendered.
void render_big_torus(benchmark::State& state, const Scene& scene) {
    long long pixels = 0, divides = 0;
    for (auto _ : state) {
        const RenderResult result = render_scene(scene);
        benchmark::DoNotOptimize(result.image.pixels().data());
        pixels = result.report.texture.pixels;
        divides = result.report.divides();
    }
    // The same counters as the other cases (the CSV has one header for all); items
    // are triangles here.
    state.counters["textured_pixels"] = static_cast<double>(pixels);
    state.counters["divides"] = static_cast<double>(divides);
    state.SetItemsProcessed(state.iterations() *
                            static_cast<long long>(scene.meshes.at(0).triangles.size()));
}

} // namespace

int main(int argc, char** argv) {
    const std::filesystem::path folder =
        std::filesystem::temp_directory_path() /
        ("exactpixels-bench-models-" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    write_generated_model(big_torus_model(), folder);
    write_file_atomically(folder / "big_torus.toml", "scene", big_torus_scene());
    const Scene big_torus = load_scene(folder / "big_torus.toml");
    std::filesystem::remove_all(folder);
    benchmark::RegisterBenchmark("render/big_torus/auto", [&big_torus](
                                                              benchmark::State& state) {
        render_big_torus(state, big_torus);
    })->Unit(benchmark::kMillisecond);
    for (const char* name : {"corridor", "horizon", "near_plane"}) {
        for (const char* mapper : {"auto", "exact", "affine"}) {
            benchmark::RegisterBenchmark(
                (std::string("render/") + name + "/" + mapper).c_str(),
                [name = std::string(name), mapper = std::string(mapper)](
                    benchmark::State& state) { render(state, name, mapper); })
                ->Unit(benchmark::kMillisecond);
        }
    }
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
}
