// textured_runs.hpp: perspective-correct nearest texturing on chapter 10's fastest
// traversal: covered runs (row_runs.hpp) feeding chapter 3's exact mapper, one divide per
// pixel, with the very texels of the teaching path.
//
// Usage:
//   std::vector<std::array<TexturedVertex, 3>> tris = {...};  // texture_mapper.hpp
//   std::vector<Rgba8> pixels(width * height);
//   draw_textured_runs(RenderTarget{pixels.data(), nullptr, width, height}, tris,
//                      checkerboard_texture(256, 256, 8), Wrap::repeat);
//   // the pixels of draw_textured_triangle(frame, t, texture, {.wrap = Wrap::repeat})
//   // for every t in order: chapter 3's exact mapper in double, rule 1 (floor).
//
// Units and conventions are texture_mapper.hpp's: positions in pixels (snapped to 1/256
// px, top-left rule), w > 0 the view-space depth, uv in texels (texel (i, j) covers
// [i, i+1) x [j, j+1)). Every triangle is drawn, none culled; the target's depth buffer
// is neither tested nor written. What makes the pixels the teaching path's, bit for bit:
// the runs are the rows' whole covered spans (the scanline spans chapter 3 maps), and
// each run's u/w, v/w and 1/w come from the same planes (texture_planes) through the same
// setup (perspective_span, or the vector kernels' copy of its operations) and the same
// per-pixel formula (exact_at), so every double is the same; only the index conversion
// (real_texel_index, which rounds with floor_to_int) and the wrap (wrap_index_masked,
// for a power-of-two texture that repeats) are their fast variants.
#pragma once

#include "exactpixels/fast/simd.hpp"
#include "exactpixels/fast/tiled_rasterizer.hpp"
#include "exactpixels/texture/texture.hpp"
#include "exactpixels/texture/texture_mapper.hpp"

#include <array>
#include <span>

namespace exactpixels {

/// The largest |u| or |v| at a vertex, in texels, that draw_textured_runs accepts: the
/// coordinates of every covered pixel lie between the vertices' (perspective-correct
/// interpolation is a convex combination), so their floors are far inside int.
inline constexpr double max_fast_texel_coordinate = 16777216.0; // 2^24 texels

/// Draws the triangles in order into target.colour, each covered pixel taking the
/// nearest texel (rule 1: floor(u), floor(v)) of chapter 3's exact mapper in double,
/// wrapped by `wrap`: exactly draw_textured_triangle's pixels with MapperSettings
/// {exact, float64, default rounding, wrap}. Every triangle is checked first
/// (check_textured_triangle, and |u|, |v| <= max_fast_texel_coordinate): on Error,
/// naming the triangle, nothing is drawn.
void draw_textured_runs(const RenderTarget& target,
                        std::span<const std::array<TexturedVertex, 3>> triangles,
                        const Texture& texture, Wrap wrap);

/// The same with the runs of a power-of-two texture under repeat computed in the
/// instruction set `variant` (exact_lanes.hpp; the overload above takes chosen_simd()),
/// which must be available: the same pixels for every variant.
void draw_textured_runs(const RenderTarget& target,
                        std::span<const std::array<TexturedVertex, 3>> triangles,
                        const Texture& texture, Wrap wrap, SimdVariant variant);

} // namespace exactpixels
