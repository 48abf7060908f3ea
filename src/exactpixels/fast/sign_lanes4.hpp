// sign_lanes4.hpp: four 32-bit edge values side by side, for triangles small enough
// that their edge values fit in 32 bits (tiny_triangle.hpp says when).
//
// Usage:
//   Lanes4 w = Lanes4::broadcast(w_row) + Lanes4::ramp(step_x); // columns x .. x + 3
//   unsigned inside = (w0 | w1 | w2).nonnegative_bits();        // bit i: column x + i
//
// The same idea as sign_lanes.hpp's Lanes8 (add, OR, read the sign bits), with int32
// lanes: SSE2 holds four of them in one register, so one add covers four pixels of an
// edge, where int64 lanes need two registers. The caller keeps every value within int32
// (the lanes wrap like the hardware). With SSE2 the lanes are one __m128i and the signs
// come out with movmskps; elsewhere, or with EXACTPIXELS_PORTABLE_LANES defined, a plain
// array. Both are always compiled (lanes4::Portable, lanes4::Sse2) and tested against
// each other.
#pragma once

#include <array>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace exactpixels {

/// The two implementations of the four int32 lanes (Lanes4 picks one).
namespace lanes4 {

/// Four int32 values in a plain array: the portable form, and the reference.
struct Portable {
    std::array<std::int32_t, 4> v; ///< lane i is column x + i
    /// Every lane set to `value`.
    static Portable broadcast(std::int32_t value) {
        return {{value, value, value, value}};
    }
    /// Lane i set to i * step (i = 0 .. 3); the caller keeps 3 step within int32.
    static Portable ramp(std::int32_t step) { return {{0, step, 2 * step, 3 * step}}; }
    /// Lane-wise sum (wraps like the hardware: callers stay within int32).
    friend Portable operator+(Portable a, const Portable& b) {
        for (std::size_t i = 0; i < 4; ++i) {
            a.v[i] = static_cast<std::int32_t>(static_cast<std::uint32_t>(a.v[i]) +
                                               static_cast<std::uint32_t>(b.v[i]));
        }
        return a;
    }
    /// Lane-wise bitwise OR: negative exactly when one of the two is.
    friend Portable operator|(Portable a, const Portable& b) {
        for (std::size_t i = 0; i < 4; ++i) {
            a.v[i] |= b.v[i];
        }
        return a;
    }
    /// Bit i set when lane i is >= 0.
    unsigned nonnegative_bits() const {
        unsigned bits = 0;
        for (std::size_t i = 0; i < 4; ++i) {
            bits |= unsigned{v[i] >= 0} << i;
        }
        return bits;
    }
};

#if defined(__SSE2__)
/// Four int32 values in one SSE2 register.
struct Sse2 {
    __m128i r; ///< lane i in bits 32 i .. 32 i + 31
    /// Every lane set to `value`.
    static Sse2 broadcast(std::int32_t value) { return {_mm_set1_epi32(value)}; }
    /// Lane i set to i * step (i = 0 .. 3): step in lanes 1 and 3 plus 2 step in lanes 2
    /// and 3, by masks (SSE2 has no four-lane 32-bit multiply).
    static Sse2 ramp(std::int32_t step) {
        const __m128i one = _mm_set1_epi32(step), two = _mm_add_epi32(one, one);
        const __m128i odd = _mm_set_epi32(-1, 0, -1, 0),
                      high = _mm_set_epi32(-1, -1, 0, 0);
        return {_mm_add_epi32(_mm_and_si128(one, odd), _mm_and_si128(two, high))};
    }
    /// Lane-wise sum (paddd).
    friend Sse2 operator+(Sse2 a, const Sse2& b) { return {_mm_add_epi32(a.r, b.r)}; }
    /// Lane-wise bitwise OR (por).
    friend Sse2 operator|(Sse2 a, const Sse2& b) { return {_mm_or_si128(a.r, b.r)}; }
    /// Bit i set when lane i is >= 0: movmskps reads the top bit of each 32-bit lane.
    unsigned nonnegative_bits() const {
        return ~static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(r))) & 0xfu;
    }
};
#endif

} // namespace lanes4

#if defined(__SSE2__) && !defined(EXACTPIXELS_PORTABLE_LANES)
/// The four int32 lanes the tiny-triangle path uses: SSE2 where the compiler targets it.
using Lanes4 = lanes4::Sse2;
#else
/// The four int32 lanes the tiny-triangle path uses: the portable array.
using Lanes4 = lanes4::Portable;
#endif

} // namespace exactpixels
