// Chapter 5 and 6's exercises on the mapper's inner loop: what wrapping a texel index by
// a bit mask saves over wrap_index's modulo, and what evaluating the affine line afresh
// at every pixel (u0 + k du, chapter 6's cure for drift) costs over stepping it.
//
// Usage:
//   taskset -c 1 build/bin/bench_ch05_span_loops --benchmark_repetitions=5
//       --benchmark_enable_random_interleaving=true --benchmark_out=loops.csv
//       --benchmark_out_format=csv                       (one line)
//   chapters/05-accuracy-cost/span_loops.sh build     # the committed table from it
//
// Each run maps the same 256 spans of 320 pixels (u and v from 0 to about 200 texels,
// the depth doubling along every span) into a row of RGBA8 texels fetched from a 64 x 64
// texture with the repeat wrap: the whole inner loop of chapter 3's mappers, coverage and
// setup left out. Variants: the affine mapper in float, stepped (as the library draws)
// or evaluated afresh; the exact mapper in double (a divide per pixel); each with the
// modulo of wrap_index or the mask of wrap_index_masked. Counter ns_per_px: CPU time per
// pixel.
#include "exactpixels/texture/span_mappers.hpp"
#include "exactpixels/texture/texture.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <vector>

using namespace exactpixels;

namespace {

constexpr int span_count = 256;
constexpr int span_pixels = 320;

struct Workload {
    Texture texture = checkerboard_texture(64, 64, 4);
    std::vector<PerspectiveSpan<double>> perspective;
    std::vector<AffineSpan<float>> affine;
};

const Workload& workload() {
    static const Workload w = [] {
        Workload w;
        for (int s = 0; s < span_count; ++s) {
            // Depth 1 + s/256 at pixel 0, twice that at the last pixel.
            const double w0 = 1.0 + s / 256.0, w1 = 2.0 * w0;
            const double u0 = 0.25 + s, u1 = u0 + 200.0, v0 = 0.5 * s, v1 = v0 + 150.0;
            const double n = span_pixels - 1;
            PerspectiveSpan<double> p{u0 / w0,
                                      v0 / w0,
                                      1.0 / w0,
                                      (u1 / w1 - u0 / w0) / n,
                                      (v1 / w1 - v0 / w0) / n,
                                      (1.0 / w1 - 1.0 / w0) / n,
                                      span_pixels};
            w.perspective.push_back(p);
            w.affine.push_back(AffineSpan<float>{float(u0), float(v0),
                                                 float((u1 - u0) / n),
                                                 float((v1 - v0) / n), span_pixels});
        }
        return w;
    }();
    return w;
}

enum class Line { affine_stepped, affine_fresh, exact };
enum class Wrapping { modulo, mask };

template <Line line, Wrapping wrapping> void span_loop(benchmark::State& state) {
    const Workload& w = workload();
    const Texture& t = w.texture;
    std::vector<Rgba8> row(span_pixels);
    const auto emit = [&](int k, auto u, auto v) {
        const int i = static_cast<int>(std::floor(u)),
                  j = static_cast<int>(std::floor(v));
        if constexpr (wrapping == Wrapping::modulo) {
            row[static_cast<std::size_t>(k)] =
                t.texel(wrap_index(i, t.width(), Wrap::repeat),
                        wrap_index(j, t.height(), Wrap::repeat));
        } else {
            row[static_cast<std::size_t>(k)] = t.texel(wrap_index_masked(i, t.width()),
                                                       wrap_index_masked(j, t.height()));
        }
    };
    for (auto _ : state) {
        for (int s = 0; s < span_count; ++s) {
            const auto index = static_cast<std::size_t>(s);
            if constexpr (line == Line::affine_stepped) {
                map_span_affine(w.affine[index], emit);
            } else if constexpr (line == Line::affine_fresh) {
                map_span_affine_fresh(w.affine[index], emit);
            } else {
                map_span_exact(w.perspective[index], emit);
            }
            benchmark::DoNotOptimize(row.data());
            benchmark::ClobberMemory();
        }
    }
    const double pixels = double(span_count) * span_pixels;
    state.counters["ns_per_px"] =
        benchmark::Counter(double(state.iterations()) * pixels * 1e-9,
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

} // namespace

BENCHMARK(span_loop<Line::affine_stepped, Wrapping::modulo>)
    ->Name("affine_stepped/modulo");
BENCHMARK(span_loop<Line::affine_stepped, Wrapping::mask>)->Name("affine_stepped/mask");
BENCHMARK(span_loop<Line::affine_fresh, Wrapping::modulo>)->Name("affine_fresh/modulo");
BENCHMARK(span_loop<Line::affine_fresh, Wrapping::mask>)->Name("affine_fresh/mask");
BENCHMARK(span_loop<Line::exact, Wrapping::modulo>)->Name("exact_double/modulo");
BENCHMARK(span_loop<Line::exact, Wrapping::mask>)->Name("exact_double/mask");

BENCHMARK_MAIN();
