// rounding.cpp: choosing the texel rounding of a textured triangle (chapter 4).
#include "exactpixels/texture/rounding.hpp"

namespace exactpixels {

namespace {

/// The rule on the row through the point of u. When the x numerator is zero the row is
/// a line of constant u, and the sign of du/dy = numerator_y / q^2 is taken on the side
/// of the row where q > 0 (the visible side): numerator_y / q has that sign everywhere.
RoundingRule rule_on_row(const ProjectedCoordinate<double>& c) {
    const double n_y = numerator_y(c);
    return choose_rule(numerator_x(c), c.q < 0 ? -n_y : n_y);
}

} // namespace

std::array<ProjectedCoordinate<double>, 2>
projected_coordinates(const std::array<TexturedVertex, 3>& v, Point2 at) {
    return projected_coordinates(
        v, {v[0].uv.x / v[0].w, v[1].uv.x / v[1].w, v[2].uv.x / v[2].w},
        {v[0].uv.y / v[0].w, v[1].uv.y / v[1].w, v[2].uv.y / v[2].w},
        {1.0 / v[0].w, 1.0 / v[1].w, 1.0 / v[2].w}, at);
}

std::array<ProjectedCoordinate<double>, 2>
projected_coordinates(const std::array<TexturedVertex, 3>& v,
                      const std::array<double, 3>& u_w, const std::array<double, 3>& v_w,
                      const std::array<double, 3>& one_w, Point2 at) {
    // u/w, v/w and 1/w are planes (@eq:linear-in-screen): their gradients, and the move
    // from vertex 0 to `at`.
    const std::array<glm::dvec2, 3> p{v[0].position, v[1].position, v[2].position};
    const Gradient<double> dq = closed_form_gradient(p, one_w);
    const Gradient<double> dpu = closed_form_gradient(p, u_w);
    const Gradient<double> dpv = closed_form_gradient(p, v_w);
    const Point2 d = at - v[0].position;
    const ProjectedCoordinate<double> u0{u_w[0], one_w[0], dpu, dq};
    const ProjectedCoordinate<double> v0{v_w[0], one_w[0], dpv, dq};
    return {moved_by(u0, d.x, d.y), moved_by(v0, d.x, d.y)};
}

TexelRounding choose_rounding(const Gradient<double>& du, const Gradient<double>& dv) {
    return texel_rounding(choose_rule(du.dx, du.dy), choose_rule(dv.dx, dv.dy));
}

Point2 centroid(const std::array<TexturedVertex, 3>& v) {
    return (v[0].position + v[1].position + v[2].position) / 3.0;
}

//> choose-rounding
TexelRounding choose_rounding(const std::array<TexturedVertex, 3>& v) {
    const auto [u, t] = projected_coordinates(v, centroid(v));
    return texel_rounding(choose_rule(u), choose_rule(t));
}

TexelRounding choose_rounding(const std::array<TexturedVertex, 3>& v, MapperKind kind) {
    if (kind != MapperKind::affine) {
        return choose_rounding(v);
    }
    const std::array<glm::dvec2, 3> p{v[0].position, v[1].position, v[2].position};
    const Gradient<double> du =
        closed_form_gradient(p, {v[0].uv.x, v[1].uv.x, v[2].uv.x});
    const Gradient<double> dv =
        closed_form_gradient(p, {v[0].uv.y, v[1].uv.y, v[2].uv.y});
    return choose_rounding(du, dv);
}
//< choose-rounding

TexelRounding choose_rounding_on_row(const std::array<TexturedVertex, 3>& v, double y) {
    // Any point of the row will do (the x numerator is constant along it); vertex 0's
    // column keeps the arithmetic short.
    const auto [u, t] = projected_coordinates(v, Point2{v[0].position.x, y});
    return texel_rounding(rule_on_row(u), rule_on_row(t));
}

} // namespace exactpixels
