#include "exactpixels/fast/depth_lanes.hpp"
#include "exactpixels/fast/depth_lanes_kernel.hpp"
#include "exactpixels/fast/tiled_rasterizer.hpp"

namespace exactpixels {

namespace {

/// The portable kernel: chapter 10's depth_run with its portable lanes.
void portable_depth_run(const RunPlane& p, int y, int x_begin, int x_end,
                        float* depth_row, Rgba8* colour_row) {
    depth_run<depth_lanes::Portable>({p.z0, p.dzdx, p.dzdy}, p.colour, y, x_begin, x_end,
                                     depth_row, colour_row);
}

} // namespace

DepthRunFn depth_run_kernel(SimdVariant v) {
    switch (v) {
#if defined(EXACTPIXELS_SIMD_X86)
    case SimdVariant::sse2:
        return simd_sse2::depth_run;
    case SimdVariant::avx2:
        return simd_avx2::depth_run;
    case SimdVariant::avx512:
        return simd_avx512::depth_run;
#elif defined(EXACTPIXELS_SIMD_ARM64)
    case SimdVariant::neon:
        return simd_neon::depth_run;
#endif
    default: // portable, and a set this build has none of (simd_available says no)
        return portable_depth_run;
    }
}

} // namespace exactpixels
