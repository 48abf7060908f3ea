// Chapter 0's exercise on the cost of writing a PNG: write_png on square frames of 64^2
// to 2048^2 pixels, split into its parts.
//
// Usage:
//   taskset -c 1 build/bin/bench_ch00_png --benchmark_repetitions=5
//       --benchmark_enable_random_interleaving=true --benchmark_out=png.csv
//       --benchmark_out_format=csv                       (one line)
//   chapters/00-pixels/png_results.sh build         # the committed table from it
//
// For each side N the frame holds a smooth gradient under a checkerboard of 8-pixel
// squares (content that compresses, as rendered pictures do). Runs:
//   copy/N    the frame's pixels copied into another buffer (what any output pays)
//   encode/N  encode_png: stb's row filters and deflate, in memory
//   write/N   write_png: the encoding, then the file written, flushed to the disk
//             (fsync) and renamed over the target (atomic_file.hpp), into the
//             system's temporary folder
// Counters: bytes_per_px, the size of the copy, the encoded PNG or the file per pixel;
// ns_per_px, CPU time per pixel (write/N also waits for the disk, which CPU time
// does not count: its wall-clock time is the real_time column).
#include "exactpixels/base/png.hpp"

#include <benchmark/benchmark.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

using namespace exactpixels;

namespace {

Framebuffer frame_of_side(int n) {
    Framebuffer frame(n, n);
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            const bool dark = ((x / 8) + (y / 8)) % 2 == 1;
            frame.at(x, y) = Rgba8{static_cast<std::uint8_t>(x * 255 / n),
                                   static_cast<std::uint8_t>(y * 255 / n),
                                   static_cast<std::uint8_t>(dark ? 64 : 192), 255};
        }
    }
    return frame;
}

/// The counters every run reports (Google Benchmark's CSV needs the same in each):
/// bytes_per_px, the size of what the run produced per pixel, and ns_per_px.
void per_pixel(benchmark::State& state, int n, double bytes) {
    state.counters["bytes_per_px"] = bytes / (double(n) * n);
    state.counters["ns_per_px"] =
        benchmark::Counter(double(state.iterations()) * n * n * 1e-9,
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void copy(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    const Framebuffer frame = frame_of_side(n);
    std::vector<Rgba8> out(frame.pixels().size());
    for (auto _ : state) {
        std::memcpy(out.data(), frame.pixels().data(), out.size() * sizeof(Rgba8));
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    per_pixel(state, n, double(out.size() * sizeof(Rgba8)));
}

void encode(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    const Framebuffer frame = frame_of_side(n);
    std::size_t bytes = 0;
    for (auto _ : state) {
        const std::string png = encode_png(frame);
        bytes = png.size();
        benchmark::DoNotOptimize(png.data());
    }
    per_pixel(state, n, double(bytes));
}

void write(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    const Framebuffer frame = frame_of_side(n);
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() /
        ("exactpixels-bench-" + std::to_string(::getpid()) + ".png");
    for (auto _ : state) {
        write_png(path, frame);
    }
    const auto bytes = std::filesystem::file_size(path);
    std::filesystem::remove(path);
    per_pixel(state, n, double(bytes));
}

} // namespace

BENCHMARK(copy)->Name("copy")->RangeMultiplier(2)->Range(64, 2048);
BENCHMARK(encode)->Name("encode")->RangeMultiplier(2)->Range(64, 2048);
BENCHMARK(write)->Name("write")->RangeMultiplier(2)->Range(64, 2048);

BENCHMARK_MAIN();
