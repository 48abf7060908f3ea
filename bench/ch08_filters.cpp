// Chapter 8: what each texture filter costs per pixel, on chapter 5's scenes and the
// horizon floor (filter_measure.hpp).
//
// Usage:
//   taskset -c 1 build/bin/bench_ch08_filters --benchmark_out=ch08.csv
//       --benchmark_out_format=csv                 # (one line) the full run, one core
//
// Each benchmark "scene/filter" samples every covered pixel of the scene once per
// iteration, given its texture coordinate and derivatives (computed beforehand, as a
// mapper would hand them over), and writes the encoded colour into a frame: the filter,
// the level of detail, the mip fetches and the sRGB encode (its fast variant), not
// coverage or mapping (chapter 5 timed those). Counters: pixels and ns_per_px. The
// errors are computed by fig_ch08_table against the reference (too slow to repeat per
// benchmark run).
#include "exactpixels/filter_measure.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
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

//> bench-loop
/// Every pixel of the scene through the configuration, into the frame.
void filter_into(Framebuffer& frame, const FilterScene& fs, const FilterConfig& config) {
    for (const FilterPixel& p : fs.pixels) {
        const TexelDerivatives& d =
            config.derivatives == Derivatives::per_pixel ? p.exact : p.triangle_wide;
        frame.at(p.x, p.y) =
            encode_linear_fast(sample_filtered(fs.chain, p.uv, d, config.settings));
    }
}
//< bench-loop

} // namespace

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
        return 1;
    }
    const std::vector<AccuracyScene> scenes = filter_scenes();
    std::vector<std::unique_ptr<FilterScene>> prepared;
    const std::vector<FilterConfig> configs = filter_configs();
    for (const AccuracyScene& scene : scenes) {
        prepared.push_back(std::make_unique<FilterScene>(prepare_filter_scene(scene)));
        const FilterScene* fs = prepared.back().get();
        for (const FilterConfig& config : configs) {
            benchmark::RegisterBenchmark(
                run_name(scene, config).c_str(),
                [fs, &config](benchmark::State& state) {
                    Framebuffer frame(fs->scene->width, fs->scene->height);
                    for (auto _ : state) {
                        filter_into(frame, *fs, config);
                        benchmark::DoNotOptimize(frame.pixels().data());
                        benchmark::ClobberMemory();
                    }
                    const double pixels = double(fs->pixels.size());
                    using C = benchmark::Counter;
                    state.counters["pixels"] = C(pixels);
                    state.counters["ns_per_px"] =
                        C(pixels * 1e-9, C::kIsIterationInvariantRate | C::kInvert);
                })
                ->Unit(benchmark::kMicrosecond);
        }
    }
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
