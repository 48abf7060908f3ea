#include "exactpixels/texture/texel_error.hpp"

#include "exactpixels/base/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace exactpixels {

//> texel-error
double texel_error(double u, double v, double u_ref, double v_ref) {
    //> exercise ch05-texel-error: one error in texels from the two coordinate errors.
    // The larger of the two: below 1/2 exactly when neither coordinate is half a texel off.
    return std::max(std::abs(u - u_ref), std::abs(v - v_ref));
    //| (void)u, (void)v, (void)u_ref, (void)v_ref;
    //| return 0.0; // stub: every mapper looks perfect
    //< exercise ch05-texel-error
}
//< texel-error

TexelError compare_texel_maps(const TexelMap& reference, const TexelMap& candidate) {
    return compare_texel_maps(reference, candidate,
                              std::vector<char>(reference.covered.size(), 1));
}

TexelError compare_texel_maps(const TexelMap& reference, const TexelMap& candidate,
                              const std::vector<char>& include) {
    if (reference.width != candidate.width || reference.height != candidate.height) {
        throw Error(fmt::format("compare_texel_maps: sizes {}x{} and {}x{} differ",
                                reference.width, reference.height, candidate.width,
                                candidate.height));
    }
    if (include.size() != reference.covered.size()) {
        throw Error(fmt::format("compare_texel_maps: {} include flags for {} pixels",
                                include.size(), reference.covered.size()));
    }
    TexelError e;
    double sum = 0.0;
    std::int64_t differing = 0;
    for (std::size_t k = 0; k < reference.covered.size(); ++k) {
        if (!include[k]) {
            continue;
        }
        if (reference.covered[k] != candidate.covered[k]) {
            ++e.coverage_mismatches;
            continue;
        }
        if (!reference.covered[k]) {
            continue;
        }
        if (!std::isfinite(candidate.u[k]) || !std::isfinite(candidate.v[k]) ||
            !std::isfinite(reference.u[k]) || !std::isfinite(reference.v[k])) {
            ++e.not_finite;
            continue;
        }
        const double error =
            texel_error(candidate.u[k], candidate.v[k], reference.u[k], reference.v[k]);
        e.worst = std::max(e.worst, error);
        sum += error;
        const bool differs =
            candidate.i[k] != reference.i[k] || candidate.j[k] != reference.j[k];
        const bool tie = std::floor(reference.u[k]) == reference.u[k] ||
                         std::floor(reference.v[k]) == reference.v[k];
        differing += differs;
        e.ties += tie;
        e.wrong_at_ties += tie && differs;
        ++e.pixels;
    }
    if (e.pixels > 0) {
        e.mean = sum / double(e.pixels);
        e.differing_share = double(differing) / double(e.pixels);
    }
    return e;
}

} // namespace exactpixels
