// block_masks.hpp: a triangle's coverage handed out as 8 x 8 blocks with a 64-bit mask,
// the mask computed eight pixels at a time (sign_lanes.hpp).
//
// Usage:
//   const EdgeSetup<FixedEdge> s = setup_edges(v);                 // chapter 2
//   traverse_block_masks(s, pixel_bounds(v, viewport), [&](BlockMask m) {
//       fill_block_mask(pixels, width, m, colour);                 // wide stores
//   });
//
// Blocks are the 8 x 8 squares aligned to multiples of 8 px (as in chapter 2's
// traverse_blocks). Bit 8 j + i of a mask is pixel (x + i, y + j); a mask holds exactly
// the pixels of the rectangle r whose centres the triangle covers (top-left rule), the
// same pixels as traverse_pixels, bit for bit (tested). Blocks with no pixel are not
// handed out; a mask of all ones (BlockMask::full) is a whole block inside.
#pragma once

#include "exactpixels/fast/sign_lanes.hpp"
#include "exactpixels/raster/edge_function.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>

namespace exactpixels {

/// The covered pixels of one 8 x 8 block: bit 8 j + i is pixel (x + i, y + j).
struct BlockMask {
    int x = 0;              ///< the block's left column (a multiple of 8)
    int y = 0;              ///< the block's top row (a multiple of 8)
    std::uint64_t bits = 0; ///< the covered pixels
    /// A mask with every pixel of the block covered.
    static constexpr std::uint64_t full = ~std::uint64_t{0};
    /// The 8 bits of row j (bit i is column x + i).
    std::uint8_t row(int j) const { return static_cast<std::uint8_t>(bits >> (8 * j)); }
};

/// The bits of the block at (bx, by) that lie inside the rectangle r.
inline std::uint64_t rect_bits(PixelRect r, int bx, int by) {
    const int i0 = std::max(r.x_begin - bx, 0), i1 = std::min(r.x_end - bx, 8);
    const int j0 = std::max(r.y_begin - by, 0), j1 = std::min(r.y_end - by, 8);
    if (i0 >= i1 || j0 >= j1) {
        return 0;
    }
    const std::uint64_t columns = ((std::uint64_t{1} << (i1 - i0)) - 1) << i0;
    std::uint64_t bits = 0;
    for (int j = j0; j < j1; ++j) {
        bits |= columns << (8 * j);
    }
    return bits;
}

//> block-mask
/// The coverage mask of the 8 x 8 block whose top-left pixel has edge values w (one per
/// edge): row by row, the three edges' values for 8 pixels at once, ORed, their signs
/// read as 8 bits. ramp[k] holds i * step_x of edge k, the row step is step_y.
template <class Lanes>
std::uint64_t block_mask(const EdgeSetup<FixedEdge>& s,
                         const std::array<std::int64_t, 3>& w,
                         const std::array<Lanes, 3>& ramp) {
    std::array<Lanes, 3> row{Lanes::broadcast(w[0]) + ramp[0],
                             Lanes::broadcast(w[1]) + ramp[1],
                             Lanes::broadcast(w[2]) + ramp[2]};
    std::array<Lanes, 3> down{Lanes::broadcast(s.edge[0].step_y()),
                              Lanes::broadcast(s.edge[1].step_y()),
                              Lanes::broadcast(s.edge[2].step_y())};
    std::uint64_t bits = 0;
    for (int j = 0; j < 8; ++j) {
        const std::uint64_t inside = (row[0] | row[1] | row[2]).nonnegative_bits();
        bits |= inside << (8 * j);
        for (int k = 0; k < 3; ++k) {
            row[k] = row[k] + down[k];
        }
    }
    return bits;
}
//< block-mask

//> traverse-block-masks
/// Hands emit(BlockMask) every 8 x 8 block meeting r that holds a covered pixel, with
/// exactly the covered pixels of r in its mask. Each block is first tested at its
/// extreme corners (chapter 2, @eq:edge-block): outside, skipped; inside, all of it;
/// otherwise its mask is computed eight pixels at a time. Lanes: lanes::Portable or
/// lanes::Sse2.
template <class Lanes = Lanes8, class MaskFn>
void traverse_block_masks(const EdgeSetup<FixedEdge>& s, PixelRect r, MaskFn&& emit) {
    if (r.empty()) {
        return;
    }
    std::array<std::int64_t, 3> largest, smallest, block_step;
    std::array<Lanes, 3> ramp;
    for (std::size_t k = 0; k < 3; ++k) {
        const std::int64_t across = 7 * s.edge[k].step_x(), down = 7 * s.edge[k].step_y();
        largest[k] = std::max<std::int64_t>(across, 0) + std::max<std::int64_t>(down, 0);
        smallest[k] = std::min<std::int64_t>(across, 0) + std::min<std::int64_t>(down, 0);
        block_step[k] = 8 * s.edge[k].step_x();
        ramp[k] = Lanes::ramp(s.edge[k].step_x());
    }
    const int first_x = r.x_begin - r.x_begin % 8; // r is never negative
    for (int by = r.y_begin - r.y_begin % 8; by < r.y_end; by += 8) {
        std::array<std::int64_t, 3> w{s.edge[0].at(first_x, by),
                                      s.edge[1].at(first_x, by),
                                      s.edge[2].at(first_x, by)};
        for (int bx = first_x; bx < r.x_end; bx += 8) {
            bool outside = false, inside = true;
            for (std::size_t k = 0; k < 3; ++k) {
                outside = outside || w[k] + largest[k] < 0;
                inside = inside && w[k] + smallest[k] >= 0;
            }
            if (!outside) {
                const std::uint64_t clip = rect_bits(r, bx, by);
                const std::uint64_t bits =
                    clip & (inside ? BlockMask::full : block_mask(s, w, ramp));
                if (bits != 0) {
                    emit(BlockMask{bx, by, bits});
                }
            }
            for (std::size_t k = 0; k < 3; ++k) {
                w[k] += block_step[k];
            }
        }
    }
}
//< traverse-block-masks

/// Calls emit(x, y) for every pixel of the mask m, row by row.
template <class EmitFn> void for_each_pixel(BlockMask m, EmitFn&& emit) {
    for (std::uint64_t bits = m.bits; bits != 0; bits &= bits - 1) {
        const int bit = std::countr_zero(bits);
        emit(m.x + bit % 8, m.y + bit / 8);
    }
}

//> fill-block-mask
/// Writes `value` into the pixels of the mask m in a row-major image of `stride` pixels
/// per row: a row of the mask that is all ones is 8 stores in a row (the compiler makes
/// them two or four vector stores), any other row pixel by pixel.
template <class Pixel>
void fill_block_mask(Pixel* pixels, std::ptrdiff_t stride, BlockMask m, Pixel value) {
    for (int j = 0; j < 8; ++j) {
        const std::uint8_t bits = m.row(j);
        if (bits == 0) {
            continue; // also every row below the image: never addressed
        }
        Pixel* row = pixels + (m.y + j) * stride + m.x;
        if (bits == 0xff) {
            for (int i = 0; i < 8; ++i) {
                row[i] = value;
            }
        } else {
            for (unsigned b = bits; b != 0; b &= b - 1) {
                row[std::countr_zero(b)] = value;
            }
        }
    }
}
//< fill-block-mask

} // namespace exactpixels
