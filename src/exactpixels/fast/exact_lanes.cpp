#include "exactpixels/fast/exact_lanes.hpp"

#include "exactpixels/base/floor_to_int.hpp"

#include <bit>
#include <cassert>

namespace exactpixels {

LaneTexels lane_texels(const Texture& texture) {
    return {texture.texels().data(), texture.width() - 1, texture.height() - 1,
            std::countr_zero(static_cast<unsigned>(texture.width()))};
}

namespace {

/// The plain loop: exact_at at every pixel.
PerspectiveSpan<double> plain_span(const LaneSpan& s) {
    return {s.u_w, s.v_w, s.one_w, s.du_w, s.dv_w, s.done_w, s.count};
}

} // namespace

// Each case calls the set's own kernel; a set this build has no kernel for (another
// architecture) falls to the plain loop, which simd_available never lets it reach.
#if defined(EXACTPIXELS_SIMD_X86)
#define EXACTPIXELS_LANES_CASES(call)                                                    \
    case SimdVariant::sse2:                                                              \
        return simd_sse2::call;                                                          \
    case SimdVariant::avx2:                                                              \
        return simd_avx2::call;                                                          \
    case SimdVariant::avx512:                                                            \
        return simd_avx512::call;
#elif defined(EXACTPIXELS_SIMD_ARM64)
#define EXACTPIXELS_LANES_CASES(call)                                                    \
    case SimdVariant::neon:                                                              \
        return simd_neon::call;
#else
#define EXACTPIXELS_LANES_CASES(call)
#endif

void exact_uv_lanes(SimdVariant variant, const LaneSpan& s, int k0, int n, double* u,
                    double* v) {
    switch (variant) {
        EXACTPIXELS_LANES_CASES(exact_uv(s, k0, n, u, v))
    default:
        break;
    }
    const PerspectiveSpan<double> plain = plain_span(s);
    for (int i = 0; i < n; ++i) {
        const UV<double> uv = exact_at(plain, k0 + i);
        u[i] = uv.u;
        v[i] = uv.v;
    }
}

void textured_run_lanes(SimdVariant variant, Rgba8* row, const LaneSpan& s,
                        const LaneTexels& tex) {
    switch (variant) {
        EXACTPIXELS_LANES_CASES(textured_run(row, s, tex))
    default:
        break;
    }
    const PerspectiveSpan<double> plain = plain_span(s);
    for (int k = 0; k < s.count; ++k) {
        const UV<double> uv = exact_at(plain, k);
        const int i = floor_to_int(uv.u) & tex.w_mask, j = floor_to_int(uv.v) & tex.h_mask;
        row[k] = tex.texels[static_cast<unsigned>(j) << tex.w_shift | static_cast<unsigned>(i)];
    }
}

} // namespace exactpixels
