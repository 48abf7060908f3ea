// mipmap.hpp: a mip chain, each level the box-filtered half of the one above, in
// linear light.
//
// Usage:
//   MipChain chain = build_mip_chain(checkerboard_texture(64, 64, 8));
//   chain.levels.size();              // 7: 64x64, 32x32, ..., 1x1
//   const LinearImage& l2 = chain.levels[2];   // 16 x 16 texels
//
// Level 0 is the texture decoded to linear light (srgb.hpp, units of 1/65535). Level
// k + 1 has size max(1, floor(n / 2)) in each direction where level k has n: a side
// that is odd rounds down, and a side that has reached 1 stays 1. Each texel of level
// k + 1 covers a box of n / n' texels of level k in each direction and is the average
// of level k over that box, texels cut by its edge counted by the part inside (eq.
// 8.5). For even sides the box is exactly 2 x 2 texels and the level is the plain
// average of four; for odd sides it is 3 texels wide, the outer two counted in part.
// The chain ends at 1 x 1. A level-k coordinate is u * width_k / width_0.
// Limits: at most mip_max_side texels per side and mip_max_texels in all, checked
// before anything is allocated (Error naming the size and the limit).
#pragma once

#include "exactpixels/texture/srgb.hpp"
#include "exactpixels/texture/texture.hpp"

#include <vector>

namespace exactpixels {

/// The largest side of a texture a mip chain is built for, in texels.
inline constexpr int mip_max_side = 1 << 14;
/// The most texels of a texture a mip chain is built for (a 2048 x 2048 texture).
inline constexpr long long mip_max_texels = 1LL << 22;

/// The levels of a mip chain, level 0 first (the full texture), the last one 1 x 1.
struct MipChain {
    std::vector<LinearImage> levels; ///< level k is about 2^-k the size of level 0
};

/// The side of the next level: max(1, floor(n / 2)).
constexpr int next_level_side(int n) {
    return n / 2 > 1 ? n / 2 : 1;
}

/// Level k + 1 from level k by the box filter of @eq:box.
LinearImage downsample(const LinearImage& level);

/// The whole chain of a texture. Throws Error when a side exceeds mip_max_side or the
/// texel count exceeds mip_max_texels (a Texture is never empty).
MipChain build_mip_chain(const Texture& texture);

} // namespace exactpixels
