// exact_lanes_kernel.hpp: the vector kernels of chapter 3's exact mapper, one set per
// instruction set, each in its own namespace (simd_sse2, simd_avx2, simd_avx512,
// simd_neon). Use them through exact_lanes.hpp, which picks the set.
//
// Each set is exact_lanes.inl compiled with its own flags (src/CMakeLists.txt). Nothing
// here is inline or a template: code compiled for AVX-512 must never be the copy of a
// shared inline function that the linker keeps for every caller (on an older CPU that
// copy would stop the program with an illegal instruction). The `one_definition_lanes`
// test checks the compiled kernels for any symbol outside their own namespace.
#pragma once

#include "exactpixels/base/framebuffer.hpp"

#include <cstdint>

namespace exactpixels {

/// One span of the exact mapper in plain numbers: PerspectiveSpan<double>'s fields.
struct LaneSpan {
    double u_w;    ///< u/w at pixel 0's centre
    double v_w;    ///< v/w at pixel 0's centre
    double one_w;  ///< 1/w at pixel 0's centre (> 0)
    double du_w;   ///< change of u/w per pixel to the right
    double dv_w;   ///< change of v/w per pixel to the right
    double done_w; ///< change of 1/w per pixel to the right
    int count;                 ///< pixels in the span, >= 1
};

/// A power-of-two texture that repeats: texel (i, j) is
/// texels[(j & h_mask) << w_shift | (i & w_mask)].
struct LaneTexels {
    const Rgba8* texels; ///< row-major, width 1 << w_shift
    int w_mask;          ///< width - 1
    int h_mask;          ///< height - 1
    int w_shift;         ///< log2(width)
};

/// A plane over the screen in plain numbers: ScreenPlane's fields (screen_plane.hpp),
/// whose value at (x, y) is value + dx (x - origin_x) + dy (y - origin_y).
struct LanePlane {
    double origin_x; ///< the corner where `value` holds, pixels
    double origin_y; ///< (its y)
    double value;    ///< the value there
    double dx;       ///< change per pixel to the right
    double dy;       ///< change per pixel down
};

/// The exact mapper's three planes of one triangle (TexturePlanes' u_w, v_w, one_w).
struct LanePlanes {
    LanePlane u_w;   ///< u/w
    LanePlane v_w;   ///< v/w
    LanePlane one_w; ///< 1/w
};

/// One covered run: pixels x_begin .. x_end - 1 of row y (a Span), x_end > x_begin.
struct LaneRun {
    int y;       ///< the row
    int x_begin; ///< the first covered column
    int x_end;   ///< one past the last
};

/// Where the runs are drawn: row y starts at colour + y * width.
struct LaneFrame {
    Rgba8* colour; ///< the top row's first pixel
    int width;     ///< pixels per row
};

#define EXACTPIXELS_DECLARE_LANES(set)                                                   \
    namespace simd_##set {                                                               \
    void textured_run(Rgba8* row, const LaneSpan& s, const LaneTexels& t);               \
    void textured_runs(LaneFrame f, const LanePlanes& p, const LaneRun* runs, int n,     \
                       const LaneTexels& t);                                             \
    LaneSpan run_span(const LanePlanes& p, LaneRun run);                                 \
    void exact_uv(const LaneSpan& s, int k0, int n, double* u, double* v);               \
    }
EXACTPIXELS_DECLARE_LANES(sse2)
EXACTPIXELS_DECLARE_LANES(avx2)
EXACTPIXELS_DECLARE_LANES(avx512)
EXACTPIXELS_DECLARE_LANES(neon)
#undef EXACTPIXELS_DECLARE_LANES

} // namespace exactpixels
