// ewa.hpp: the elliptical weighted average (Heckbert 1989), chapter 8's reference
// filter: a Gaussian over the pixel's elliptical footprint, summed texel by texel.
//
// Usage:
//   MipChain chain = build_mip_chain(texture);
//   TexelDerivatives d = derivatives_at(triangle, centre);      // level_of_detail.hpp
//   LinearTexel c = sample_ewa(chain, uv, d, Wrap::repeat);     // linear light
//
// Units: uv in texels of level 0, derivatives in texels of level 0 per pixel, results in
// linear light (srgb.hpp). The pixel is a Gaussian on screen with the variance of the
// unit pixel square (1/12 per axis); the Jacobian J = [du/dx du/dy; dv/dx dv/dy] carries
// it to texel space with covariance ewa_pixel_variance * J J^T, and a texel's own square
// adds ewa_texel_variance on the level read (so a magnified pixel still reads a texel).
// Every texel whose centre lies within ewa_cutoff standard deviations (Mahalanobis
// distance) is weighted by exp(-d^2 / 2) and the weights are normalised. The level read
// is the one where the footprint's shorter side is one to two texels, raised when the
// longer side would span more than ewa_max_major texels there; levels are clamped to
// the chain.
#pragma once

#include "exactpixels/texture/level_of_detail.hpp"
#include "exactpixels/texture/mipmap.hpp"
#include "exactpixels/texture/srgb.hpp"
#include "exactpixels/texture/texture.hpp"

namespace exactpixels {

/// The variance per axis of the pixel square [0, 1)^2, in pixels^2: the screen Gaussian.
inline constexpr double ewa_pixel_variance = 1.0 / 12.0;

/// The variance per axis of one texel square of the level read, in its texels^2.
inline constexpr double ewa_texel_variance = 1.0 / 12.0;

/// Texels within this many standard deviations of uv are summed (3: the weights left out
/// are below exp(-4.5), 1.1% of the peak).
inline constexpr double ewa_cutoff = 3.0;

/// The longest footprint side, in texels of the level read, before a coarser level is
/// taken: bounds the texels one sample sums to about pi * 3^2 * ewa_max_major / 12.
inline constexpr double ewa_max_major = 64.0;

/// The elliptical weighted average of `chain` at uv with screen derivatives d.
LinearTexel sample_ewa(const MipChain& chain, TexCoord uv, const TexelDerivatives& d,
                       Wrap wrap);

} // namespace exactpixels
