#include "exactpixels/texture/filter.hpp"

#include "exactpixels/texture/bilinear.hpp"
#include "exactpixels/texture/ewa.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace exactpixels {

namespace {

/// uv in texels of level 0, as texels of `level`.
TexCoord on_level(const MipChain& chain, const LinearImage& level, TexCoord uv) {
    const LinearImage& base = chain.levels.front();
    return {uv.x * level.width / base.width, uv.y * level.height / base.height};
}

/// The bilinear sample on level k; u is kept inside +-2^13 texels by repeat wrapping
/// first (it does not change the sample), so that 16.16 holds it.
LinearTexel bilinear_on(const MipChain& chain, int k, TexCoord uv, Wrap wrap) {
    const LinearImage& level = chain.levels[static_cast<std::size_t>(k)];
    TexCoord t = on_level(chain, level, uv);
    if (wrap == Wrap::repeat) {
        t.x -= level.width * std::floor(t.x / level.width);
        t.y -= level.height * std::floor(t.y / level.height);
    } else {
        t = glm::clamp(t, TexCoord{-1.0},
                       TexCoord{level.width + 1.0, level.height + 1.0});
    }
    return sample_bilinear(level, t, wrap);
}

int last_level(const MipChain& chain) {
    return static_cast<int>(chain.levels.size()) - 1;
}

} // namespace

std::string_view filter_name(Filter filter) {
    switch (filter) {
    case Filter::nearest:
        return "nearest";
    case Filter::bilinear:
        return "bilinear";
    case Filter::mip_nearest:
        return "mip-nearest";
    case Filter::trilinear:
        return "trilinear";
    case Filter::anisotropic:
        return "anisotropic";
    case Filter::ewa:
        return "ewa";
    }
    return "?";
}

//> trilinear
LinearTexel sample_trilinear(const MipChain& chain, TexCoord uv, double lambda,
                             Wrap wrap) {
    const double clamped = std::clamp(lambda, 0.0, double(last_level(chain)));
    const int k = static_cast<int>(std::floor(clamped));
    const double t = clamped - k; // 0 on level k, towards 1 on level k + 1
    const LinearTexel fine = bilinear_on(chain, k, uv, wrap);
    if (t == 0.0) {
        return fine;
    }
    return (1.0 - t) * fine + t * bilinear_on(chain, k + 1, uv, wrap);
}
//< trilinear

//> sample-filtered
LinearTexel sample_filtered(const MipChain& chain, TexCoord uv, const TexelDerivatives& d,
                            const FilterSettings& settings) {
    switch (settings.filter) {
    case Filter::nearest:
        return sample_nearest(chain.levels.front(), uv, settings.wrap);
    case Filter::bilinear:
        return bilinear_on(chain, 0, uv, settings.wrap);
    case Filter::mip_nearest: {
        const double lambda =
            std::clamp(isotropic_level(d), 0.0, double(last_level(chain)));
        const int k = static_cast<int>(std::floor(lambda + 0.5));
        const LinearImage& level = chain.levels[static_cast<std::size_t>(k)];
        return sample_nearest(level, on_level(chain, level, uv), settings.wrap);
    }
    case Filter::trilinear:
        return sample_trilinear(chain, uv, isotropic_level(d), settings.wrap);
    case Filter::anisotropic: {
        // N probes at the centres of N equal pieces of the longer side (@eq:anisotropy).
        const Anisotropy a = anisotropy(d, settings.max_probes);
        LinearTexel sum{0.0};
        for (int k = 0; k < a.probes; ++k) {
            const double offset = (k + 0.5) / a.probes - 0.5; // in (-1/2, 1/2)
            sum += sample_trilinear(chain, uv + offset * a.axis, a.level, settings.wrap);
        }
        return sum / double(a.probes);
    }
    case Filter::ewa:
        return sample_ewa(chain, uv, d, settings.wrap);
    }
    assert(false && "unknown filter");
    return LinearTexel{0.0};
}
//< sample-filtered

} // namespace exactpixels
