#include "exactpixels/texture/mipmap.hpp"

#include "exactpixels/base/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <numeric>

namespace exactpixels {

namespace {

/// One tap of the box filter along one direction: a texel of the level above and the
/// length of its overlap with the box, in units of g / n' texel of the level above,
/// g = gcd(n, n'), so that the overlaps of one box add up to n / g (2 when n is even).
struct BoxTap {
    int index;
    int overlap;
};

//> box-taps
/// The texels of a level of side n under texel i of the next level (side n'), with
/// their overlaps. Measured in units of 1/n' texel of level k, texel i of level k + 1
/// covers [i n, (i + 1) n) and texel a of level k covers [a n', (a + 1) n'); the overlaps
/// are whole numbers and add up to n (@eq:box); dividing them by g = gcd(n, n') keeps
// them whole and makes the even case the plain average of two.
std::vector<BoxTap> box_taps(int i, int n, int n_next) {
    const long long g = std::gcd(n, n_next);
    std::vector<BoxTap> taps;
    const long long lo = static_cast<long long>(i) * n, hi = lo + n;
    for (long long a = lo / n_next; a * n_next < hi; ++a) {
        const long long overlap =
            std::min(hi, (a + 1) * n_next) - std::max(lo, a * n_next);
        taps.push_back({static_cast<int>(a), static_cast<int>(overlap / g)});
    }
    return taps;
}
//< box-taps

} // namespace

//> downsample
LinearImage downsample(const LinearImage& level) {
    const int w = next_level_side(level.width), h = next_level_side(level.height);
    LinearImage next{w, h, {}};
    next.texels.reserve(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    // The box's total weight: (n_x / g_x) (n_y / g_y), 4 when both sides are even.
    const double box_area = double(level.width / std::gcd(level.width, w)) *
                            double(level.height / std::gcd(level.height, h));
    for (int j = 0; j < h; ++j) {
        const std::vector<BoxTap> rows = box_taps(j, level.height, h);
        for (int i = 0; i < w; ++i) {
            LinearTexel sum{0.0};
            for (const BoxTap& col : box_taps(i, level.width, w)) {
                for (const BoxTap& row : rows) {
                    sum += double(col.overlap * row.overlap) *
                           level.at(col.index, row.index);
                }
            }
            next.texels.push_back(sum / box_area);
        }
    }
    return next;
}
//< downsample

MipChain build_mip_chain(const Texture& texture) {
    const long long texels = static_cast<long long>(texture.width()) * texture.height();
    if (texture.width() > mip_max_side || texture.height() > mip_max_side ||
        texels > mip_max_texels) {
        throw Error(
            fmt::format("mip chain: texture of {}x{} texels is too large (at most "
                        "{} per side and {} in all)",
                        texture.width(), texture.height(), mip_max_side, mip_max_texels));
    }
    MipChain chain;
    chain.levels.push_back(decode_texture(texture));
    while (chain.levels.back().width > 1 || chain.levels.back().height > 1) {
        chain.levels.push_back(downsample(chain.levels.back()));
    }
    return chain;
}

} // namespace exactpixels
