// rounding.cpp: choosing the texel rounding of a textured triangle (chapter 4).
#include "exactpixels/texture/rounding.hpp"

namespace exactpixels {

namespace {

/// 1/w, u/w and v/w at the three vertices, and their screen gradients.
struct ProjectedPlanes {
    CornerQuotients at_corners;
    Gradient<double> dq, dpu, dpv;
};

ProjectedPlanes projected_planes(const std::array<TexturedVertex, 3>& v,
                                 const CornerQuotients& q) {
    const std::array<glm::dvec2, 3> p{v[0].position, v[1].position, v[2].position};
    return {q, closed_form_gradient(p, q.one_w), closed_form_gradient(p, q.u_w),
            closed_form_gradient(p, q.v_w)};
}

/// The two coordinates at the screen point `at` from the planes.
std::array<ProjectedCoordinate<double>, 2> coordinates_at(const ProjectedPlanes& planes,
                                                         const std::array<TexturedVertex, 3>& v,
                                                         Point2 at) {
    const CornerQuotients& q = planes.at_corners;
    const Point2 d = at - v[0].position; // move from vertex 0 to `at`
    const ProjectedCoordinate<double> u0{q.u_w[0], q.one_w[0], planes.dpu, planes.dq};
    const ProjectedCoordinate<double> v0{q.v_w[0], q.one_w[0], planes.dpv, planes.dq};
    return {moved_by(u0, d.x, d.y), moved_by(v0, d.x, d.y)};
}

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
    return coordinates_at(projected_planes(v, corner_quotients(v)), v, at);
}

TexelRounding choose_rounding(const Gradient<double>& du, const Gradient<double>& dv) {
    return texel_rounding(choose_rule(du.dx, du.dy), choose_rule(dv.dx, dv.dy));
}

//> choose-rounding
TexelRounding choose_rounding(const std::array<TexturedVertex, 3>& v) {
    return choose_rounding(v, corner_quotients(v));
}

TexelRounding choose_rounding(const std::array<TexturedVertex, 3>& v,
                              const CornerQuotients& q) {
    const Point2 centroid = (v[0].position + v[1].position + v[2].position) / 3.0;
    const auto [u, t] = coordinates_at(projected_planes(v, q), v, centroid);
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
