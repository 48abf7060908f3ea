// exact_lanes.inl: chapter 3's exact mapper on LANES pixels at once, the one source text
// of every instruction set's kernels. src/CMakeLists.txt compiles it once per set, each
// time with that set's flags (-msse2, -mavx2, -mavx512f; nothing on ARM64, where NEON is
// the baseline), EXACTPIXELS_LANES_SET naming the namespace and EXACTPIXELS_LANES the
// doubles per step, and always with -ffp-contract=off.
//
// The lanes are GCC's (and Clang's) vector types: the compiler turns `a / b` on eight
// doubles into one vdivpd on a 512-bit register, or two on 256-bit ones, or four divpd.
// Each lane does exact_at's operations in exact_at's order (span_mappers.hpp), on the
// same doubles, so each lane rounds as the scalar loop rounds: the same bits. The floor
// to an int has no operator in the vector types and takes the set's own instruction
// where it has one (vcvtpd2dq rounding down on AVX-512, vroundpd then vcvtpd2dq on AVX2;
// elsewhere truncate and correct); the indices are wrapped by masks in lanes, the texels
// fetched one load per lane, and on AVX2 and AVX-512 their colours stored in one store.
// textured_runs takes a triangle's runs in one call and sets each run's span up as
// perspective_span does (span_of), so that a row costs no call and no copy.
// (Gathering the texels with vpgatherdd measured 3 to 4 per cent slower than the loads on
// the AMD EPYC of chapter 10's runs; combining SSE2's two colours into one store, 8 per
// cent slower than two stores.)
//
// This file calls no inline function or template of another header, so that nothing
// compiled here for a wide instruction set can stand in for a shared function (see
// exact_lanes_kernel.hpp); the compiler's intrinsics (immintrin.h) are always inlined
// and never emitted as functions of their own.
#include "exactpixels/fast/exact_lanes_kernel.hpp"

