// Chapter 8: what each texture filter costs per pixel, on chapter 5's scenes and the
// horizon floor (filter_measure.hpp).
//
// Usage:
//   taskset -c 1 build/bin/bench_ch08_filters --benchmark_out=ch08.csv
//       --benchmark_out_format=csv                 # (one line) the full run, one core
//   build/bin/bench_ch08_filters --list            # every run's name and pixel count
//   build/bin/bench_ch08_filters --once=horizon/trilinear   # one pass (callgrind)
//   build/bin/bench_ch08_filters --oblique ...     # the exercise's wall60 scene only
//
// Each benchmark "scene/filter" samples every covered pixel of the scene once per
// iteration, given its texture coordinate and derivatives (computed beforehand, as a
// mapper would hand them over), and writes the colour into a frame (filter_frame in
// filter_measure.hpp): the filter, the level of detail, the mip fetches and the sRGB
// encode (its fast variant), not coverage or mapping (chapter 5 timed those). The
// baseline "nearest" fetches the 8-bit texel and writes it as it is, as a renderer
// does; "nearest linear-light" takes the same texel through linear light and back.
// Counters: pixels and ns_per_px, in CPU time (one thread: the process's). The errors are
// computed by fig_ch08_table against the reference (deterministic, not repeated per
// benchmark run).
// --oblique times chapter 8's exercise scene instead, the wall at 60 degrees
//   (oblique_wall_scene), and adds the counter `error`: the run's RMS error in 8-bit
//   codes on the minified pixels against the reference (rms_code_error), computed once
//   before timing (chapters/08-filtering/oblique.sh makes the committed table of it).
// --once filters one run's scene once inside the function ch08_filter_once, so that
//   valgrind --tool=callgrind --toggle-collect=ch08_filter_once bench_ch08_filters
//   --once=NAME
// counts the instructions of exactly one pass (chapters/08-filtering/callgrind.sh),
// after a first, uncounted pass that builds the one-time tables (the encode's steps).
#include "exactpixels/lab/filter_measure.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

using namespace exactpixels;

namespace {

/// "scene/filter" with spaces as '_'.
std::string run_name(const AccuracyScene& scene, const FilterConfig& config) {
    std::string name = scene.name + "/" + config.name;
    std::replace(name.begin(), name.end(), ' ', '_');
    return name;
}

} // namespace

/// One pass of the filter over the scene: the only function callgrind collects in --once
/// mode.
extern "C" [[gnu::noinline]] void
ch08_filter_once(Framebuffer* frame, const FilterScene* fs, const FilterConfig* config) {
    filter_frame(*frame, *fs, *config);
}

int main(int argc, char** argv) {
    for (int a = 1; a < argc; ++a) {
        const bool list = std::strcmp(argv[a], "--list") == 0;
        const bool once = std::strncmp(argv[a], "--once=", 7) == 0;
        if (!list && !once) {
            continue;
        }
        for (const AccuracyScene& scene : filter_scenes()) {
            for (const FilterConfig& config : filter_configs()) {
                const std::string name = run_name(scene, config);
                if (once && name != argv[a] + 7) {
                    continue;
                }
                const FilterScene fs = prepare_filter_scene(scene);
                if (once) {
                    Framebuffer frame(scene.width, scene.height);
                    filter_frame(frame, fs,
                                 config); // warm up: one-time tables built here
                    ch08_filter_once(&frame, &fs, &config);
                }
                std::printf("%s %zu\n", name.c_str(), fs.pixels.size());
                if (once) {
                    return 0;
                }
            }
        }
        if (once) {
            std::fprintf(stderr, "bench_ch08_filters: no run named '%s' (see --list)\n",
                         argv[a] + 7);
            return 2;
        }
        return 0;
    }
    bool oblique = false;
    for (int a = 1; a < argc; ++a) {
        if (std::strcmp(argv[a], "--oblique") == 0) {
            oblique = true;
            std::copy(argv + a + 1, argv + argc, argv + a); // not Google Benchmark's
            --argc;
            break;
        }
    }
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
        return 1;
    }
    const std::vector<AccuracyScene> scenes =
        oblique ? std::vector<AccuracyScene>{oblique_wall_scene()} : filter_scenes();
    std::vector<std::unique_ptr<FilterScene>> prepared;
    const std::vector<FilterConfig> configs = filter_configs();
    for (const AccuracyScene& scene : scenes) {
        prepared.push_back(std::make_unique<FilterScene>(prepare_filter_scene(scene)));
        const FilterScene* fs = prepared.back().get();
        std::vector<LinearTexel> reference;
        std::vector<bool> minified;
        if (oblique) { // deterministic: once, before any timing
            reference = reference_image(*fs);
            minified = minified_pixels(*fs);
        }
        const auto minified_count =
            static_cast<double>(std::count(minified.begin(), minified.end(), true));
        for (const FilterConfig& config : configs) {
            const double error =
                oblique ? rms_code_error(filter_image(*fs, config), reference, minified)
                        : 0.0;
            benchmark::RegisterBenchmark(
                run_name(scene, config).c_str(),
                [fs, &config, oblique, error, minified_count](benchmark::State& state) {
                    Framebuffer frame(fs->scene->width, fs->scene->height);
                    for (auto _ : state) {
                        filter_frame(frame, *fs, config);
                        benchmark::DoNotOptimize(frame.pixels().data());
                        benchmark::ClobberMemory();
                    }
                    const double pixels = double(fs->pixels.size());
                    using C = benchmark::Counter;
                    state.counters["pixels"] = C(pixels);
                    state.counters["ns_per_px"] =
                        C(pixels * 1e-9, C::kIsIterationInvariantRate | C::kInvert);
                    if (oblique) {
                        state.counters["error"] = C(error);
                        state.counters["minified"] = C(minified_count);
                    }
                })
                ->Unit(benchmark::kMicrosecond);
        }
    }
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
