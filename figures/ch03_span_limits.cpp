// Figure data for chapter 3's Exercise 5: on one span of 256 pixels that runs over 256
// texels, how large may the depth ratio r grow before the subdivided affine and the
// subdivided quadratic mapper (pieces of N = 4, 8, 16, 32 pixels, in double) pick another
// texel than the exact mapper, or stray by more than half a texel from it? And what does
// the table of span limits predict, applied piece by piece? Writes ch03_span_limits.txt
// into the folder argv[1], one fact per line (MAPPER is sub or quad):
//   MAPPER_N_texel  the largest r before some pixel's texel floor(u) differs
//   MAPPER_N_half   the largest r before some pixel's u is more than 1/2 texel off
//   MAPPER_N_pred   the largest r for which every piece, at its own depth ratio and
//                   extent, is within 1/2 texel by @eq:affine-bound / @eq:quadratic-error
//   r_max           the largest r tried (a limit equal to it means: not reached)
// The ratios tried grow by 0.5 % a step from 1 to r_max; u runs from 0.25 at pixel 0 to
// 256.25 at pixel 255 (so no exact u lands on a texel edge at either end), depth from 1
// to r, in the placement of figures/ch03_mappers.cpp (@eq:exact-fraction).
#include "exactpixels/base/error.hpp"
#include "exactpixels/texture/perspective_error.hpp"
#include "exactpixels/texture/span_mappers.hpp"
#include "support/figure_file.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace exactpixels;

constexpr int span_pixels = 256;
constexpr double span_texels = 256.0;
constexpr double u_first = 0.25;
constexpr double r_max = 1024.0;

/// The span of depth ratio r: u from u_first at pixel 0 to u_first + 256 at pixel 255.
PerspectiveSpan<double> span_of(double r) {
    const double n = span_pixels - 1, u0 = u_first, u1 = u_first + span_texels;
    return {u0, 0.0, 1.0, (u1 / r - u0) / n, 0.0, (1.0 / r - 1.0) / n, span_pixels};
}

/// The worst |u - exact u| and whether any pixel's texel differs, for one mapper.
struct Outcome {
    double worst = 0;
    bool other_texel = false;
};

Outcome compare(double r, int n, bool quadratic) {
    const PerspectiveSpan<double> s = span_of(r);
    std::vector<double> exact(span_pixels);
    map_span_exact(s, [&](int k, double u, double) { exact[k] = u; });
    Outcome out;
    const auto check = [&](int k, double u, double) {
        out.worst = std::max(out.worst, std::abs(u - exact[k]));
        out.other_texel = out.other_texel || std::floor(u) != std::floor(exact[k]);
    };
    if (quadratic) {
        map_span_quadratic_subdivided(s, n, check);
    } else {
        map_span_subdivided(s, n, check);
    }
    return out;
}

/// the span-limit table's rule applied to every piece the mapper places: each piece's own
/// depth ratio and texel extent must keep its worst error within half a texel.
bool predicted_within(double r, int n, bool quadratic) {
    const PerspectiveSpan<double> s = span_of(r);
    const auto depth = [&](int k) { return 1.0 / (s.one_w + k * s.done_w); };
    const auto u = [&](int k) { return (s.u_w + k * s.du_w) * depth(k); };
    for (int k0 = 0; k0 < span_pixels - 1; k0 += n) {
        const int k1 = piece_target(k0, n, span_pixels);
        const double ratio = depth(k1) / depth(k0), extent = std::abs(u(k1) - u(k0));
        const double fraction =
            quadratic ? quadratic_error_max(ratio) : affine_error_bound(ratio);
        if (fraction * extent > 0.5) {
            return false;
        }
    }
    return true;
}

} // namespace

int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    std::vector<double> ratios;
    for (double r = 1.0; r <= r_max; r *= 1.005) {
        ratios.push_back(r);
    }
    std::ostringstream facts;
    facts << "# chapter 3, Exercise 5: largest depth ratio of a 256-pixel, 256-texel "
             "span\n";
    for (const bool quadratic : {false, true}) {
        for (const int n : {4, 8, 16, 32}) {
            // The largest r of the grid before the first failure of each criterion.
            double texel = ratios.back(), half = ratios.back(), pred = ratios.back();
            bool texel_done = false, half_done = false, pred_done = false;
            for (std::size_t i = 1; i < ratios.size(); ++i) {
                const Outcome o = compare(ratios[i], n, quadratic);
                if (!texel_done && o.other_texel) {
                    texel = ratios[i - 1], texel_done = true;
                }
                if (!half_done && o.worst > 0.5) {
                    half = ratios[i - 1], half_done = true;
                }
                if (!pred_done && !predicted_within(ratios[i], n, quadratic)) {
                    pred = ratios[i - 1], pred_done = true;
                }
            }
            const std::string key =
                std::string(quadratic ? "quad_" : "sub_") + std::to_string(n);
            facts << key << "_texel " << texel << '\n'
                  << key << "_half " << half << '\n'
                  << key << "_pred " << pred << '\n';
        }
    }
    facts << "r_max " << ratios.back() << '\n';
    try {
        write_figure_file(folder / "ch03_span_limits.txt", facts.str());
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch03_span_limits: %s\n", error.what());
        return 1;
    }
}
