#include "exactpixels/scene/corner_quotients.hpp"

#include <cstddef>

namespace exactpixels {

CornerQuotients corner_quotients(const std::array<TexturedVertex, 3>& v) {
    CornerQuotients q{};
    for (std::size_t k = 0; k < 3; ++k) {
        q.u_w[k] = v[k].uv.x / v[k].w;
        q.v_w[k] = v[k].uv.y / v[k].w;
        q.one_w[k] = 1.0 / v[k].w;
    }
    return q;
}

TexturePlanes texture_planes(const std::array<Point2, 3>& corners,
                             const std::array<TexturedVertex, 3>& v,
                             const CornerQuotients& q, const ScreenPlane& one_w,
                             bool affine) {
    TexturePlanes planes{
        plane_through(corners, q.u_w), plane_through(corners, q.v_w), one_w, {}, {}};
    if (affine) {
        planes.u = plane_through(corners, {v[0].uv.x, v[1].uv.x, v[2].uv.x});
        planes.v = plane_through(corners, {v[0].uv.y, v[1].uv.y, v[2].uv.y});
    }
    return planes;
}

TexelRounding choose_rounding(const std::array<TexturedVertex, 3>& v,
                              const CornerQuotients& q) {
    const auto [u, t] = projected_coordinates(v, q.u_w, q.v_w, q.one_w, centroid(v));
    return texel_rounding(choose_rule(u), choose_rule(t));
}

} // namespace exactpixels
