#include "exactpixels/fast/exact_lanes.hpp"

#include "exactpixels/base/floor_to_int.hpp"

#include <bit>
#include <cstddef>
#include <cassert>

namespace exactpixels {

LaneTexels lane_texels(const Texture& texture) {
    return {texture.texels().data(), texture.width() - 1, texture.height() - 1,
            std::countr_zero(static_cast<unsigned>(texture.width()))};
}

LanePlanes lane_planes(const TexturePlanes& planes) {
    const auto lane = [](const ScreenPlane& p) {
        return LanePlane{p.origin.x, p.origin.y, p.value, p.g.dx, p.g.dy};
    };
    return {lane(planes.u_w), lane(planes.v_w), lane(planes.one_w)};
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

LaneSpan run_span_lanes(SimdVariant variant, const LanePlanes& p, LaneRun run) {
    switch (variant) {
        EXACTPIXELS_LANES_CASES(run_span(p, run))
    default:
        break;
    }
    const auto plane = [](const LanePlane& q) {
        return ScreenPlane{{q.origin_x, q.origin_y}, q.value, {q.dx, q.dy}};
    };
    const PerspectiveSpan<double> ps =
        perspective_span({plane(p.u_w), plane(p.v_w), plane(p.one_w), {}, {}},
                         Span{run.y, run.x_begin, run.x_end});
    return lane_span(ps);
}

void textured_runs_lanes(SimdVariant variant, LaneFrame frame, const LanePlanes& p,
                         const LaneRun* runs, int n, const LaneTexels& tex) {
    switch (variant) {
        EXACTPIXELS_LANES_CASES(textured_runs(frame, p, runs, n, tex))
    default:
        break;
    }
    for (int r = 0; r < n; ++r) {
        textured_run_lanes(variant,
                           frame.colour +
                               static_cast<std::size_t>(runs[r].y) *
                                   static_cast<std::size_t>(frame.width) +
                               static_cast<std::size_t>(runs[r].x_begin),
                           run_span_lanes(variant, p, runs[r]), tex);
    }
}

} // namespace exactpixels
