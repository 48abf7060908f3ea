// Chapter 8 tests, part 1: sRGB, bilinear sampling from chapter 3's 16.16 coordinates,
// and its exactness at 1:1 and under mirroring.
#include "exactpixels/texture/bilinear.hpp"
#include "exactpixels/texture/srgb.hpp"
#include "exactpixels/texture/texture.hpp"
#include "exactpixels/texture/texture_mapper.hpp"
#include "support/printing.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

using namespace exactpixels;

namespace {

constexpr std::int64_t D = texel_scale;

/// The texture mirrored left-right (mu) and/or top-bottom (mv).
Texture mirrored(const Texture& t, bool mu, bool mv) {
    std::vector<Rgba8> texels;
    for (int j = 0; j < t.height(); ++j) {
        for (int i = 0; i < t.width(); ++i) {
            texels.push_back(
                t.texel(mu ? t.width() - 1 - i : i, mv ? t.height() - 1 - j : j));
        }
    }
    return Texture(t.width(), t.height(), texels);
}

/// The 16.16 coordinates chapter 3's exact fixed-point mapper gives every pixel of a 1:1
/// quad of a W x H texture with its corner at (3 + offset, 2 + offset), u running
/// backwards when mu, v when mv. The map's u and v hold U / D exactly.
TexelMap one_to_one(int W, int H, double offset, bool mu, bool mv) {
    const double x0 = 3.0 + offset, y0 = 2.0 + offset;
    const auto corner = [&](double a, double b) {
        return TexturedVertex{{x0 + a, y0 + b}, 1.0, {mu ? W - a : a, mv ? H - b : b}};
    };
    const TexturedVertex p00 = corner(0, 0), p10 = corner(W, 0), p11 = corner(W, H),
                         p01 = corner(0, H);
    const MapperSettings s{.mapper = {MapperKind::exact}, .precision = Precision::fixed};
    TexelMap map(W + 8, H + 8);
    map_textured_triangle(map, {p00, p10, p11}, s);
    map_textured_triangle(map, {p00, p11, p01}, s);
    return map;
}

/// The bilinear image of the map: every covered pixel sampled at its 16.16 coordinate.
std::vector<Rgba8> bilinear_image(const TexelMap& map, const Texture& texture,
                                  Wrap wrap) {
    const LinearImage image = decode_texture(texture);
    std::vector<Rgba8> out(map.covered.size(), rgba(0, 0, 0, 0));
    for (std::size_t k = 0; k < map.covered.size(); ++k) {
        if (map.covered[k]) {
            const double U = map.u[k] * D, V = map.v[k] * D;
            REQUIRE(U == std::floor(U)); // the map holds whole 16.16 units
            REQUIRE(V == std::floor(V));
            out[k] = encode_linear(sample_bilinear(image, static_cast<std::int32_t>(U),
                                                   static_cast<std::int32_t>(V), wrap));
        }
    }
    return out;
}

} // namespace

TEST_CASE("every 8-bit code survives the round trip through linear light") {
    int previous = -1;
    for (int c = 0; c < 256; ++c) {
        const double l = srgb_to_linear16(static_cast<std::uint8_t>(c));
        CHECK(l == std::floor(l)); // a whole number of units
        CHECK(int(l) > previous);  // strictly increasing: no two codes share a value
        previous = int(l);
        CHECK(linear16_to_srgb(l) == c);
        // Alpha is linear: a * 257 and back.
        const Rgba8 t =
            rgba(static_cast<std::uint8_t>(c), 0, 255, static_cast<std::uint8_t>(c));
        CHECK(encode_linear(decode_texel(t)) == t);
    }
    CHECK(srgb_to_linear16(0) == 0.0);
    CHECK(srgb_to_linear16(255) == linear_full);
    // Half the light is code 188, not 128: averaging codes would darken every blend.
    CHECK(linear16_to_srgb(linear_full / 2) == 188);
}