#if defined(__AVX2__)
#include <immintrin.h>
#endif

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace exactpixels::EXACTPIXELS_LANES_SET {

namespace {

constexpr int lanes = EXACTPIXELS_LANES;
using Doubles = double __attribute__((vector_size(lanes * sizeof(double))));
using Ints = std::int32_t __attribute__((vector_size(lanes * sizeof(std::int32_t))));
static_assert(sizeof(Rgba8) == sizeof(std::int32_t)); // a colour fills one int lane

// The sets with a floor conversion of their own and a vector store of the colours.
#if defined(__AVX512F__) && EXACTPIXELS_LANES == 8
#define EXACTPIXELS_LANES_WIDE 512
#elif defined(__AVX2__) && EXACTPIXELS_LANES == 4
#define EXACTPIXELS_LANES_WIDE 256
#endif

/// Calls step(t, k, n) for the pixels first, first + 1, ..., first + count - 1, lanes at
/// a time: t holds the pixel numbers first + k .. first + k + lanes - 1 as doubles, of
/// which the first n are to be kept. A run of at least `lanes` pixels ends with one step
/// over its last `lanes` pixels, overlapping the step before (its pixels come out the
/// same twice), so every step keeps all its lanes; a shorter run is one step that repeats
/// its last pixel in the spare lanes rather than run past the end, keeping n = count.
template <class Step> [[gnu::always_inline]] inline void for_lanes(int first, int count, Step&& step) {
    Doubles iota{};
    for (int l = 0; l < lanes; ++l) {
        iota[l] = static_cast<double>(l);
    }
    if (count < lanes) {
        Doubles t{};
        for (int l = 0; l < lanes; ++l) {
            t[l] = static_cast<double>(first + (l < count ? l : count - 1));
        }
        step(t, 0, count);
        return;
    }
    Doubles t = iota + static_cast<double>(first);
    int k = 0;
    for (; k + lanes <= count; k += lanes) {
        step(t, k, lanes);
        t += static_cast<double>(lanes); // small integers: exact
    }
    if (k < count) {
        k = count - lanes;
        step(iota + static_cast<double>(first + k), k, lanes);
    }
}

/// floor(x) of every lane, |x| < 2^31.
Ints floor_lanes(Doubles x) {
#if EXACTPIXELS_LANES_WIDE == 512
    // One conversion rounding towards minus infinity (the zero-masking form, all lanes
    // kept: the plain one reads an undefined register that GCC 12 warns of).
    return reinterpret_cast<Ints>(_mm512_maskz_cvt_roundpd_epi32(
        static_cast<__mmask8>(0xff), reinterpret_cast<__m512d>(x),
        _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC));
#elif EXACTPIXELS_LANES_WIDE == 256
    // floor in double (exact), then a conversion of an integer: exact in any rounding.
    return reinterpret_cast<Ints>(
        _mm256_cvtpd_epi32(_mm256_floor_pd(reinterpret_cast<__m256d>(x))));
#else
    // Truncate, then subtract one where the truncation came out above x (floor_to_int's
    // correction, per lane).
    const Ints t = __builtin_convertvector(x, Ints);
    const Ints above =
        __builtin_convertvector(__builtin_convertvector(t, Doubles) > x, Ints);
    return t + above; // a true comparison is -1 in every bit
#endif
}

//> exact-lanes
/// u and v at the pixels t: one divide per lane, then two multiplications (exact_at).
struct LaneUV {
    Doubles u, v;
};
LaneUV exact_lanes(const LaneSpan& s, Doubles t) {
    const Doubles w = 1.0 / (s.one_w + t * s.done_w);
    return {(s.u_w + t * s.du_w) * w, (s.v_w + t * s.dv_w) * w};
}
//< exact-lanes

/// The plane's value at (x, y): ScreenPlane::at's operations in its order.
double plane_at(const LanePlane& p, double x, double y) {
    return p.value + p.dx * (x - p.origin_x) + p.dy * (y - p.origin_y);
}

//> lanes-run-span
/// A run's span, set up as perspective_span sets it up: the planes at the centre of the
/// run's first pixel, and their steps to the right.
LaneSpan span_of(const LanePlanes& p, LaneRun run) {
    const double x = run.x_begin + 0.5, y = run.y + 0.5;
    return {plane_at(p.u_w, x, y), plane_at(p.v_w, x, y), plane_at(p.one_w, x, y),
            p.u_w.dx,              p.v_w.dx,              p.one_w.dx,
            run.x_end - run.x_begin};
}
//< lanes-run-span

/// One run's texels (s and tex are the caller's copies, kept in registers), inlined
/// into each caller so that its loop is the caller's.
[[gnu::always_inline]] inline void run_texels(Rgba8* row, const LaneSpan& s, const LaneTexels& tex) {
    for_lanes(0, s.count, [&](Doubles t, int k, int n) {
        const LaneUV uv = exact_lanes(s, t);
        const Ints index = ((floor_lanes(uv.v) & tex.h_mask) << tex.w_shift) |
                           (floor_lanes(uv.u) & tex.w_mask);
#if defined(EXACTPIXELS_LANES_WIDE)
        if (n == lanes) { // one load per texel, one store of all the colours
            Ints colour;
            for (int l = 0; l < lanes; ++l) { // (a vector element has no address)
                std::uint32_t texel = 0;
                std::memcpy(&texel, &tex.texels[static_cast<std::uint32_t>(index[l])],
                            sizeof(Rgba8));
                colour[l] = static_cast<std::int32_t>(texel); // modular, as C++20 says
            }
            std::memcpy(static_cast<void*>(row + k), &colour, sizeof(colour));
            return;
        }
#endif
        for (int l = 0; l < n; ++l) { // two lanes, or a short run: pixel by pixel
            row[k + l] = tex.texels[static_cast<std::uint32_t>(index[l])];
        }
    });
}

} // namespace

void textured_run(Rgba8* row, const LaneSpan& span, const LaneTexels& texels) {
    // Copies, so that the compiler keeps them in registers across the stores to row.
    const LaneSpan s = span;
    const LaneTexels tex = texels;
    run_texels(row, s, tex);
}

void textured_runs(LaneFrame frame, const LanePlanes& planes, const LaneRun* runs, int n,
                   const LaneTexels& texels) {
    const LanePlanes p = planes;
    const LaneTexels tex = texels;
    for (int r = 0; r < n; ++r) { // a triangle's runs in one call: no call per row
        const LaneRun run = runs[r];
        run_texels(frame.colour +
                       static_cast<std::size_t>(run.y) * static_cast<std::size_t>(frame.width) +
                       static_cast<std::size_t>(run.x_begin),
                   span_of(p, run), tex);
    }
}

LaneSpan run_span(const LanePlanes& p, LaneRun run) {
    return span_of(p, run);
}

void exact_uv(const LaneSpan& span, int k0, int n, double* u, double* v) {
    const LaneSpan s = span;
    for_lanes(k0, n, [&](Doubles t, int k, int m) {
        const LaneUV uv = exact_lanes(s, t);
        for (int l = 0; l < m; ++l) {
            u[k + l] = uv.u[l];
            v[k + l] = uv.v[l];
        }
    });
}

} // namespace exactpixels::EXACTPIXELS_LANES_SET
