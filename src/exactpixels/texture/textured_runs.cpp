#include "exactpixels/texture/textured_runs.hpp"

#include "exactpixels/base/error.hpp"
#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"
#include "exactpixels/raster/row_runs.hpp"

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#if defined(__SSE2__) && !defined(EXACTPIXELS_PORTABLE_LANES)
#include <emmintrin.h>
#endif

namespace exactpixels {

namespace {

/// The bias of rule 1, floor(u): the texel the teaching path picks (TexelRounding).
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

/// A texture that can_fetch_masked allows (power-of-two sides, repeat): texel (i, j) is
/// fetch_texel_masked's, and the SSE2 loop finds the same texel as
/// texels[(j & h_mask) << w_shift | (i & w_mask)].
struct MaskedTexels {
    explicit MaskedTexels(const Texture& t)
        : texture(&t), texels(t.texels().data()), w_mask(t.width() - 1),
          h_mask(t.height() - 1),
          w_shift(std::countr_zero(static_cast<unsigned>(t.width()))) {}
    const Texture* texture; ///< the texture read
    const Rgba8* texels;    ///< its texels, row-major, width 1 << w_shift
    int w_mask;             ///< width - 1
    int h_mask;             ///< height - 1
    int w_shift;            ///< log2(width)
    /// Texel (i, j) after wrapping.
    Rgba8 operator()(int i, int j) const { return fetch_texel_masked(*texture, i, j); }
};

#if defined(__SSE2__) && !defined(EXACTPIXELS_PORTABLE_LANES)
/// The fast variant of textured_run for a masked texture: two pixels, k and k + 1, per
/// step in the two double lanes of SSE2, each lane doing exact_at's operations in its
/// order (IEEE arithmetic rounds a lane as it rounds a scalar: the same bits, tested),
/// then floor_to_int's truncation and correction, and the masks, in integer
/// lanes. An odd last pixel is the scalar loop's.
void textured_run_sse2(Rgba8* row, const PerspectiveSpan<double>& ps,
                       const MaskedTexels& tex) {
    const __m128d u_w = _mm_set1_pd(ps.u_w), du_w = _mm_set1_pd(ps.du_w);
    const __m128d v_w = _mm_set1_pd(ps.v_w), dv_w = _mm_set1_pd(ps.dv_w);
    const __m128d one_w = _mm_set1_pd(ps.one_w), done_w = _mm_set1_pd(ps.done_w);
    const __m128d one = _mm_set1_pd(1.0), two = _mm_set1_pd(2.0);
    const __m128i w_mask = _mm_set1_epi32(tex.w_mask),
                  h_mask = _mm_set1_epi32(tex.h_mask);
    const __m128i shift = _mm_cvtsi32_si128(tex.w_shift);
    // floor of both lanes as two int32 in lanes 0 and 1: truncate, then add -1 (the
    // comparison's all-ones) where the truncation is above the value.
    const auto floor2 = [](__m128d x) {
        const __m128i t = _mm_cvttpd_epi32(x);
        const __m128d above = _mm_cmpgt_pd(_mm_cvtepi32_pd(t), x);
        return _mm_add_epi32(
            t, _mm_shuffle_epi32(_mm_castpd_si128(above), _MM_SHUFFLE(3, 3, 2, 0)));
    };
    __m128d t = _mm_set_pd(1.0, 0.0); // k, k + 1 as doubles
    int k = 0;
    for (; k + 1 < ps.count; k += 2) {
        const __m128d w = _mm_div_pd(one, _mm_add_pd(one_w, _mm_mul_pd(t, done_w)));
        const __m128d u = _mm_mul_pd(_mm_add_pd(u_w, _mm_mul_pd(t, du_w)), w);
        const __m128d v = _mm_mul_pd(_mm_add_pd(v_w, _mm_mul_pd(t, dv_w)), w);
        const __m128i index =
            _mm_or_si128(_mm_sll_epi32(_mm_and_si128(floor2(v), h_mask), shift),
                         _mm_and_si128(floor2(u), w_mask));
        row[k] = tex.texels[static_cast<std::uint32_t>(_mm_cvtsi128_si32(index))];
        row[k + 1] = tex.texels[static_cast<std::uint32_t>(
            _mm_cvtsi128_si32(_mm_srli_si128(index, 4)))];
        t = _mm_add_pd(t, two);
    }
    if (k < ps.count) {
        const UV<double> uv = exact_at(ps, k);
        row[k] = tex(real_texel_index(uv.u, rule_1), real_texel_index(uv.v, rule_1));
    }
}
#endif

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
    traverse_runs_stepped(s, r, [&](Span run) {
        Rgba8* row =
            target.colour +
            static_cast<std::size_t>(run.y) * static_cast<std::size_t>(target.width) +
            static_cast<std::size_t>(run.x_begin);
        const PerspectiveSpan<double> ps = perspective_span(planes, run);
#if defined(__SSE2__) && !defined(EXACTPIXELS_PORTABLE_LANES)
        if constexpr (std::is_same_v<std::decay_t<Fetch>, MaskedTexels>) {
            textured_run_sse2(row, ps, fetch);
            return;
        }
#endif
        textured_run(row, ps, fetch);
    });
}

} // namespace

void draw_textured_runs(const RenderTarget& target,
                        std::span<const std::array<TexturedVertex, 3>> triangles,
                        const Texture& texture, Wrap wrap) {
    check_all(triangles);
    if (can_fetch_masked(texture, wrap)) {
        // Repeat on a power of two: wrap_index_masked, a mask per index (the fast case).
        const MaskedTexels fetch(texture);
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
