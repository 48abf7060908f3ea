// depth_lanes_kernel.hpp: chapter 10's depth-tested covered runs in the vector
// instruction set chosen at run time (fast/simd.hpp): one kernel per instruction set,
// each in its own namespace (simd_sse2, simd_avx2, simd_avx512, simd_neon), compiled
// from fast/depth_lanes.inl with that set's flags.
//
// Usage:
//   const DepthRunFn depth = depth_run_kernel(chosen_simd());   // once per triangle
//   depth({z0, dzdx, dzdy, colour}, y, x_begin, x_end, depth_row, colour_row);
//
// The kernel writes depth_run's bits (depth_lanes.hpp): z = (z0 + float(y) dzdy) +
// float(x) dzdx in float, without contraction, drawn where z < the stored depth; it reads
// and writes no pixel outside the run. As with exact_lanes_kernel.hpp, nothing here is
// inline or a template, so that no wide instruction can reach a caller on a CPU without
// it (`one_definition_lanes`).
#pragma once

#include "exactpixels/base/framebuffer.hpp"
#include "exactpixels/fast/simd.hpp"

namespace exactpixels {

/// A triangle's depth plane and colour as the depth kernels take them (DepthPlane's
/// fields, tiled_rasterizer.hpp).
struct RunPlane {
    float z0;     ///< z at the centre of pixel (0, 0)
    float dzdx;   ///< change of z per pixel to the right
    float dzdy;   ///< change of z per pixel down
    Rgba8 colour; ///< written where the depth test passes
};

/// Depth-tests and draws pixels x_begin .. x_end - 1 of row y (depth_row and colour_row
/// point at column 0 of the row).
using DepthRunFn = void (*)(const RunPlane& plane, int y, int x_begin, int x_end,
                            float* depth_row, Rgba8* colour_row);

/// The depth-tested run of variant v (portable: depth_run with its portable lanes).
DepthRunFn depth_run_kernel(SimdVariant v);

#define EXACTPIXELS_DECLARE_RUN_KERNELS(set)                                             \
    namespace simd_##set {                                                               \
        void depth_run(const RunPlane& plane, int y, int x_begin, int x_end,             \
                       float* depth_row, Rgba8* colour_row);                             \
    }
EXACTPIXELS_DECLARE_RUN_KERNELS(sse2)
EXACTPIXELS_DECLARE_RUN_KERNELS(avx2)
EXACTPIXELS_DECLARE_RUN_KERNELS(avx512)
EXACTPIXELS_DECLARE_RUN_KERNELS(neon)
#undef EXACTPIXELS_DECLARE_RUN_KERNELS

} // namespace exactpixels
