// supersampled_reference.hpp: what a scene's pixels should be when each one averages the
// texture over its whole square, for measuring the renderer's filters (chapter 8).
//
// Usage:
//   const Scene scene = load_scene("chapters/07-scenes/scenes/horizon_filtered.toml");
//   std::vector<LinearTexel> ref = supersampled_reference(scene, 8);   // 8 x 8 per pixel
//   std::vector<LinearTexel> img = linear_pixels(render_scene(scene).image);
//   double e = rms_code_error(img, ref);    // lab/filter_measure.hpp, 8-bit codes
//
// The reference renders the scene with nearest sampling at s times its width and height
// (the same camera and field of view, so the samples of pixel (x, y) are the s x s
// sub-pixel centres (x + (i + 0.5) / s, y + (j + 0.5) / s)) and averages each block in
// linear light (srgb.hpp, units of 1/65535). Pixels are row-major, row 0 at the top,
// scene.width x scene.height of them. s is in [1, supersample_max_factor] and the big
// render must stay within max_image_side (scene_loader.hpp) (both checked, Error
// otherwise).
#pragma once

#include "exactpixels/base/framebuffer.hpp"
#include "exactpixels/scene/scene.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/texture/srgb.hpp"

#include <vector>

namespace exactpixels {

/// The most samples per side of a pixel supersampled_reference takes.
inline constexpr int supersample_max_factor = 16;

/// Every pixel of the frame decoded to linear light (decode_texel), row-major.
std::vector<LinearTexel> linear_pixels(const Framebuffer& frame);

/// The scene rendered with nearest sampling at `s` x `s` samples per pixel and each
/// pixel's samples averaged in linear light: the reference the filters are measured
/// against. Throws Error when s is outside [1, supersample_max_factor] or the enlarged
/// image would exceed max_image_side on a side.
std::vector<LinearTexel> supersampled_reference(const Scene& scene, int s);

} // namespace exactpixels