TEST_CASE("the fast encode gives the same code as the plain one, everywhere") {
    // Every whole linear value, both neighbours (one double away) of every value where
    // the code steps up, and a million fractional values in between.
    for (int l = 0; l <= 65535; ++l) {
        REQUIRE(linear16_to_srgb_fast(l) == linear16_to_srgb(l));
    }
    int steps = 0;
    for (double l = 0.0; l < linear_full; l = std::nextafter(l, linear_full)) {
        // Jump to the next step of the plain code by bisection, then look around it.
        const int code = linear16_to_srgb(l);
        double lo = l, hi = linear_full;
        if (linear16_to_srgb(hi) == code) {
            break;
        }
        while (std::nextafter(lo, hi) < hi) {
            const double mid = lo + (hi - lo) / 2;
            const double probe = mid > lo && mid < hi ? mid : std::nextafter(lo, hi);
            (linear16_to_srgb(probe) > code ? hi : lo) = probe;
        }
        REQUIRE(linear16_to_srgb_fast(lo) == linear16_to_srgb(lo));
        REQUIRE(linear16_to_srgb_fast(hi) == linear16_to_srgb(hi));
        ++steps;
        l = hi;
    }
    CHECK(steps == 255);
    std::uint64_t state = 1;
    for (int n = 0; n < 1000000; ++n) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        const double l = double(state >> 11) * 0x1p-53 * 66000.0 - 200.0;
        REQUIRE(linear16_to_srgb_fast(l) == linear16_to_srgb(l));
    }
    const LinearTexel t{12345.5, 0.25, 65535.0, 40000.0};
    CHECK(encode_linear_fast(t) == encode_linear(t));
}

TEST_CASE("bilinear weights sum to one and a texel centre gives that texel" *
          doctest::description("points: 6; exercise: ch08-bilinear")) {
    // Every fraction in u against a spread of fractions in v: the weights are whole
    // numbers in [0, D^2] that add up to D^2 exactly.
    for (std::int64_t fu = 0; fu < D; ++fu) {
        for (std::int64_t fv : {std::int64_t{0}, std::int64_t{1}, D / 3, D / 2, D - 1}) {
            const auto w = bilinear_weights({0, 0, fu, fv});
            REQUIRE(w[0] + w[1] + w[2] + w[3] == D * D);
            REQUIRE(std::min({w[0], w[1], w[2], w[3]}) >= 0);
        }
    }
    // Taps: u = i + 1/2 is texel i with fraction 0, also for negative i.
    for (int i = -5; i <= 5; ++i) {
        const BilinearTaps t =
            bilinear_taps(to_texel_fixed(i + 0.5), to_texel_fixed(2.5));
        CHECK(t.i == i);
        CHECK(t.j == 2);
        CHECK(t.fu == 0);
        CHECK(t.fv == 0);
    }
    const BilinearTaps quarter =
        bilinear_taps(to_texel_fixed(0.75), to_texel_fixed(0.25));
    CHECK(quarter.i == 0);
    CHECK(quarter.j == -1);
    CHECK(quarter.fu == D / 4);
    CHECK(quarter.fv == 3 * D / 4);
    // At every texel centre of the F the sample is the texel, exactly, in both wraps.
    const Texture f = f_texture(2);
    const LinearImage img = decode_texture(f);
    for (Wrap wrap : {Wrap::repeat, Wrap::clamp}) {
        for (int j = 0; j < f.height(); ++j) {
            for (int i = 0; i < f.width(); ++i) {
                const LinearTexel s =
                    sample_bilinear(img, TexCoord{i + 0.5, j + 0.5}, wrap);
                REQUIRE(s == img.at(i, j));
                REQUIRE(encode_linear(s) == f.texel(i, j));
            }
        }
    }
}

TEST_CASE("between centres the sample is the exact weighted average in linear light" *
          doctest::description("points: 6; exercise: ch08-bilinear")) {
    // A 2 x 2 texture; at (u, v) = (1/2 + a, 1/2 + b) the sample is
    // (1-a)(1-b) t00 + a(1-b) t10 + (1-a)b t01 + ab t11, with a, b multiples of 1/D.
    const Texture t(
        2, 2,
        {rgba(0, 10, 200), rgba(255, 20, 100), rgba(30, 40, 50), rgba(128, 250, 0)});
    const LinearImage img = decode_texture(t);
    for (std::int64_t A : {std::int64_t{0}, std::int64_t{1}, D / 4, D / 2 + 7, D - 1}) {
        for (std::int64_t B : {std::int64_t{0}, D / 8, D / 2, D - 3}) {
            const LinearTexel s =
                sample_bilinear(img, static_cast<std::int32_t>(D / 2 + A),
                                static_cast<std::int32_t>(D / 2 + B), Wrap::clamp);
            for (int c = 0; c < 4; ++c) {
                // Integer arithmetic: D^2 times the sample is a whole number.
                const auto L = [&](int i, int j) {
                    return static_cast<std::int64_t>(img.at(i, j)[c]);
                };
                const std::int64_t expected = (D - A) * (D - B) * L(0, 0) +
                                              A * (D - B) * L(1, 0) +
                                              (D - A) * B * L(0, 1) + A * B * L(1, 1);
                REQUIRE(s[c] * double(D * D) == double(expected));
            }
        }
    }
}

