// Chapter 7's depth precision (@sec:scene-depth): the depth step, the smallest distance
// between two surfaces that always store different keys, over the distance from the
// near plane (0.1) to the far plane (1000), for the renderer's float 1/w, OpenGL's z/w in
// 24-bit fixed point and reversed z in float (depth_precision.hpp). Writes
// ch07_depth_precision.dat (ch07_depth_precision.gp plots it) and the steps at 1, 10 and
// 100 units as facts for the prose (ch07_depth_precision.txt).
// Usage: fig_ch07_depth_precision FIGURE_DIR
#include "exactpixels/base/error.hpp"
#include "exactpixels/scene/depth_precision.hpp"
#include "support/figure_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

using namespace exactpixels;

int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    constexpr double near = 0.1, far = 1000.0;
    constexpr int samples = 400; // log-spaced from near to just short of far
    std::string data = "# w  float_1/w  fixed24_z/w  reversed_float  (depth steps)\n";
    double ours_over_reversed_least = 1e300, ours_over_reversed_most = 0.0; // w <= 100
    for (int k = 0; k < samples; ++k) {
        const double w = near * std::pow(far / near, double(k) / samples);
        const double ours = nearness_depth_step(w);
        const double reversed = reversed_z_depth_step(w, near, far);
        data += fmt::format("{:.6g} {:.6g} {:.6g} {:.6g}\n", w, ours,
                            fixed_z_depth_step(w, near, far, 24), reversed);
        if (w <= 100.0) {
            ours_over_reversed_least = std::min(ours_over_reversed_least, ours / reversed);
            ours_over_reversed_most = std::max(ours_over_reversed_most, ours / reversed);
        }
    }
    std::string facts = "# depth steps (units of w), near 0.1, far 1000: float 1/w (ours), "
                        "24-bit fixed z/w, reversed z in float\n";
    for (const int w : {1, 10, 100}) {
        facts += fmt::format("ours_{0} {1:.3g}\nfixed_{0} {2:.3g}\nreversed_{0} {3:.3g}\n", w,
                             nearness_depth_step(w), fixed_z_depth_step(w, near, far, 24),
                             reversed_z_depth_step(w, near, far));
    }
    facts += fmt::format("# float 1/w's step over reversed z's, from the near plane to 100\n"
                         "ours_over_reversed_least {:.3f}\nours_over_reversed_most {:.3f}\n",
                         ours_over_reversed_least, ours_over_reversed_most);
    try {
        write_figure_file(folder / "ch07_depth_precision.dat", data);
        write_figure_file(folder / "ch07_depth_precision.txt", facts);
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch07_depth_precision: %s\n", error.what());
        return 1;
    }
}
