// filter_measure.hpp: chapter 8's test bench: each filter against a reference image of
// the texture integrated over every pixel, on chapter 5's scenes.
//
// Usage:
//   const AccuracyScene scene = grazing_floor_scene();
//   const FilterScene fs = prepare_filter_scene(scene);     // pixels, uv, derivatives
//   const std::vector<LinearTexel> ref = reference_image(fs);  // exact, deterministic
//   const FilterConfig trilinear{"trilinear", {.filter = Filter::trilinear}};
//   const std::vector<LinearTexel> img = filter_image(fs, trilinear);
//   double e = rms_code_error(img, ref);                     // in 8-bit sRGB codes
//   filter_frame(frame, fs, trilinear);  // the same pixels as 8-bit codes (the bench)
//
// Every pixel a triangle covers (chapter 1's coverage, the last triangle wins) is
// sampled at its centre: uv of the exact perspective mapping there and its exact
// derivatives (level_of_detail.hpp). A span is a run of consecutive pixels of one row
// that one triangle owns; its derivatives are taken at its middle. The reference is the
// mean of the texture (level 0, each texel a uniform square, linear light) over the
// pixel's square [x, x+1) x [y, y+1) under the same triangle's mapping (its planes
// extended where the square reaches past an edge), computed exactly: the texel edges
// are straight lines on screen, and each texel is weighted by the area of the piece of
// the square it covers. sampled_reference_image estimates the same mean from n x n
// samples, to check the exact one against. Scenes wrap with repeat.
#pragma once

#include "exactpixels/lab/accuracy_scenes.hpp"
#include "exactpixels/texture/filter.hpp"
#include "exactpixels/texture/level_of_detail.hpp"
#include "exactpixels/texture/mipmap.hpp"
#include "exactpixels/texture/perspective.hpp"

#include <array>
#include <string>
#include <vector>

