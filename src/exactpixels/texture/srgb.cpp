#include "exactpixels/texture/srgb.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace exactpixels {

//> srgb-curves
// The sRGB transfer curves on [0, 1] (@eq:srgb-decode and 8.2): a straight segment near
// black, a power curve above it; each is the other's inverse.
double srgb_decode(double s) {
    return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
}
double srgb_encode(double l) {
    return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
}
//< srgb-curves

Colour colour_to_linear(const Colour& c) {
    return {srgb_decode(c.r), srgb_decode(c.g), srgb_decode(c.b)};
}

Colour linear_to_colour(const Colour& l) {
    return {srgb_encode(std::max(l.r, 0.0)), srgb_encode(std::max(l.g, 0.0)),
            srgb_encode(std::max(l.b, 0.0))};
}

namespace {

std::array<double, 256> decode_table() {
    std::array<double, 256> table{};
    for (int c = 0; c < 256; ++c) {
        table[static_cast<std::size_t>(c)] =
            std::round(srgb_decode(c / 255.0) * linear_full);
    }
    return table;
}

/// For each code c = 1..255 the smallest double l with linear16_to_srgb(l) >= c, found
/// by bisection on the doubles between two linear values (the code only grows with l).
std::array<double, 256> code_thresholds() {
    std::array<double, 256> t{};
    t[0] = -1.0; // every l reaches code 0
    for (int c = 1; c < 256; ++c) {
        double lo = 0.0, hi = linear_full; // code(lo) < c <= code(hi)
        while (std::nextafter(lo, hi) < hi) {
            const double mid = lo + (hi - lo) / 2;
            const double probe = mid > lo && mid < hi ? mid : std::nextafter(lo, hi);
            (linear16_to_srgb(probe) >= c ? hi : lo) = probe;
        }
        t[static_cast<std::size_t>(c)] = hi;
    }
    return t;
}

} // namespace

double srgb_to_linear16(std::uint8_t code) {
    static const std::array<double, 256> table = decode_table();
    return table[code];
}

std::uint8_t linear16_to_srgb(double l) {
    const double s = srgb_encode(std::clamp(l, 0.0, linear_full) / linear_full);
    return static_cast<std::uint8_t>(std::lround(s * 255.0));
}

std::uint8_t linear16_to_srgb_fast(double l) {
    static const std::array<double, 256> thresholds = code_thresholds();
    // The last threshold not above l: its index is the code.
    const auto above = std::upper_bound(thresholds.begin() + 1, thresholds.end(), l);
    return static_cast<std::uint8_t>(above - thresholds.begin() - 1);
}

LinearTexel decode_texel(Rgba8 t) {
    return {srgb_to_linear16(t.r), srgb_to_linear16(t.g), srgb_to_linear16(t.b),
            t.a * 257.0};
}

Rgba8 encode_linear(const LinearTexel& t) {
    const double a = std::clamp(t.a, 0.0, linear_full) / 257.0;
    return {linear16_to_srgb(t.r), linear16_to_srgb(t.g), linear16_to_srgb(t.b),
            static_cast<std::uint8_t>(std::lround(a))};
}

Rgba8 encode_linear_fast(const LinearTexel& t) {
    const double a = std::clamp(t.a, 0.0, linear_full) / 257.0;
    return {linear16_to_srgb_fast(t.r), linear16_to_srgb_fast(t.g),
            linear16_to_srgb_fast(t.b), static_cast<std::uint8_t>(std::lround(a))};
}

LinearImage decode_texture(const Texture& texture) {
    LinearImage image{texture.width(), texture.height(), {}};
    image.texels.reserve(texture.texels().size());
    for (const Rgba8& t : texture.texels()) {
        image.texels.push_back(decode_texel(t));
    }
    return image;
}

} // namespace exactpixels
