// texel_error.hpp: how far a mapper's texels are from a reference's, measured over every
// pixel of a render (chapter 5's measure; chapter 7's `render --check` uses it too).
//
// Usage:
//   TexelMap reference(320, 240), candidate(320, 240);
//   map_textured_triangle(reference, triangle, exact_settings);
//   map_textured_triangle(candidate, triangle, settings);
//   TexelError e = compare_texel_maps(reference, candidate);
//   // e.worst, e.mean in texels; e.differing_share in [0, 1]; e.wrong_at_ties, pixels
//
// The texel error at a pixel is one number in texels made from |u - u_ref| and
// |v - v_ref| (@eq:texel-error), where (u, v) is the coordinate the mapper computed there (16.16 values divided by
// 2^16) and (u_ref, v_ref) the reference's. A pixel "differs" when the texel indices
// (i, j) the two picked are not the same (compared before wrapping). A pixel is a "tie"
// when the reference's u or v is a whole number: the sample lies exactly on a texel edge,
// where only the rounding rule (chapter 4) decides the texel; wrong_at_ties counts the
// ties where the candidate's texel differs, the error that rule fixes. Only pixels that
// both maps cover are compared; every mapper covers the same pixels (chapter 1's
// fixed-point coverage), and coverage_mismatches counts any pixel where that fails.
#pragma once

#include "exactpixels/texture/texture_mapper.hpp"

#include <cstdint>
#include <vector>

namespace exactpixels {

/// The error of one render against the reference.
struct TexelError {
    std::int64_t pixels = 0;              ///< pixels covered by both and compared
    double worst = 0.0;                   ///< largest texel error, texels
    double mean = 0.0;                    ///< mean texel error, texels
    double differing_share = 0.0;         ///< share of pixels whose texel differs, [0, 1]
    std::int64_t ties = 0;                ///< pixels whose reference u or v is whole
    std::int64_t wrong_at_ties = 0;       ///< ties where the texel differs
    std::int64_t coverage_mismatches = 0; ///< pixels covered by one map only
    /// Pixels where either map holds a NaN or infinite coordinate: a failure, counted
    /// apart and never hidden in worst or mean (std::max would drop a NaN).
    std::int64_t not_finite = 0;
};

/// The texel error at one pixel, in texels (@eq:texel-error).
double texel_error(double u, double v, double u_ref, double v_ref);

/// Compares two maps of the same size pixel by pixel (Error if the sizes differ).
TexelError compare_texel_maps(const TexelMap& reference, const TexelMap& candidate);

/// The same, counting only pixels k with include[k] != 0 (include: one entry per
/// pixel, row-major).
TexelError compare_texel_maps(const TexelMap& reference, const TexelMap& candidate,
                              const std::vector<char>& include);

} // namespace exactpixels
