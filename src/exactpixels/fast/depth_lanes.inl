// depth_lanes.inl: chapter 10's depth-tested covered runs on up to eight floats at once,
// as many as the instruction set's registers hold: the one source text of every set's
// depth kernel (depth_lanes_kernel.hpp). src/CMakeLists.txt compiles it once per set
// beside exact_lanes.inl, with the same macros (EXACTPIXELS_LANES doubles per register,
// so 2 * EXACTPIXELS_LANES floats: 4 on SSE2 and NEON, 8 on AVX2, 16 on AVX-512, of which
// `widest` below uses at most 8) and always with -ffp-contract=off.
//
// A run of n pixels takes steps of the widest lanes W with n >= W, halving W down to 4
// for a shorter run and going pixel by pixel below 4. The last step of a run ends at
// the run's end, overlapping the step before: testing a pixel twice draws it as once,
// since a pixel the first test drew holds z (and z < z is false) and one it did not
// holds a depth z is not less than. Each lane computes z as DepthPlane::at does, the row
// part then one multiply and one add, in float: the bits depth_run writes (tested per
// variant). The lanes are GCC's (and Clang's) vector types; nothing here calls an
// inline function of another header (exact_lanes_kernel.hpp says why).
#include "exactpixels/fast/depth_lanes_kernel.hpp"

#include <cstdint>
#include <cstring>

namespace exactpixels::EXACTPIXELS_LANES_SET {

namespace {

/// Floats per step at most: 4 on SSE2 and NEON, 8 on AVX2 and AVX-512. (AVX-512's 16,
/// a compare into a mask register and a masked store of the colours, took about half as
/// long again as 8 to draw the 1000-px depth-tested set on the AMD EPYC of chapter 10's
/// runs: a quick interleaved timing on a busy machine, a hint only.)
constexpr int widest = 2 * EXACTPIXELS_LANES > 8 ? 8 : 2 * EXACTPIXELS_LANES;
static_assert(sizeof(Rgba8) == sizeof(std::uint32_t)); // a colour is one 32-bit lane

/// W floats and W 32-bit words in one vector (an alias template would drop the
/// attribute in GCC 12; a member typedef keeps it).
template <int W> struct Vectors {
    typedef float Floats __attribute__((vector_size(W * sizeof(float))));
    typedef std::int32_t Words __attribute__((vector_size(W * sizeof(std::int32_t))));
};
template <int W> using Floats = typename Vectors<W>::Floats;
template <int W> using Words = typename Vectors<W>::Words;

/// W pixels from `first` tested at once: z = row + columns dzdx per lane.
template <int W>
void test_lanes(Floats<W> row, Floats<W> dzdx, Floats<W> columns, Words<W> colour,
                float* depth, Rgba8* pixels) {
    const Floats<W> z = row + columns * dzdx; // no contraction: at()'s two roundings
    Floats<W> stored;
    std::memcpy(&stored, depth, sizeof stored);
    const Words<W> nearer = z < stored; // all ones where nearer; NaN: never
    const Words<W> depths = (nearer & reinterpret_cast<Words<W>>(z)) |
                            (~nearer & reinterpret_cast<Words<W>>(stored));
    std::memcpy(depth, &depths, sizeof depths);
    Words<W> old;
    std::memcpy(&old, static_cast<const void*>(pixels), sizeof old);
    const Words<W> colours = (nearer & colour) | (~nearer & old);
    std::memcpy(static_cast<void*>(pixels), &colours, sizeof colours);
}

/// depth_run of pixels x_begin .. x_end - 1, row part `row`, W at a time.
template <int W>
void depth_lanes(float row, float dzdx, std::int32_t word, int x_begin, int x_end,
                 float* depth_row, Rgba8* colour_row) {
    if constexpr (W > 4) {
        if (x_end - x_begin < W) {
            depth_lanes<W / 2>(row, dzdx, word, x_begin, x_end, depth_row, colour_row);
            return;
        }
    } else if (x_end - x_begin < 4) {
        for (int x = x_begin; x < x_end; ++x) {
            const float z = row + static_cast<float>(x) * dzdx;
            if (z < depth_row[x]) {
                depth_row[x] = z;
                std::memcpy(static_cast<void*>(colour_row + x), &word, sizeof word);
            }
        }
        return;
    }
    Floats<W> iota{};
    for (int l = 0; l < W; ++l) {
        iota[l] = static_cast<float>(l);
    }
    const Floats<W> rows = Floats<W>{} + row, steps = Floats<W>{} + dzdx;
    const Words<W> colour = Words<W>{} + word;
    // float(x + l): exact, |x| < 2^24; adding W keeps it exact.
    Floats<W> columns = iota + static_cast<float>(x_begin);
    int x = x_begin;
    for (; x + W <= x_end; x += W, columns += static_cast<float>(W)) {
        test_lanes<W>(rows, steps, columns, colour, depth_row + x, colour_row + x);
    }
    if (x < x_end) { // the last W pixels, overlapping those done
        const int last = x_end - W;
        test_lanes<W>(rows, steps, iota + static_cast<float>(last), colour,
                      depth_row + last, colour_row + last);
    }
}

std::int32_t word_of(Rgba8 colour) {
    std::int32_t word = 0;
    std::memcpy(&word, &colour, sizeof word);
    return word;
}

} // namespace

void depth_run(const RunPlane& plane, int y, int x_begin, int x_end, float* depth_row,
               Rgba8* colour_row) {
    const float row = plane.z0 + static_cast<float>(y) * plane.dzdy; // as at(x, y)
    depth_lanes<widest>(row, plane.dzdx, word_of(plane.colour), x_begin, x_end, depth_row,
                        colour_row);
}

} // namespace exactpixels::EXACTPIXELS_LANES_SET
