#include "exactpixels/texture/level_of_detail.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace exactpixels {

TexelDerivatives derivatives_at(const std::array<TexturedVertex, 3>& triangle,
                                Point2 at) {
    const auto [u, v] = projected_coordinates(triangle, at);
    return exact_derivatives(u, v);
}

TexelDerivatives derivatives_per_triangle(const std::array<TexturedVertex, 3>& triangle) {
    const Point2 centroid =
        (triangle[0].position + triangle[1].position + triangle[2].position) / 3.0;
    return derivatives_at(triangle, centroid);
}

std::array<double, 2> footprint_sides(const TexelDerivatives& d) {
    return {std::hypot(d.du_dx, d.dv_dx), std::hypot(d.du_dy, d.dv_dy)};
}

//> isotropic-level
double isotropic_level(const TexelDerivatives& d) {
    const auto [side_x, side_y] = footprint_sides(d);
    const double rho = std::max(side_x, side_y); // texels per pixel, the longer side
    return rho > 0.0 ? std::log2(rho) : -1000.0;
}
//< isotropic-level

//> anisotropy
Anisotropy anisotropy(const TexelDerivatives& d, int max_probes) {
    assert(max_probes >= 1);
    const auto [side_x, side_y] = footprint_sides(d);
    const double longer = std::max(side_x, side_y), shorter = std::min(side_x, side_y);
    if (longer <= 0.0) {
        return {1, -1000.0, {0.0, 0.0}};
    }
    const double ratio = shorter > 0.0 ? longer / shorter : double(max_probes);
    const int n = std::clamp(static_cast<int>(std::ceil(ratio)), 1, max_probes);
    const glm::dvec2 axis =
        side_x >= side_y ? glm::dvec2{d.du_dx, d.dv_dx} : glm::dvec2{d.du_dy, d.dv_dy};
    return {n, std::log2(longer / n), axis};
}
//< anisotropy

} // namespace exactpixels
