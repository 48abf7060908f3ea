// exact_lanes.inl: chapter 3's exact mapper on LANES pixels at once, the one source text
// of every instruction set's kernels. src/CMakeLists.txt compiles it once per set, each
// time with that set's flags (-msse2, -mavx2, -mavx512f; nothing on ARM64, where NEON is
// the baseline), EXACTPIXELS_LANES_SET naming the namespace and EXACTPIXELS_LANES the
// doubles per step, and always with -ffp-contract=off.
//
// The lanes are GCC's (and Clang's) vector types: the compiler turns `a / b` on eight
// doubles into one vdivpd on a 512-bit register, or two on 256-bit ones, or four divpd.
// Each lane does exact_at's operations in exact_at's order (span_mappers.hpp), on the
// same doubles, so each lane rounds as the scalar loop rounds: the same bits.
//
// This file calls no inline function or template of another header, so that nothing
// compiled here for a wide instruction set can stand in for a shared function (see
// exact_lanes_kernel.hpp).
#include "exactpixels/fast/exact_lanes_kernel.hpp"

namespace exactpixels::EXACTPIXELS_LANES_SET {

namespace {

constexpr int lanes = EXACTPIXELS_LANES;
using Doubles = double __attribute__((vector_size(lanes * sizeof(double))));
using Ints = std::int32_t __attribute__((vector_size(lanes * sizeof(std::int32_t))));

/// Calls step(t, k, n) for the pixels first, first + 1, ..., first + count - 1, lanes at a
/// time: t holds the pixel numbers as doubles, pixels k .. k + n - 1 of the run are
/// valid (n <= lanes). The last, shorter step repeats the last pixel in its spare lanes
/// rather than run past the end.
template <class Step> void for_lanes(int first, int count, Step&& step) {
    Doubles t{};
    for (int l = 0; l < lanes; ++l) {
        t[l] = static_cast<double>(first + l);
    }
    int k = 0;
    for (; k + lanes <= count; k += lanes) {
        step(t, k, lanes);
        t += static_cast<double>(lanes); // small integers: exact
    }
    if (k < count) {
        const int last = first + count - 1;
        for (int l = 0; l < lanes; ++l) {
            const int pixel = first + k + l;
            t[l] = static_cast<double>(pixel < last ? pixel : last);
        }
        step(t, k, count - k);
    }
}

/// floor(x) of every lane, |x| < 2^31: truncate, then subtract one where the truncation
/// came out above x (floor_to_int's correction, per lane).
Ints floor_lanes(Doubles x) {
    const Ints t = __builtin_convertvector(x, Ints);
    const Ints above = __builtin_convertvector(__builtin_convertvector(t, Doubles) > x, Ints);
    return t + above; // a true comparison is -1 in every bit
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

} // namespace

void textured_run(Rgba8* row, const LaneSpan& s, const LaneTexels& tex) {
    for_lanes(0, s.count, [&](Doubles t, int k, int n) {
        const LaneUV uv = exact_lanes(s, t);
        const Ints index = ((floor_lanes(uv.v) & tex.h_mask) << tex.w_shift) |
                           (floor_lanes(uv.u) & tex.w_mask);
        for (int l = 0; l < n; ++l) {
            row[k + l] = tex.texels[static_cast<std::uint32_t>(index[l])];
        }
    });
}

void exact_uv(const LaneSpan& s, int k0, int n, double* u, double* v) {
    for_lanes(k0, n, [&](Doubles t, int k, int m) {
        const LaneUV uv = exact_lanes(s, t);
        for (int l = 0; l < m; ++l) {
            u[k + l] = uv.u[l];
            v[k + l] = uv.v[l];
        }
    });
}

} // namespace exactpixels::EXACTPIXELS_LANES_SET
