// sign_lanes.hpp: eight 64-bit edge values side by side, the only SIMD the book uses.
//
// Usage:
//   Lanes8 w = Lanes8::broadcast(e.at(x, y)) + Lanes8::ramp(e.step_x()); // x .. x + 7
//   std::uint8_t inside = (w0 | w1 | w2).nonnegative_bits(); // bit i: x + i covered
//
// Values are the exact fixed-point edge values of chapter 2 (1/65536 px^2, int64); the
// lanes only add and OR them, so every result is the integer the scalar loop computes.
// "Covered" is w0 >= 0 && w1 >= 0 && w2 >= 0, which is "the sign bit of w0 | w1 | w2 is
// clear": one OR per edge and one sign extraction per lane, no 64-bit compare (SSE2 has
// none). With SSE2 (every x86-64) the lanes are four __m128i and the signs come out with
// movmskpd; elsewhere, or with EXACTPIXELS_PORTABLE_LANES defined, a plain array. Both
// are always compiled as lanes::Portable and lanes::Sse2, and tested against each other.
#pragma once

#include <array>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace exactpixels {

/// The two implementations of the eight lanes (Lanes8 picks one).
namespace lanes {

/// Eight int64 values in a plain array: the portable form, and the reference.
struct Portable {
    std::array<std::int64_t, 8> v; ///< lane i is pixel x + i of a block row
    /// Every lane set to `value`.
    static Portable broadcast(std::int64_t value) {
        Portable p;
        p.v.fill(value);
        return p;
    }
    /// Lane i set to i * step (i = 0 .. 7).
    static Portable ramp(std::int64_t step) {
        Portable p;
        for (int i = 0; i < 8; ++i) {
            p.v[static_cast<std::size_t>(i)] = i * step;
        }
        return p;
    }
    /// Lane-wise sum (wraps like the hardware: callers stay within int64,
    /// @eq:edge-range).
    friend Portable operator+(Portable a, const Portable& b) {
        for (std::size_t i = 0; i < 8; ++i) {
            a.v[i] = static_cast<std::int64_t>(static_cast<std::uint64_t>(a.v[i]) +
                                               static_cast<std::uint64_t>(b.v[i]));
        }
        return a;
    }
    /// Lane-wise bitwise OR: negative exactly when one of the two is.
    friend Portable operator|(Portable a, const Portable& b) {
        for (std::size_t i = 0; i < 8; ++i) {
            a.v[i] |= b.v[i];
        }
        return a;
    }
    /// Bit i set when lane i is >= 0.
    std::uint8_t nonnegative_bits() const {
        unsigned bits = 0;
        for (std::size_t i = 0; i < 8; ++i) {
            bits |= unsigned{v[i] >= 0} << i;
        }
        return static_cast<std::uint8_t>(bits);
    }
};

#if defined(__SSE2__)
/// Eight int64 values in four SSE2 registers (two lanes each).
struct Sse2 {
    __m128i r[4]; ///< r[k] holds lanes 2k and 2k + 1
    /// Every lane set to `value`.
    static Sse2 broadcast(std::int64_t value) {
        const __m128i x = _mm_set1_epi64x(value);
        return {{x, x, x, x}};
    }
    /// Lane i set to i * step (i = 0 .. 7).
    static Sse2 ramp(std::int64_t step) {
        Sse2 s;
        for (int k = 0; k < 4; ++k) {
            s.r[static_cast<std::size_t>(k)] =
                _mm_set_epi64x((2 * k + 1) * step, 2 * k * step); // high, low
        }
        return s;
    }
    /// Lane-wise sum (paddq).
    friend Sse2 operator+(Sse2 a, const Sse2& b) {
        for (std::size_t k = 0; k < 4; ++k) {
            a.r[k] = _mm_add_epi64(a.r[k], b.r[k]);
        }
        return a;
    }
    /// Lane-wise bitwise OR (por).
    friend Sse2 operator|(Sse2 a, const Sse2& b) {
        for (std::size_t k = 0; k < 4; ++k) {
            a.r[k] = _mm_or_si128(a.r[k], b.r[k]);
        }
        return a;
    }
    /// Bit i set when lane i is >= 0: movmskpd reads the top bit of each 64-bit lane.
    std::uint8_t nonnegative_bits() const {
        unsigned negative = 0;
        for (std::size_t k = 0; k < 4; ++k) {
            const auto two =
                static_cast<unsigned>(_mm_movemask_pd(_mm_castsi128_pd(r[k])));
            negative |= two << (2 * k);
        }
        return static_cast<std::uint8_t>(~negative & 0xffu);
    }
};
#endif

} // namespace lanes

#if defined(__SSE2__) && !defined(EXACTPIXELS_PORTABLE_LANES)
/// The eight lanes the fast rasterizers use: SSE2 where the compiler targets it.
using Lanes8 = lanes::Sse2;
#else
/// The eight lanes the fast rasterizers use: the portable array.
using Lanes8 = lanes::Portable;
#endif

} // namespace exactpixels
