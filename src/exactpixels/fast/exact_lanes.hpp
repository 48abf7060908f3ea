// exact_lanes.hpp: chapter 3's exact mapper with 2, 4 or 8 pixels' divides at once, in
// the vector instruction set chosen at run time (fast/simd.hpp): a named fast variant
// of map_span_exact and of the textured runs' per-pixel loop, with their bits.
//
// Usage:
//   map_span_exact_lanes(chosen_simd(), ps, [&](int k, double u, double v) { ... });
//   // the calls map_span_exact(ps, ...) makes, with the same u and v
//   textured_run_lanes(chosen_simd(), row, ps, lane_texels(texture));
//   // row[k] = the texel at floor(u), floor(v) of pixel k, wrapped by masks
//
// Units are span_mappers.hpp's. SimdVariant::portable runs the plain scalar loop.
#pragma once

#include "exactpixels/fast/exact_lanes_kernel.hpp"
#include "exactpixels/fast/simd.hpp"
#include "exactpixels/texture/span_mappers.hpp"
#include "exactpixels/texture/texture.hpp"
#include "exactpixels/texture/texture_mapper.hpp"

#include <algorithm>

namespace exactpixels {

/// The span's numbers for the kernels.
inline LaneSpan lane_span(const PerspectiveSpan<double>& s) {
    return {s.u_w, s.v_w, s.one_w, s.du_w, s.dv_w, s.done_w, s.count};
}

/// The texels of a texture that can_fetch_masked allows (power-of-two sides, repeat).
LaneTexels lane_texels(const Texture& texture);

/// u and v of pixels k0 .. k0 + n - 1 of span s into u[0 .. n), v[0 .. n): exact_at's
/// values, computed in the instruction set v (portable: exact_at itself).
void exact_uv_lanes(SimdVariant variant, const LaneSpan& s, int k0, int n, double* u,
                    double* v);

/// Pixels 0 .. s.count - 1 of `row` take their texels under the exact mapper and rule 1
/// (floor(u), floor(v)), wrapped by tex's masks, computed in the instruction set
/// `variant` (portable: exact_at and floor_to_int, pixel by pixel). Every u and v of the
/// span must lie within +-2^24 texels (textured_runs.hpp checks the corners).
void textured_run_lanes(SimdVariant variant, Rgba8* row, const LaneSpan& s,
                        const LaneTexels& tex);

/// The exact mapper's planes of a triangle (u/w, v/w, 1/w) for the kernels.
LanePlanes lane_planes(const TexturePlanes& planes);

/// textured_run_lanes on each of n runs of one triangle, whose span is set up from the
/// planes as perspective_span sets it up: one call, not one per row.
void textured_runs_lanes(SimdVariant variant, LaneFrame frame, const LanePlanes& planes,
                         const LaneRun* runs, int n, const LaneTexels& tex);

/// The span of one run as the kernels of `variant` set it up (perspective_span's bits).
LaneSpan run_span_lanes(SimdVariant variant, const LanePlanes& planes, LaneRun run);

//> map-span-exact-lanes
/// The exact mapper with its divides in lanes: u and v for up to 64 pixels at a time
/// from exact_uv_lanes, then emit(k, u, v) for each, in order, as map_span_exact does.
template <class Emit>
void map_span_exact_lanes(SimdVariant variant, const PerspectiveSpan<double>& s,
                          Emit&& emit) {
    constexpr int chunk = 64;
    double u[chunk], v[chunk];
    const LaneSpan lane = lane_span(s);
    for (int k0 = 0; k0 < s.count; k0 += chunk) {
        const int n = std::min(chunk, s.count - k0);
        exact_uv_lanes(variant, lane, k0, n, u, v);
        for (int i = 0; i < n; ++i) {
            emit(k0 + i, u[i], v[i]);
        }
    }
}
//< map-span-exact-lanes

} // namespace exactpixels
