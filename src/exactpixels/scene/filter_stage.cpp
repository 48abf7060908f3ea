#include "exactpixels/scene/filter_stage.hpp"

#include "exactpixels/texture/level_of_detail.hpp"
#include "exactpixels/texture/mipmap.hpp"

namespace exactpixels {

//> choose-filter
/// The filter a triangle gets under the scene's `filter` key. `auto` looks at the
/// exact derivatives at the three corners (@eq:derivatives): where no corner is
/// minified (lambda <= 0 at each, @eq:level) bilinear on level 0 is all a pixel needs
/// and no mip chain is built; else trilinear, or anisotropic where a minified corner's
/// footprint is at least twice as long as it is wide (@eq:anisotropy).
Filter triangle_filter(SceneFilter wanted, const std::array<TexturedVertex, 3>& t) {
    switch (wanted) {
    case SceneFilter::nearest:
        return Filter::nearest;
    case SceneFilter::bilinear:
        return Filter::bilinear;
    case SceneFilter::trilinear:
        return Filter::trilinear;
    case SceneFilter::anisotropic:
        return Filter::anisotropic;
    case SceneFilter::automatic:
        break;
    }
    Filter chosen = Filter::bilinear;
    for (const TexturedVertex& corner : t) {
        const TexelDerivatives d = derivatives_at(t, corner.position);
        if (isotropic_level(d) > 0.0) {
            if (anisotropy(d, 8).probes >= 2) {
                return Filter::anisotropic;
            }
            chosen = Filter::trilinear;
        }
    }
    return chosen;
}
//< choose-filter

void prepare_chain(MeshContext& m, Filter filter) {
    if (filter != Filter::bilinear && !*m.full_chain) {
        *m.chain = build_mip_chain(*m.texture);
        *m.full_chain = true;
        m.report.mip_chains += 1;
    } else if (m.chain->levels.empty()) {
        m.chain->levels.push_back(decode_texture(*m.texture));
    }
}

//> filter-stage
int filter_span(const MipChain& chain, const FilterSettings& settings,
                const std::array<TexturedVertex, 3>& corners, Span s, const char* visible,
                Rgba8* row) {
    const double x = s.x_begin + 0.5, y = s.y + 0.5; // the first pixel's centre
    int filtered = 0;
    for (int k = 0; k < s.x_end - s.x_begin; ++k) {
        if (visible != nullptr && visible[k] == 0) {
            continue; // hidden: not filtered
        }
        filtered += 1;
        const auto [u, v] = projected_coordinates(corners, Point2{x + k, y});
        const TexCoord uv{u.p / u.q, v.p / v.q}; // q = 1/w > 0
        row[k] =
            encode_linear(sample_filtered(chain, uv, exact_derivatives(u, v), settings));
    }
    return filtered;
}
//< filter-stage

} // namespace exactpixels
