#include "exactpixels/fast/textured_runs.hpp"

#include "exactpixels/base/error.hpp"
#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/fast/exact_lanes.hpp"
#include "exactpixels/fast/row_runs.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>


namespace exactpixels {

namespace {

/// The modifier of rule 1, floor(u): the texel the teaching path picks (TexelRounding).
constexpr std::int32_t rule_1 = texel_scale / 2;

/// Checks every triangle before anything is drawn; Error names the triangle.
void check_all(std::span<const std::array<TexturedVertex, 3>> triangles) {
    const MapperSettings exact{}; // the exact mapper in double: what is drawn
    for (std::size_t n = 0; n < triangles.size(); ++n) {
        try {
            check_textured_triangle(triangles[n], exact);
            for (std::size_t k = 0; k < 3; ++k) {
                const TexCoord uv = triangles[n][k].uv;
                if (std::abs(uv.x) > max_fast_texel_coordinate ||
                    std::abs(uv.y) > max_fast_texel_coordinate) {
                    throw Error(fmt::format("textured triangle: vertex {} has texture "
                                            "coordinate ({}, {}) texels, beyond the fast "
                                            "path's +-2^24",
                                            k, uv.x, uv.y));
                }
            }
        } catch (const Error& error) {
            throw Error(fmt::format("triangle {}: {}", n, error.what()));
        }
    }
}

//> textured-run
/// Writes the n = ps.count pixels from `row` on: at pixel k chapter 3's exact mapper
/// (exact_at: one divide, two multiplications), the texel floor(u), floor(v) (rule 1,
/// real_texel_index), fetched by fetch(i, j), which wraps.
template <class Fetch>
void textured_run(Rgba8* row, const PerspectiveSpan<double>& ps, Fetch&& fetch) {
    for (int k = 0; k < ps.count; ++k) {
        const UV<double> uv = exact_at(ps, k);
        row[k] = fetch(real_texel_index(uv.u, rule_1), real_texel_index(uv.v, rule_1));
    }
}
//< textured-run

/// A texture that can_fetch_masked allows (power-of-two sides, repeat), with the
/// instruction set of its runs (exact_lanes.hpp): texel (i, j) is fetch_texel_masked's.
struct MaskedTexels {
    MaskedTexels(const Texture& t, SimdVariant v)
        : texture(&t), lanes(lane_texels(t)), variant(v) {}
    const Texture* texture; ///< the texture read
    LaneTexels lanes;       ///< its texels and masks, for the vector kernels
    SimdVariant variant;    ///< the runs' instruction set (portable: textured_run)
    /// Texel (i, j) after wrapping.
    Rgba8 operator()(int i, int j) const { return fetch_texel_masked(*texture, i, j); }
};

/// The triangle's runs in the vector kernels, up to 64 rows per call: each kernel sets
/// a run's span up itself (perspective_span's operations), so that a row costs no call.
void draw_runs_lanes(const RenderTarget& target, const EdgeSetup<FixedEdge>& s, PixelRect r,
                     const TexturePlanes& planes, const MaskedTexels& fetch) {
    const LanePlanes p = lane_planes(planes);
    const LaneFrame frame{target.colour, target.width};
    std::array<LaneRun, 64> runs{};
    int n = 0;
    traverse_runs_stepped(s, r, [&](Span run) {
        runs[static_cast<std::size_t>(n++)] = {run.y, run.x_begin, run.x_end};
        if (n == static_cast<int>(runs.size())) {
            textured_runs_lanes(fetch.variant, frame, p, runs.data(), n, fetch.lanes);
            n = 0;
        }
    });
    textured_runs_lanes(fetch.variant, frame, p, runs.data(), n, fetch.lanes);
}

/// Draws one checked triangle, wrapping texel indices with fetch(i, j).
template <class Fetch>
void draw_one(const RenderTarget& target, const std::array<TexturedVertex, 3>& v,
              Fetch&& fetch) {
    std::array<FixedPoint2, 3> snapped{};
    std::array<Point2, 3> corners{};
    for (std::size_t k = 0; k < 3; ++k) {
        snapped[k] = snap_to_subpixel(v[k].position);
        corners[k] = to_pixels(snapped[k]); // the planes run through the snapped corners
    }
    const EdgeSetup<FixedEdge> s = setup_edges(snapped);
    const PixelRect r = pixel_bounds(snapped, Viewport{target.width, target.height});
    if (s.empty || r.empty()) {
        return;
    }
    const TexturePlanes planes = texture_planes(corners, v, /*affine=*/false);
    if constexpr (std::is_same_v<std::decay_t<Fetch>, MaskedTexels>) {
        if (fetch.variant != SimdVariant::portable) { // 2, 4 or 8 divides at once
            draw_runs_lanes(target, s, r, planes, fetch);
            return;
        }
    }
    traverse_runs_stepped(s, r, [&](Span run) {
        Rgba8* row =
            target.colour +
            static_cast<std::size_t>(run.y) * static_cast<std::size_t>(target.width) +
            static_cast<std::size_t>(run.x_begin);
        textured_run(row, perspective_span(planes, run), fetch);
    });
}

} // namespace

void draw_textured_runs(const RenderTarget& target,
                        std::span<const std::array<TexturedVertex, 3>> triangles,
                        const Texture& texture, Wrap wrap) {
    draw_textured_runs(target, triangles, texture, wrap, chosen_simd());
}

void draw_textured_runs(const RenderTarget& target,
                        std::span<const std::array<TexturedVertex, 3>> triangles,
                        const Texture& texture, Wrap wrap, SimdVariant variant) {
    check_all(triangles);
    if (can_fetch_masked(texture, wrap)) {
        // Repeat on a power of two: wrap_index_masked, a mask per index (the fast case).
        const MaskedTexels fetch(texture, variant);
        for (const auto& tri : triangles) {
            draw_one(target, tri, fetch);
        }
        return;
    }
    const auto fetch = [&](int i, int j) { return fetch_texel(texture, i, j, wrap); };
    for (const auto& tri : triangles) {
        draw_one(target, tri, fetch);
    }
}

} // namespace exactpixels