namespace exactpixels {

/// Chapter 8's own scene, "horizon": a floor one unit below a level camera, from depth
/// 1 to 120 and 60 units to each side, 8 texels per unit of a 64 x 64 checkerboard of
/// 4-texel squares (repeated); near the horizon one pixel covers hundreds of texels.
AccuracyScene horizon_floor_scene();

/// Chapter 8's exercise on an oblique wall, "wall60" (not one of filter_scenes): a wall
/// whose normal is 60 degrees from the view axis, from depth 1.4 to 6.6, 128 texels per
/// unit of a 256 x 256 checkerboard of 2-texel squares (repeated), so that every pixel
/// is minified and the footprint stretches along the wall.
AccuracyScene oblique_wall_scene();

/// The scenes chapter 8 measures: chapter 5's wall, floor and field, then the horizon.
std::vector<AccuracyScene> filter_scenes();

/// One covered pixel of a scene with what every filter needs there.
struct FilterPixel {
    int x = 0;                      ///< column
    int y = 0;                      ///< row
    int triangle = 0;               ///< index of the covering triangle in the scene
    TexCoord uv{0.0};               ///< exact texture coordinate at the centre, texels
    TexelDerivatives exact;         ///< exact derivatives at the centre (@eq:derivatives)
    TexelDerivatives span_wide;     ///< the span's middle's derivatives
    TexelDerivatives triangle_wide; ///< the triangle's centroid derivatives
    Point2 span_middle{0.0};        ///< where span_wide was evaluated
};

/// A scene made ready for filtering: its covered pixels and its texture's mip chain.
struct FilterScene {
    const AccuracyScene* scene = nullptr; ///< the scene (outlives this)
    MipChain chain;                       ///< the mip chain of scene->texture
    std::vector<FilterPixel> pixels;      ///< row-major order
};

/// The covered pixels of the scene, their coordinates and derivatives, and the chain.
FilterScene prepare_filter_scene(const AccuracyScene& scene);

/// Which derivatives a filter is given: exact per pixel, the span's or the triangle's.
enum class Derivatives {
    per_pixel,   ///< exact at every pixel centre (@eq:derivatives)
    per_span,    ///< exact at the middle of the pixel's span, used for all its pixels
    per_triangle ///< exact at the triangle's centroid, used for all its pixels
};

/// The derivatives of pixel p under the choice `which`.
const TexelDerivatives& derivatives_of(const FilterPixel& p, Derivatives which);

/// How a configuration's texels reach the frame.
enum class TexelPath {
    linear_light, ///< decoded to linear light, filtered there, encoded once (srgb.hpp)
    as_stored     ///< nearest only: the 8-bit texel fetched and written as it is stored
};

/// One filter configuration the chapter measures.
struct FilterConfig {
    std::string name;        ///< short, unique, no commas: "trilinear"
    FilterSettings settings; ///< the filter, wrap, probes
    Derivatives derivatives = Derivatives::per_pixel; ///< where the level comes from
    TexelPath path = TexelPath::linear_light;         ///< as_stored: nearest only
};

/// The configurations of the chapter. The first, "nearest", samples as a renderer does
/// (the 8-bit texel, no light involved) and is the time baseline; the second, "nearest
/// linear-light", picks the same texel through the linear-light chain every filter
/// uses (decode, encode), and gives the same pixels.
std::vector<FilterConfig> filter_configs();

/// Every pixel of the scene through the configuration, written into `frame`
/// (scene-sized) as 8-bit codes: what the benchmark times. Linear-light paths encode
/// with encode_linear_fast; the as-stored path copies the texel.
void filter_frame(Framebuffer& frame, const FilterScene& fs, const FilterConfig& config);

/// Every pixel of the scene (same order as fs.pixels) through the configuration, in
/// linear light (the as-stored path's texel decoded, so that errors compare alike).
std::vector<LinearTexel> filter_image(const FilterScene& fs, const FilterConfig& config);

/// The reference of every pixel (same order as fs.pixels): the mean of the texture over
/// the pixel's square, exact up to rounding. Each texel counts with the area of the
/// piece of the square it covers (the pieces are convex polygons: the perspective
/// mapping takes texel edges to straight lines). Throws Error when 1/w is not positive
/// over a pixel's square.
std::vector<LinearTexel> reference_image(const FilterScene& fs);

/// Where a sampled reference puts its n x n samples in a pixel.
enum class SamplePattern {
    grid,    ///< at the centres of the n x n cells (the book's first edition's reference)
    jittered ///< one uniformly random point in each cell, seeded per pixel: deterministic
};

/// An estimate of reference_image from per_side^2 samples of the nearest texel of level
/// 0 per pixel, for the pixels k with selected[k] (all when `selected` is empty); the
/// other pixels are 0.
std::vector<LinearTexel> sampled_reference_image(const FilterScene& fs, int per_side,
                                                 SamplePattern pattern,
                                                 const std::vector<bool>& selected = {});

/// Root mean square over pixels and the r, g, b channels of the difference between the
/// 8-bit sRGB codes of two images (same size), over the pixels k with selected[k] (all
/// when `selected` is empty). 0 when no pixel is selected.
double rms_code_error(const std::vector<LinearTexel>& image,
                      const std::vector<LinearTexel>& reference,
                      const std::vector<bool>& selected = {});

/// For every pixel of fs.pixels, whether it is minified: lambda >= 0 from the exact
/// derivatives, so that one pixel covers at least one texel along its longer side.
std::vector<bool> minified_pixels(const FilterScene& fs);

/// How far an approximation's level is from the exact one over a scene's pixels, both
/// clamped at 0 (every level below 0 samples level 0).
struct LevelErrors {
    double worst = 0.0;       ///< max |lambda(approximation) - lambda(exact)|
    double mean = 0.0;        ///< mean of the same over the pixels
    long long changed = 0;    ///< pixels whose mip-nearest level (lambda rounded) differs
    double worst_bound = 0.0; ///< per_span: the largest bound of @eq:level-bound used
};

/// The level errors of the approximation `which` against the exact derivatives.
LevelErrors level_errors(const FilterScene& fs, Derivatives which);

/// The image as a scene-sized frame (uncovered pixels black).
Framebuffer to_frame(const FilterScene& fs, const std::vector<LinearTexel>& image);

} // namespace exactpixels
