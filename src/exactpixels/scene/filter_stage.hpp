// filter_stage.hpp: chapter 8's filter stage in chapter 7's renderer: the filter a
// triangle gets under the scene's `filter` key, the mip chain made ready for it, and the
// stage on one span, which samples the filtered texture at each visible pixel.
//
// Usage (in the span loop, after the texture stage):
//   const Filter filter = triangle_filter(scene.options.filter, snapped_corners);
//   prepare_chain(m, filter);
//   const int filtered = filter_span(*m.chain, {.filter = filter, .wrap = mesh.wrap},
//                                    snapped_corners, span, visible, row);
#pragma once

#include "exactpixels/scene/span_stages.hpp"
#include "exactpixels/texture/filter.hpp"

#include <array>

namespace exactpixels {

/// The filter a triangle with corners `t` gets under the scene's `filter` key.
Filter triangle_filter(SceneFilter wanted, const std::array<TexturedVertex, 3>& t);

/// Makes the mesh's chain ready for `filter`: level 0 for bilinear, every level (built
/// once per texture, limits checked by build_mip_chain) for the mip filters.
void prepare_chain(MeshContext& m, Filter filter);

/// The filter stage on span `s` of the triangle with (snapped) corners `corners`: writes
/// row[k] for each pixel k seen (every pixel when `visible` is null, else where
/// visible[k] != 0) and returns how many it filtered (3 divides each).
int filter_span(const MipChain& chain, const FilterSettings& settings,
                const std::array<TexturedVertex, 3>& corners, Span s, const char* visible,
                Rgba8* row);

} // namespace exactpixels
