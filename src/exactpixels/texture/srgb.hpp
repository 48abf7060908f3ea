// srgb.hpp: 8-bit sRGB codes to linear light and back, and images in linear light.
//
// Usage:
//   double l = srgb_to_linear16(188);           // 32768.9...: about half the light
//   std::uint8_t c = linear16_to_srgb(l);       // 188 again (for every code 0..255)
//   LinearImage img = decode_texture(texture);  // every texel in linear light
//   Rgba8 p = encode_linear(img.at(3, 2));      // the texel's 8-bit codes again
//
// Units (chapter 8): a linear channel is measured in units of 1/65535 of full light, so
// it lies in [0, 65535] and every decoded 8-bit code is a whole number of units (an
// integer held exactly in a double). Alpha is not gamma-encoded: code a stands for
// a * 257 units (255 * 257 = 65535). Filters average in these units and encode once,
// at the end, with round-to-nearest.
#pragma once

#include "exactpixels/base/framebuffer.hpp"
#include "exactpixels/texture/texture.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace exactpixels {

/// Full light in linear units: a linear channel lies in [0, linear_full].
inline constexpr double linear_full = 65535.0;

/// A texel in linear light: r, g, b, a in units of 1/65535 (see the usage block).
using LinearTexel = glm::dvec4;

/// The sRGB decoding curve (@eq:srgb-decode): the linear light, a fraction of full
/// light in [0, 1], of the code fraction s = code / 255 in [0, 1].
double srgb_decode(double s);

/// The sRGB encoding curve, the inverse of srgb_decode: the code fraction (code / 255,
/// not rounded) of the linear light l in [0, 1]; above 1 the curve goes on rising.
double srgb_encode(double l);

/// A Colour (each channel an sRGB code / 255, chapter 8's rule) in linear light: each
/// channel through srgb_decode.
Colour colour_to_linear(const Colour& c);

/// Linear light (each channel >= 0; below 0 counts as 0) back to a Colour: each channel
/// through srgb_encode, unrounded (to_rgba8 rounds it to the nearest code).
Colour linear_to_colour(const Colour& l);

/// The linear light of an 8-bit sRGB code, rounded to a whole unit of 1/65535
/// (@eq:srgb-decode).
double srgb_to_linear16(std::uint8_t code);

/// The 8-bit sRGB code nearest the linear value l in units of 1/65535 (@eq:srgb-encode);
/// l is clamped to [0, 65535]. linear16_to_srgb(srgb_to_linear16(c)) == c for every c.
std::uint8_t linear16_to_srgb(double l);

/// The fast variant of linear16_to_srgb, the same code for every l: a binary search in
/// the 255 linear values where the code steps up (found once, from linear16_to_srgb
/// itself), instead of a power function.
std::uint8_t linear16_to_srgb_fast(double l);

/// A texel decoded: colour channels through srgb_to_linear16, alpha times 257.
LinearTexel decode_texel(Rgba8 texel);

/// A linear texel encoded to 8 bits: colour by linear16_to_srgb, alpha by rounding a/257.
Rgba8 encode_linear(const LinearTexel& texel);

/// encode_linear with linear16_to_srgb_fast: the same pixel, faster.
Rgba8 encode_linear_fast(const LinearTexel& texel);

/// A width x height image in linear light, row-major, row 0 at the top (one mip level).
struct LinearImage {
    int width = 0;                   ///< texels per row, >= 1
    int height = 0;                  ///< rows, >= 1
    std::vector<LinearTexel> texels; ///< width * height texels, row after row
    /// Texel (i, j), both inside the image.
    const LinearTexel& at(int i, int j) const {
        return texels[static_cast<std::size_t>(j) * static_cast<std::size_t>(width) +
                      static_cast<std::size_t>(i)];
    }
};

/// Every texel of the texture in linear light (level 0 of a mip chain).
LinearImage decode_texture(const Texture& texture);

} // namespace exactpixels