TEST_CASE("at the border repeat blends the far edge and clamp repeats the edge texel" *
          doctest::description("points: 3; exercise: ch08-bilinear")) {
    const Texture t(
        4, 1, {rgba(255, 0, 0), rgba(0, 255, 0), rgba(0, 0, 255), rgba(255, 255, 255)});
    const LinearImage img = decode_texture(t);
    // u = 1/4: a quarter texel left of texel 0's centre, so texel -1 weighs 1/4.
    const LinearTexel repeat = sample_bilinear(img, TexCoord{0.25, 0.5}, Wrap::repeat);
    const LinearTexel clamp = sample_bilinear(img, TexCoord{0.25, 0.5}, Wrap::clamp);
    CHECK(repeat == 0.25 * img.at(3, 0) + 0.75 * img.at(0, 0));
    CHECK(clamp == img.at(0, 0));
    // And on the right: u = 3.75 is 1/4 towards texel 4, which is texel 0 or texel 3.
    CHECK(sample_bilinear(img, TexCoord{3.75, 0.5}, Wrap::repeat) ==
          0.75 * img.at(3, 0) + 0.25 * img.at(0, 0));
    CHECK(sample_bilinear(img, TexCoord{3.75, 0.5}, Wrap::clamp) == img.at(3, 0));
    // Far outside, repeat is periodic: 7 periods to the left give the same sample.
    CHECK(sample_bilinear(img, TexCoord{0.25 - 28.0, 0.5}, Wrap::repeat) == repeat);
}

TEST_CASE("bilinear at 1:1 reproduces the texture exactly") {
    const Texture f = f_texture(2); // 10 x 14
    const TexelMap map = one_to_one(f.width(), f.height(), 0.0, false, false);
    for (Wrap wrap : {Wrap::repeat, Wrap::clamp}) {
        const std::vector<Rgba8> img = bilinear_image(map, f, wrap);
        int covered = 0;
        for (int y = 0; y < map.height; ++y) {
            for (int x = 0; x < map.width; ++x) {
                const std::size_t k = static_cast<std::size_t>(y * map.width + x);
                if (map.covered[k]) {
                    ++covered;
                    REQUIRE(img[k] == f.texel(x - 3, y - 2));
                }
            }
        }
        CHECK(covered == f.width() * f.height());
    }
}

TEST_CASE("a mirrored mapping draws exactly the mirrored texture, with no rounding rule" *
          doctest::description("points: 5; exercise: ch08-bilinear")) {
    // Aligned quads sample texel centres; quads offset by half a pixel sample the ties of
    // chapter 4, where bilinear weighs both texels 1/2 and needs no rule. Either way the
    // texture drawn backwards is, pixel for pixel, the mirrored texture drawn forwards.
    const Texture f = f_texture(2);
    for (double offset : {0.0, 0.5}) {
        for (bool mu : {false, true}) {
            for (bool mv : {false, true}) {
                for (Wrap wrap : {Wrap::repeat, Wrap::clamp}) {
                    CAPTURE(offset);
                    CAPTURE(mu);
                    CAPTURE(mv);
                    const TexelMap back =
                        one_to_one(f.width(), f.height(), offset, mu, mv);
                    const TexelMap fwd =
                        one_to_one(f.width(), f.height(), offset, false, false);
                    CHECK(back.covered == fwd.covered);
                    CHECK(bilinear_image(back, f, wrap) ==
                          bilinear_image(fwd, mirrored(f, mu, mv), wrap));
                }
            }
        }
    }
    // Nearest sampling with rule 1 fails the same comparison on the offset quad.
    const TexelMap back = one_to_one(f.width(), f.height(), 0.5, true, false);
    const TexelMap fwd = one_to_one(f.width(), f.height(), 0.5, false, false);
    const Texture fm = mirrored(f, true, false);
    int differ = 0;
    for (std::size_t k = 0; k < back.covered.size(); ++k) {
        if (back.covered[k]) {
            differ += sample_nearest(f, {back.u[k], back.v[k]}, Wrap::clamp) !=
                      sample_nearest(fm, {fwd.u[k], fwd.v[k]}, Wrap::clamp);
        }
    }
    CHECK(differ > 0);
}
