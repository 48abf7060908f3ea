#include "exactpixels/texture/level_of_detail.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

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

TexelDerivatives derivatives_per_span(const std::array<TexturedVertex, 3>& triangle,
                                      int y, int x_first, int x_last) {
    assert(x_first <= x_last);
    return derivatives_at(triangle, Point2{0.5 * (x_first + x_last) + 0.5, y + 0.5});
}

//> level-bound
double level_change_bound(const std::array<TexturedVertex, 3>& triangle, Point2 from,
                          Point2 at) {
    const auto [u, v] = projected_coordinates(triangle, from);
    const double dx = std::abs(at.x - from.x), dy = std::abs(at.y - from.y);
    const double q_at = u.q + u.dq.dx * (at.x - from.x) + u.dq.dy * (at.y - from.y);
    // The numerators' change per pixel: N_y grows by k per pixel in x, N_x by -k in y.
    const double k = std::hypot(u.dp.dy * u.dq.dx - u.dp.dx * u.dq.dy,
                                v.dp.dy * v.dq.dx - v.dp.dx * v.dq.dy);
    const double nx = std::hypot(numerator_x(u), numerator_x(v)),
                 ny = std::hypot(numerator_y(u), numerator_y(v));
    const double g = std::max(nx, ny);
    const double g_high = std::max(nx + k * dy, ny + k * dx);
    const double g_low = std::max(nx - k * dy, ny - k * dx);
    if (!(g_low > 0.0) || !(q_at > 0.0)) {
        return std::numeric_limits<double>::infinity();
    }
    return 2.0 * std::abs(std::log2(q_at / u.q)) +
           std::max(std::log2(g_high / g), std::log2(g / g_low));
}
//< level-bound

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

} // namespace exactpixels
