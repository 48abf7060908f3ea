// Chapter 8 tests, part 2: the mip chain (box filter in linear light, exact for
// power-of-two sizes, bounded otherwise) and its limits.
#include "exactpixels/base/error.hpp"
#include "exactpixels/texture/mipmap.hpp"
#include "exactpixels/texture/texture.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

using namespace exactpixels;

namespace {

/// A width x height texture of fixed pseudo-random texels (a 64-bit LCG, same
/// everywhere).
Texture noise_texture(int width, int height, std::uint64_t seed) {
    std::vector<Rgba8> texels;
    for (int k = 0; k < width * height; ++k) {
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        const auto byte = [&](int shift) {
            return static_cast<std::uint8_t>(seed >> shift);
        };
        texels.push_back(rgba(byte(56), byte(48), byte(40), byte(32)));
    }
    return Texture(width, height, texels);
}

} // namespace

TEST_CASE(
    "each mip level is exactly the box average of the level above, power-of-two sizes") {
    for (auto [w, h] : {std::array{16, 16}, std::array{32, 8}, std::array{1, 64}}) {
        const Texture t = noise_texture(w, h, 7);
        const MipChain chain = build_mip_chain(t);
        const int levels = static_cast<int>(std::log2(std::max(w, h))) + 1;
        REQUIRE(chain.levels.size() == static_cast<std::size_t>(levels));
        const LinearImage& base = chain.levels[0];
        for (std::size_t k = 1; k < chain.levels.size(); ++k) {
            const LinearImage& above = chain.levels[k - 1];
            const LinearImage& level = chain.levels[k];
            CHECK(level.width == std::max(1, above.width / 2));
            CHECK(level.height == std::max(1, above.height / 2));
            // Integer arithmetic: a texel of level k times its block's texel count is the
            // sum of the level-0 texels of its block, a whole number of linear units.
            const int bw = base.width / level.width, bh = base.height / level.height;
            for (int j = 0; j < level.height; ++j) {
                for (int i = 0; i < level.width; ++i) {
                    for (int c = 0; c < 4; ++c) {
                        std::int64_t sum = 0;
                        for (int b = 0; b < bh; ++b) {
                            for (int a = 0; a < bw; ++a) {
                                sum += static_cast<std::int64_t>(
                                    base.at(i * bw + a, j * bh + b)[c]);
                            }
                        }
                        REQUIRE(level.at(i, j)[c] * double(bw * bh) == double(sum));
                    }
                    // And the plain average of its (up to) four texels of the level
                    // above.
                    LinearTexel four{0.0};
                    const int sw = above.width / level.width,
                              sh = above.height / level.height;
                    for (int b = 0; b < sh; ++b) {
                        for (int a = 0; a < sw; ++a) {
                            four += above.at(i * sw + a, j * sh + b);
                        }
                    }
                    REQUIRE(level.at(i, j) == four / double(sw * sh));
                }
            }
        }
        CHECK(chain.levels.back().width == 1);
        CHECK(chain.levels.back().height == 1);
    }
}

