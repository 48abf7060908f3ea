// Chapter 7 benchmark: rendering the shipped perspective scenes with `auto` against
// `exact` (and `affine`, the cheapest and wrong). Run pinned to one core for real
// numbers: taskset -c 1 build/bin/bench_ch07_scenes
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"

#include <benchmark/benchmark.h>

#include <string>

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

} // namespace

int main(int argc, char** argv) {
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
