// bilinear.hpp: bilinear texture sampling from chapter 3's 16.16 texel coordinates.
//
// Usage:
//   LinearImage img = decode_texture(f_texture(4));
//   std::int32_t U = to_texel_fixed(3.5), V = to_texel_fixed(0.5); // 16.16, D = 2^16
//   BilinearTaps t = bilinear_taps(U, V);          // texels (3, 0)..(4, 1), weights
//   LinearTexel c = sample_bilinear(img, U, V, Wrap::clamp);  // exactly texel (3, 0)
//
// Conventions (chapters 3, 4 and 8). u is in texels, texel i covers [i, i+1), its
// centre is at u = i + 1/2. The fixed-point coordinate is U = u * D with D = 2^16, as
// chapter 3's fixed loops hold it. Bilinear sampling measures from texel centres, like
// chapter 4's rounding, and splits that coordinate into the left texel i and the
// fraction f in [0, D) (@eq:bilinear-split). Texel i gets weight D - f,
// texel i + 1 weight f (@eq:bilinear-sample); both directions multiply, so the four
// weights are integers summing to D^2. At a texel centre f = 0 and the sample is that
// texel, exactly. Indices outside the image are wrapped (repeat or clamp) as
// texture.hpp's nearest sampling does.
#pragma once

#include "exactpixels/base/types.hpp"
#include "exactpixels/texture/srgb.hpp"
#include "exactpixels/texture/texture.hpp"
#include "exactpixels/texture/texture_mapper.hpp"

#include <array>
#include <cstdint>

namespace exactpixels {

/// The 2 x 2 texels a bilinear sample blends: the top-left one and the fractions.
struct BilinearTaps {
    int i = 0;           ///< column of the left texels
    int j = 0;           ///< row of the upper texels
    std::int64_t fu = 0; ///< weight of column i + 1, in [0, D); column i gets D - fu
    std::int64_t fv = 0; ///< weight of row j + 1, in [0, D); row j gets D - fv
};

//> bilinear-taps
/// The texels and fractions of a bilinear sample at (U, V) in 16.16 (@eq:bilinear-split).
constexpr BilinearTaps bilinear_taps(std::int32_t U, std::int32_t V) {
    constexpr std::int64_t D = texel_scale;
    //> exercise ch08-bilinear: measure from texel centres; split that into floor and fraction.
    // C = U - D/2 is 0 at texel 0's centre.
    const std::int64_t Cu = std::int64_t{U} - D / 2; // u - 1/2: 0 at texel 0's centre
    const std::int64_t Cv = std::int64_t{V} - D / 2;
    const std::int64_t i = Cu >> texel_fraction_bits; // floor(Cu / D), also for Cu < 0
    const std::int64_t j = Cv >> texel_fraction_bits;
    return {static_cast<int>(i), static_cast<int>(j), Cu - i * D, Cv - j * D};
    //| (void)D;
    //| return {static_cast<int>(U >> texel_fraction_bits),
    //|         static_cast<int>(V >> texel_fraction_bits), 0, 0}; // stub: nearest, rule 1
    //< exercise ch08-bilinear
}
//< bilinear-taps

/// The four integer weights of the taps, in the order (i, j), (i+1, j), (i, j+1),
/// (i+1, j+1); they sum to D^2 = 2^32.
constexpr std::array<std::int64_t, 4> bilinear_weights(const BilinearTaps& t) {
    constexpr std::int64_t D = texel_scale;
    return {(D - t.fu) * (D - t.fv), t.fu * (D - t.fv), (D - t.fu) * t.fv, t.fu * t.fv};
}

/// A real texel coordinate in 16.16: the nearest multiple of 1/D (ties upwards). |u|
/// must be below 2^14, as for chapter 3's fixed loops.
std::int32_t to_texel_fixed(double u);

/// The bilinear sample at (U, V) in 16.16, in linear light (@eq:bilinear-split and 8.4).
LinearTexel sample_bilinear(const LinearImage& image, std::int32_t U, std::int32_t V,
                            Wrap wrap);

/// The bilinear sample at (u, v) in texels: (u, v) rounded to 16.16 first.
LinearTexel sample_bilinear(const LinearImage& image, TexCoord uv, Wrap wrap);

/// The nearest texel at (u, v) in texels, floor(u), floor(v) (rule 1), wrapped.
LinearTexel sample_nearest(const LinearImage& image, TexCoord uv, Wrap wrap);

} // namespace exactpixels
