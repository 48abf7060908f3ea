// Chapter 5: what each texture mapper of chapters 3 and 4 costs per pixel, and how far
// its texels are from the exact double reference, on the scenes of accuracy_scenes.hpp.
//
// Usage:
//   taskset -c 1 build/bin/bench_ch05_mappers --benchmark_out=ch05.csv
//       --benchmark_out_format=csv                 # (one line) the full run, one core
//   build/bin/bench_ch05_mappers --list            # every run's name, one per line
//   build/bin/bench_ch05_mappers --once=floor/quadratic_fixed   # one drawing (callgrind)
//
// Each benchmark "scene/mapper" draws the whole scene once per iteration with
// draw_textured_triangle (coverage, setup, the mapper's inner loop and the texel fetch:
// everything a caller pays). Counters: pixels (writes per drawing), ns_per_px, and the
// deterministic error of that mapper on that scene against the reference
// (texel_error.hpp): worst and mean texel error (texels), the share of pixels whose
// texel differs, and the wrong texels at ties (pixels whose exact u or v is whole and
// whose texel differs).
// Chapter 5's full run and the book's quick run both repeat every benchmark three times,
// interleaved; fig_ch05_table keeps each one's fastest repetition and takes the run's
// noise from the spread of the repetitions.
// --once draws one run's scene once inside the function ch05_render_once, so that
//   valgrind --tool=callgrind --toggle-collect=ch05_render_once bench_ch05_mappers
//   --once=NAME
// counts the instructions of exactly one drawing
// (chapters/05-accuracy-cost/callgrind.sh).
#include "exactpixels/lab/accuracy_scenes.hpp"
#include "exactpixels/texture/texel_error.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

using namespace exactpixels;

/// One drawing of the scene: the only function callgrind collects in --once mode.
extern "C" [[gnu::noinline]] void ch05_render_once(Framebuffer* frame,
                                                   const AccuracyScene* scene,
                                                   const MapperConfig* mapper) {
    draw_with(*frame, *scene, *mapper);
}

namespace {

void register_all(const std::vector<AccuracyScene>& scenes,
                  const std::vector<MapperConfig>& mappers) {
    for (const AccuracyScene& scene : scenes) {
        const std::int64_t pixels = pixel_writes(scene);
        for (const MapperConfig& mapper : mappers) {
            auto error = std::make_shared<std::unique_ptr<TexelError>>();
            benchmark::RegisterBenchmark(
                benchmark_name(scene, mapper).c_str(),
                [&scene, &mapper, pixels, error](benchmark::State& state) {
                    if (!*error) { // deterministic: measured once per run
                        *error = std::make_unique<TexelError>(
                            measure_mapper_error(scene, mapper));
                    }
                    Framebuffer frame(scene.width, scene.height);
                    for (auto _ : state) {
                        draw_with(frame, scene, mapper);
                        benchmark::DoNotOptimize(frame.pixels().data());
                        benchmark::ClobberMemory();
                    }
                    using C = benchmark::Counter;
                    state.counters["pixels"] = C(double(pixels));
                    state.counters["ns_per_px"] = C(
                        double(pixels) * 1e-9, C::kIsIterationInvariantRate | C::kInvert);
                    state.counters["worst_texels"] = C((*error)->worst);
                    state.counters["mean_texels"] = C((*error)->mean);
                    state.counters["differing_share"] = C((*error)->differing_share);
                    state.counters["wrong_at_ties"] = C(double((*error)->wrong_at_ties));
                })
                ->Unit(benchmark::kMicrosecond);
        }
    }
}

} // namespace

int main(int argc, char** argv) {
    const std::vector<AccuracyScene> scenes = accuracy_scenes();
    const std::vector<MapperConfig> mappers = accuracy_mappers();
    for (int a = 1; a < argc; ++a) {
        if (std::strcmp(argv[a], "--list") == 0) {
            for (const AccuracyScene& s : scenes) {
                for (const MapperConfig& m : mappers) {
                    std::printf("%s %lld\n", benchmark_name(s, m).c_str(),
                                static_cast<long long>(pixel_writes(s)));
                }
            }
            return 0;
        }
        if (std::strncmp(argv[a], "--once=", 7) == 0) {
            const std::string wanted = argv[a] + 7;
            for (const AccuracyScene& s : scenes) {
                for (const MapperConfig& m : mappers) {
                    if (benchmark_name(s, m) == wanted) {
                        Framebuffer frame(s.width, s.height);
                        ch05_render_once(&frame, &s, &m);
                        std::printf("%s pixels %lld\n", wanted.c_str(),
                                    static_cast<long long>(pixel_writes(s)));
                        return 0;
                    }
                }
            }
            std::fprintf(stderr, "bench_ch05_mappers: no run named '%s' (see --list)\n",
                         wanted.c_str());
            return 2;
        }
    }
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
        return 1;
    }
    register_all(scenes, mappers);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
