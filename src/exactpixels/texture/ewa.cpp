#include "exactpixels/texture/ewa.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace exactpixels {

//> ewa
LinearTexel sample_ewa(const MipChain& chain, TexCoord uv, const TexelDerivatives& d,
                       Wrap wrap) {
    // The level: the shorter side one to two texels there, the longer at most
    // ewa_max_major texels.
    const auto [side_x, side_y] = footprint_sides(d);
    const double minor = std::min(side_x, side_y), major = std::max(side_x, side_y);
    const int last = static_cast<int>(chain.levels.size()) - 1;
    const double wanted = std::max(minor > 0.0 ? std::floor(std::log2(minor)) : 0.0,
                                   std::ceil(std::log2(major / ewa_max_major)));
    const int k = static_cast<int>(std::clamp(wanted, 0.0, double(last)));
    const LinearImage& base = chain.levels.front();
    const LinearImage& level = chain.levels[static_cast<std::size_t>(k)];
    const double sx = double(level.width) / base.width,
                 sy = double(level.height) / base.height;
    // The covariance [a b; b c] of the footprint's Gaussian in texels of level k.
    const double ux = d.du_dx * sx, uy = d.du_dy * sx, vx = d.dv_dx * sy,
                 vy = d.dv_dy * sy;
    const double a = ewa_pixel_variance * (ux * ux + uy * uy) + ewa_texel_variance;
    const double b = ewa_pixel_variance * (ux * vx + uy * vy);
    const double c = ewa_pixel_variance * (vx * vx + vy * vy) + ewa_texel_variance;
    const double det = a * c - b * b; // > 0: both variances include the texel's
    const double r2 = ewa_cutoff * ewa_cutoff;
    const double cu = uv.x * sx, cv = uv.y * sy; // the centre on level k
    // Texel (i, j) has its centre at (i + 1/2, j + 1/2); rows within R sqrt(c) of cv.
    const double reach_v = ewa_cutoff * std::sqrt(c);
    LinearTexel sum{0.0};
    double weights = 0.0;
    const int j0 = static_cast<int>(std::ceil(cv - reach_v - 0.5)),
              j1 = static_cast<int>(std::floor(cv + reach_v - 0.5));
    for (int j = j0; j <= j1; ++j) {
        const double dv = j + 0.5 - cv;
        const double room = r2 * c - dv * dv; // the row's chord, from Q(du, dv) <= R^2
        if (room < 0.0) {
            continue;
        }
        const double mid = cu + b / c * dv, half = std::sqrt(det * room) / c;
        const int i0 = static_cast<int>(std::ceil(mid - half - 0.5)),
                  i1 = static_cast<int>(std::floor(mid + half - 0.5));
        for (int i = i0; i <= i1; ++i) {
            const double du = i + 0.5 - cu;
            const double q = (c * du * du - 2.0 * b * du * dv + a * dv * dv) / det;
            const double w = std::exp(-0.5 * q);
            sum += w * level.at(wrap_index(i, level.width, wrap),
                                wrap_index(j, level.height, wrap));
            weights += w;
        }
    }
    // The nearest texel centre is at most sqrt(1/2) texel away, inside the cutoff.
    assert(weights > 0.0);
    return sum / weights;
}
//< ewa

} // namespace exactpixels