TEST_CASE("odd sizes: each level keeps the mean and stays within its box") {
    // Odd sides round down (n' = floor(n/2)); texel i of the next level averages level k
    // over [i n/n', (i+1) n/n'), the cut texels weighted by the part inside. The box
    // weights of a row add up to the whole row, so the mean of every level is the mean
    // of level 0, up to rounding: the stated bound is 1e-12 of full light. Each texel
    // lies between the smallest and largest texel its box touches.
    for (const std::array<int, 2> size :
         {std::array{13, 7}, std::array{5, 5}, std::array{12, 1}, std::array{3, 17}}) {
        const int w = size[0], h = size[1]; // named copies: CAPTURE takes them (Clang 14)
        CAPTURE(w);
        CAPTURE(h);
        const MipChain chain = build_mip_chain(noise_texture(w, h, 11));
        const auto mean = [](const LinearImage& l) {
            LinearTexel s{0.0};
            for (const LinearTexel& t : l.texels) {
                s += t;
            }
            return s / double(l.texels.size());
        };
        const LinearTexel m0 = mean(chain.levels[0]);
        for (std::size_t k = 1; k < chain.levels.size(); ++k) {
            const LinearImage& above = chain.levels[k - 1];
            const LinearImage& level = chain.levels[k];
            CHECK(level.width == std::max(1, above.width / 2));
            CHECK(level.height == std::max(1, above.height / 2));
            const LinearTexel mk = mean(level);
            for (int c = 0; c < 4; ++c) {
                CHECK(std::abs(mk[c] - m0[c]) <= 1e-12 * linear_full);
            }
            for (int j = 0; j < level.height; ++j) {
                for (int i = 0; i < level.width; ++i) {
                    // The box, in texels of the level above: [i w/w', (i+1) w/w').
                    const int a0 = i * above.width / level.width;
                    const int a1 =
                        ((i + 1) * above.width + level.width - 1) / level.width;
                    const int b0 = j * above.height / level.height;
                    const int b1 =
                        ((j + 1) * above.height + level.height - 1) / level.height;
                    for (int c = 0; c < 4; ++c) {
                        double lo = linear_full, hi = 0.0;
                        for (int b = b0; b < b1; ++b) {
                            for (int a = a0; a < a1; ++a) {
                                lo = std::min(lo, above.at(a, b)[c]);
                                hi = std::max(hi, above.at(a, b)[c]);
                            }
                        }
                        REQUIRE(level.at(i, j)[c] >= lo - 1e-9);
                        REQUIRE(level.at(i, j)[c] <= hi + 1e-9);
                    }
                }
            }
        }
    }
    // The 3-texel box of an odd row: 7 -> 3 texels, weights 1, 1, 1/3 ... in thirds.
    const Texture row(7, 1,
                      {rgba(255, 0, 0), rgba(0, 0, 0), rgba(0, 0, 0), rgba(255, 0, 0),
                       rgba(0, 0, 0), rgba(0, 0, 0), rgba(255, 0, 0)});
    const LinearImage next = build_mip_chain(row).levels[1];
    REQUIRE(next.width == 3);
    // Texel 0 covers [0, 7/3): texel 0 whole (3/7 of the box), texel 1 whole, texel 2 a
    // third.
    CHECK(std::abs(next.at(0, 0)[0] - linear_full * 3.0 / 7.0) < 1e-9);
    // Texel 1 covers [7/3, 14/3): two thirds of texel 2, texel 3 whole, two thirds of 4.
    CHECK(std::abs(next.at(1, 0)[0] - linear_full * 3.0 / 7.0) < 1e-9);
}

TEST_CASE("the box filter averages light, not codes") {
    // Black and white texels average to half the light: code 188, not 128.
    const Texture t(
        2, 2, {rgba(0, 0, 0), rgba(255, 255, 255), rgba(255, 255, 255), rgba(0, 0, 0)});
    const MipChain chain = build_mip_chain(t);
    CHECK(encode_linear(chain.levels[1].at(0, 0)) == rgba(188, 188, 188));
}

TEST_CASE("a texture too large for a mip chain is an Error naming its size") {
    const Texture wide(mip_max_side + 1, 1, std::vector<Rgba8>(mip_max_side + 1));
    CHECK_THROWS_WITH_AS(build_mip_chain(wide), doctest::Contains("16385x1"), Error);
    const int side = 2049; // 2049^2 > mip_max_texels = 2048^2
    const Texture big(side, side, std::vector<Rgba8>(std::size_t(side) * side));
    CHECK_THROWS_WITH_AS(build_mip_chain(big), doctest::Contains("2049x2049"), Error);
    // Zero size never reaches the chain: a texture cannot be empty.
    CHECK_THROWS_AS(Texture(0, 4, {}), Error);
    CHECK_NOTHROW(build_mip_chain(Texture(2048, 2048, std::vector<Rgba8>(2048 * 2048))));
}
