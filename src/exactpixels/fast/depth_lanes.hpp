// depth_lanes.hpp: the depth test of a run of pixels, four floats at a time, with the
// same bits as testing them one by one.
//
// Usage:
//   float* depth_row = depth + y * width;  Rgba8* colour_row = colour + y * width;
//   depth_run(plane, red, y, x_begin, x_end, depth_row, colour_row);   // a covered run
//   depth_mask_row(plane, red, y, x, bits, width, depth_row, colour_row); // 8 px, mask
//
// A pixel (x, y) is drawn when z = plane.at(x, y) is less than the stored depth (NaN
// never is); then z and the colour are written, as chapter 10's plot does. Depths are
// IEEE single floats; x and y are pixel columns and rows, |x|, |y| < 2^24 (far beyond
// any framebuffer), so float(x) is exact. The lanes compute z as plot does, in the same
// order and the same float operations: the row part z0 + float(y) dzdy once, then
// + float(x) dzdx per lane (no fused multiply-add: the build targets x86-64 without FMA
// and the lanes use separate multiply and add), so every depth written is the bit
// pattern plot writes. With SSE2 (every x86-64) four pixels are one __m128 of depths and
// one __m128i of colours, the test one cmpltps, the write an and/andnot/or blend of new
// and stored values; elsewhere, or with EXACTPIXELS_PORTABLE_LANES defined, a plain loop.
// Both are always compiled as depth_lanes::Portable and depth_lanes::Sse2, and tested
// against plot pixel by pixel, bit for bit.
#pragma once

#include "exactpixels/base/framebuffer.hpp"
#include "exactpixels/fast/tiled_rasterizer.hpp"

#include <bit>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace exactpixels {

/// The two implementations of four depth-tested pixels (DepthLanes4 picks one).
namespace depth_lanes {

//> depth-lanes-portable
/// Four pixels one after another: the portable form, and the reference.
struct Portable {
    float row;  ///< the row's part of z: z0 + float(y) dzdy, rounded as in at(x, y)
    float dzdx; ///< change of z per pixel to the right
    int x;      ///< the column of the first of the four pixels
    /// The four pixels from column x of a row (a constructor, so that Lanes(row, dzdx, x)
    /// compiles where parenthesized aggregate initialization does not: Clang before 16).
    Portable(float row_z, float dz_dx, int first) : row(row_z), dzdx(dz_dx), x(first) {}
    /// The next four pixels to the right.
    void next() { x += 4; }
    /// Tests the pixels x + i (i = 0 .. 3) whose bit i of `keep` is set: z = row +
    /// float(x + i) dzdx; where z < depth[i], writes z and `c`. depth and colour point
    /// at pixel x.
    void test(unsigned keep, float* depth, Rgba8* colour, Rgba8 c) const {
        for (int i = 0; i < 4; ++i) {
            if ((keep >> i & 1u) == 0) {
                continue;
            }
            const float z = row + static_cast<float>(x + i) * dzdx;
            if (z < depth[i]) {
                depth[i] = z;
                colour[i] = c;
            }
        }
    }
};
//< depth-lanes-portable

#if defined(__SSE2__)
//> depth-lanes-sse2
/// Four pixels in one SSE2 register each for depths and colours.
struct Sse2 {
    __m128 row;     ///< the row's part of z in every lane
    __m128 dzdx;    ///< dzdx in every lane
    __m128 columns; ///< float(x + i) in lane i: exact, |x| < 2^24
    /// The four pixels from column x of a row (Portable's members, in lanes).
    Sse2(float row_z, float dz_dx, int x)
        : row(_mm_set1_ps(row_z)), dzdx(_mm_set1_ps(dz_dx)),
          columns(_mm_cvtepi32_ps(
              _mm_add_epi32(_mm_set1_epi32(x), _mm_setr_epi32(0, 1, 2, 3)))) {}
    /// The next four pixels: float(x + i) + 4 is float(x + i + 4) exactly.
    void next() { columns = _mm_add_ps(columns, _mm_set1_ps(4.0f)); }
    /// Portable::test, four lanes at once: the same float operations per lane, the
    /// compare as a mask, new and stored values blended by it.
    void test(unsigned keep, float* depth, Rgba8* colour, Rgba8 c) const {
        const __m128 z = _mm_add_ps(row, _mm_mul_ps(columns, dzdx)); // each lane: at()
        const __m128 stored = _mm_loadu_ps(depth);
        __m128 nearer = _mm_cmplt_ps(z, stored); // all ones where z < stored; NaN: 0
        if (keep != 0xfu) {
            const __m128i bit = _mm_setr_epi32(1, 2, 4, 8);
            const __m128i kept =
                _mm_and_si128(_mm_set1_epi32(static_cast<int>(keep)), bit);
            nearer = _mm_and_ps(nearer, _mm_castsi128_ps(_mm_cmpeq_epi32(kept, bit)));
        }
        if (_mm_movemask_ps(nearer) == 0) {
            return; // nothing nearer: no store at all
        }
        _mm_storeu_ps(depth,
                      _mm_or_ps(_mm_and_ps(nearer, z), _mm_andnot_ps(nearer, stored)));
        const __m128i pick = _mm_castps_si128(nearer);
        auto* pixels = reinterpret_cast<__m128i*>(colour); // __m128i may alias anything
        const __m128i old = _mm_loadu_si128(pixels);
        const __m128i fresh = _mm_set1_epi32(std::bit_cast<std::int32_t>(c));
        _mm_storeu_si128(pixels, _mm_or_si128(_mm_and_si128(pick, fresh),
                                              _mm_andnot_si128(pick, old)));
    }
};
//< depth-lanes-sse2
#endif

} // namespace depth_lanes

