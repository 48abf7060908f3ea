#include "exactpixels/scene/corner_quotients.hpp"

#include <cstddef>
#include <tuple>

namespace exactpixels {

//> gradients-at-once
template <std::size_t N>
std::array<Gradient<double>, N>
closed_form_gradients(const std::array<Point2, 3>& p,
                      const std::array<std::array<double, 3>, N>& c) {
    static_assert(N >= 1 && N <= 4);
    // Two doubles at a time, baseline x86-64's width: a wider vector of four, split in
    // halves through the stack, stalled each reload of halves stored as scalars.
    using Lanes = double __attribute__((vector_size(16)));
    const auto at = [&](std::size_t i, std::size_t k) { return i < N ? c[i][k] : 0.0; };
    const double dx2 = p[1].x - p[0].x, dy2 = p[1].y - p[0].y;
    const double dx3 = p[2].x - p[0].x, dy3 = p[2].y - p[0].y;
    const double area2 = dx2 * dy3 - dx3 * dy2;
    std::array<Gradient<double>, N> g{};
    if (area2 == 0.0) {
        return g; // collinear or coincident corners: no plane, as the one-value form
    }
    for (std::size_t i = 0; i < N; i += 2) { // values i and i + 1 (a spare lane 0)
        const Lanes c0{at(i, 0), at(i + 1, 0)};
        const Lanes dc2 = Lanes{at(i, 1), at(i + 1, 1)} - c0;
        const Lanes dc3 = Lanes{at(i, 2), at(i + 1, 2)} - c0;
        const Lanes gx = (dc2 * dy3 - dc3 * dy2) / area2; // a scalar is in every lane
        const Lanes gy = (dc3 * dx2 - dc2 * dx3) / area2;
        g[i] = {gx[0], gy[0]};
        if (i + 1 < N) {
            g[i + 1] = {gx[1], gy[1]};
        }
    }
    return g;
}
//< gradients-at-once

template std::array<Gradient<double>, 2>
closed_form_gradients<2>(const std::array<Point2, 3>&,
                         const std::array<std::array<double, 3>, 2>&);
template std::array<Gradient<double>, 3>
closed_form_gradients<3>(const std::array<Point2, 3>&,
                         const std::array<std::array<double, 3>, 3>&);

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
    const auto [du_w, dv_w] = closed_form_gradients<2>(corners, {q.u_w, q.v_w});
    TexturePlanes planes{
        {corners[0], q.u_w[0], du_w}, {corners[0], q.v_w[0], dv_w}, one_w, {}, {}};
    if (affine) {
        std::tie(planes.u, planes.v) = affine_planes(corners, v);
    }
    return planes;
}

std::pair<ScreenPlane, ScreenPlane>
affine_planes(const std::array<Point2, 3>& corners,
              const std::array<TexturedVertex, 3>& v) {
    const std::array<double, 3> u{v[0].uv.x, v[1].uv.x, v[2].uv.x},
        t{v[0].uv.y, v[1].uv.y, v[2].uv.y};
    const auto [du, dt] = closed_form_gradients<2>(corners, {u, t});
    return {{corners[0], u[0], du}, {corners[0], t[0], dt}};
}

TexelRounding choose_affine_rounding(const std::array<TexturedVertex, 3>& v) {
    // choose_rounding(v, MapperKind::affine): the gradients of u and v over the
    // unsnapped corners.
    const std::array<Point2, 3> p{v[0].position, v[1].position, v[2].position};
    const auto [du, dv] = closed_form_gradients<2>(
        p, {std::array<double, 3>{v[0].uv.x, v[1].uv.x, v[2].uv.x},
            std::array<double, 3>{v[0].uv.y, v[1].uv.y, v[2].uv.y}});
    return choose_rounding(du, dv);
}

TexelRounding choose_rounding(const std::array<TexturedVertex, 3>& v,
                              const CornerQuotients& q) {
    // projected_coordinates(v, q.u_w, q.v_w, q.one_w, centroid(v)), its three
    // gradients at once.
    const std::array<Point2, 3> p{v[0].position, v[1].position, v[2].position};
    const auto [dq, du_w, dv_w] = closed_form_gradients<3>(p, {q.one_w, q.u_w, q.v_w});
    const Point2 d = centroid(v) - v[0].position;
    const ProjectedCoordinate<double> u{q.u_w[0], q.one_w[0], du_w, dq},
        t{q.v_w[0], q.one_w[0], dv_w, dq};
    return texel_rounding(choose_rule(moved_by(u, d.x, d.y)),
                          choose_rule(moved_by(t, d.x, d.y)));
}

} // namespace exactpixels
