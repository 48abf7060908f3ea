// filter.hpp: one texture sample per pixel, by any of chapter 8's filters.
//
// Usage:
//   MipChain chain = build_mip_chain(texture);
//   TexelDerivatives d = derivatives_at(triangle, centre);   // level_of_detail.hpp
//   FilterSettings s{.filter = Filter::trilinear, .wrap = Wrap::repeat};
//   Rgba8 c = encode_linear(sample_filtered(chain, uv, d, s));
//
// Units: uv in texels of level 0 (texel (i, j) covers [i, i+1) x [j, j+1)), derivatives
// in texels of level 0 per pixel, results in linear light (srgb.hpp). A coordinate on
// level k is u * width_k / width_0 (and v with the heights). The filters:
//   - nearest: texel floor(u), floor(v) of level 0 (chapter 3's sampling);
//   - bilinear: @eq:bilinear-split on level 0;
//   - mip_nearest: the nearest texel of the level nearest lambda (@eq:level);
//   - trilinear: bilinear on the two levels around lambda, blended by its fraction;
//   - anisotropic: N trilinear probes spread along the footprint's longer side
//   (@eq:anisotropy);
//   - ewa: the elliptical weighted average, the reference filter (ewa.hpp).
// Levels below 0 (magnification) use level 0; levels above the last use the last.
#pragma once

#include "exactpixels/texture/level_of_detail.hpp"
#include "exactpixels/texture/mipmap.hpp"
#include "exactpixels/texture/srgb.hpp"
#include "exactpixels/texture/texture.hpp"

#include <string_view>

namespace exactpixels {

/// Which filter turns (u, v) and its derivatives into a colour.
enum class Filter {
    nearest,     ///< the texel holding (u, v) on level 0
    bilinear,    ///< @eq:bilinear-sample on level 0
    mip_nearest, ///< the nearest texel of the level nearest the level of detail
    trilinear,   ///< bilinear on the two levels around the level of detail, blended
    anisotropic, ///< trilinear probes along the footprint's longer side (@eq:anisotropy)
    ewa          ///< Heckbert's elliptical weighted average (ewa.hpp), the reference
};

/// The filter's name as the chapter and the scene files spell it: "nearest",
/// "bilinear", "mip-nearest", "trilinear", "anisotropic", "ewa".
std::string_view filter_name(Filter filter);

/// Everything that chooses how a pixel is filtered.
struct FilterSettings {
    Filter filter = Filter::trilinear; ///< which filter
    Wrap wrap = Wrap::repeat;          ///< how indices outside a level wrap
    int max_probes = 8;                ///< anisotropic: at most this many probes, >= 1
};

/// The sample of `chain` at uv (level-0 texels) with screen derivatives d.
LinearTexel sample_filtered(const MipChain& chain, TexCoord uv, const TexelDerivatives& d,
                            const FilterSettings& settings);

/// Trilinear at an explicit level lambda: bilinear on floor(lambda) and the level
/// below it in the chain, blended by lambda - floor(lambda); clamped to the chain.
LinearTexel sample_trilinear(const MipChain& chain, TexCoord uv, double lambda,
                             Wrap wrap);

} // namespace exactpixels