static_assert(sizeof(Rgba8) == 4, "a colour is one 32-bit lane");

#if defined(__SSE2__) && !defined(EXACTPIXELS_PORTABLE_LANES)
/// The four depth lanes the fast rasterizers use: SSE2 where the compiler targets it.
using DepthLanes4 = depth_lanes::Sse2;
#else
/// The four depth lanes the fast rasterizers use: the portable loop.
using DepthLanes4 = depth_lanes::Portable;
#endif

//> depth-run
/// Depth-tests and draws pixels x_begin .. x_end - 1 of row y with `plane` and
/// `colour` (depth_row and colour_row point at column 0 of row y): four at a time, and
/// the last one to three as the four that end the run with only those pixels kept (no
/// pixel outside the run is read or written); a run shorter than four pixel by pixel.
/// Every z is the bits of plane.at(x, y).
template <class Lanes = DepthLanes4>
void depth_run(DepthPlane plane, Rgba8 colour, int y, int x_begin, int x_end,
               float* depth_row, Rgba8* colour_row) {
    const float row = plane.z0 + static_cast<float>(y) * plane.dzdy; // as at(x, y)
    if (x_end - x_begin < 4) {
        const unsigned all = (1u << (x_end - x_begin)) - 1;
        depth_lanes::Portable{row, plane.dzdx, x_begin}.test(
            all, depth_row + x_begin, colour_row + x_begin, colour);
        return;
    }
    Lanes four{row, plane.dzdx, x_begin};
    int x = x_begin;
    for (; x + 4 <= x_end; x += 4, four.next()) {
        four.test(0xfu, depth_row + x, colour_row + x, colour);
    }
    if (x < x_end) {
        const int last = x_end - 4;                        // overlaps pixels done,
        const unsigned rest = (0xfu << (x - last)) & 0xfu; // which it keeps out
        Lanes{row, plane.dzdx, last}
            .test(rest, depth_row + last, colour_row + last, colour);
    }
}
//< depth-run

/// Depth-tests and draws the pixels x + i of row y whose bit i of `bits` is set (a
/// row of an 8 x 8 mask): two steps of four, each only when some bit is set; a step
/// that would reach past column width - 1 goes pixel by pixel (no load beyond the row).
template <class Lanes = DepthLanes4>
void depth_mask_row(DepthPlane plane, Rgba8 colour, int y, int x, std::uint8_t bits,
                    int width, float* depth_row, Rgba8* colour_row) {
    const float row = plane.z0 + static_cast<float>(y) * plane.dzdy; // as at(x, y)
    Lanes four{row, plane.dzdx, x};
    for (int half = 0; half < 8; half += 4, four.next()) {
        const unsigned keep = (static_cast<unsigned>(bits) >> half) & 0xfu;
        const int left = x + half;
        if (keep == 0) {
            continue;
        }
        float* d = depth_row + left;
        Rgba8* c = colour_row + left;
        if (left + 4 <= width) {
            four.test(keep, d, c, colour);
        } else {
            depth_lanes::Portable{row, plane.dzdx, left}.test(keep, d, c, colour);
        }
    }
}

} // namespace exactpixels
