#include "exactpixels/texture_mapper.hpp"

#include "exactpixels/error.hpp"
#include "exactpixels/fixed_point.hpp"
#include "exactpixels/gradients.hpp"
#include "exactpixels/rounding.hpp"
#include "exactpixels/scanline.hpp"
#include "exactpixels/span_mappers.hpp"

#include <fmt/format.h>

#include <cmath>

namespace exactpixels {

int real_texel_index(double u, std::int32_t bias) {
    const std::int32_t offset = bias - texel_scale / 2; // b' in floor((U + b') / D)
    if (offset >= 0) {
        return static_cast<int>(std::floor(u + double(offset) / texel_scale));
    }
    // For integer U, floor((U + b') / D) = ceil((U + b' + 1) / D) - 1; bias = D/2 - 1
    // makes this ceil(u) - 1, rule 2.
    return static_cast<int>(std::ceil(u + double(offset + 1) / texel_scale)) - 1;
}

TexelMap::TexelMap(int width_, int height_)
    : width(width_), height(height_),
      covered(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_),
              false),
      i(covered.size(), 0), j(covered.size(), 0), u(covered.size(), 0.0),
      v(covered.size(), 0.0) {
    if (width_ < 0 || height_ < 0) {
        throw Error(fmt::format("texel map: negative size {}x{}", width_, height_));
    }
}

void check_textured_triangle(const std::array<TexturedVertex, 3>& v,
                             const MapperSettings& settings) {
    const double position_limit = max_fixed_coordinate_px;
    const double uv_limit = settings.precision == Precision::fixed ? 16384.0 : 1e30;
    for (int k = 0; k < 3; ++k) {
        const TexturedVertex& p = v[static_cast<std::size_t>(k)];
        for (const double c : {p.position.x, p.position.y}) {
            if (!std::isfinite(c) || std::abs(c) > position_limit) {
                throw Error(
                    fmt::format("textured triangle: vertex {} has position {} px, "
                                "not finite or beyond +-2^20 px",
                                k, c));
            }
        }
        if (!std::isfinite(p.w) || !(p.w > 0.0)) {
            throw Error(fmt::format("textured triangle: vertex {} has depth w = {} "
                                    "(w must be finite and > 0)",
                                    k, p.w));
        }
        for (const double c : {p.uv.x, p.uv.y}) {
            if (!std::isfinite(c) || std::abs(c) >= uv_limit) {
                throw Error(fmt::format("textured triangle: vertex {} has texture "
                                        "coordinate {} texels (must be finite, and below "
                                        "2^14 in size for fixed point)",
                                        k, c));
            }
        }
    }
    if (settings.span < 2 || settings.span > 4096) {
        throw Error(fmt::format(
            "mapper settings: span = {} pixels (must be in [2, 4096])", settings.span));
    }
}

namespace {

/// A value linear over the screen: its value at `origin` and its gradient.
struct Plane {
    double at_origin;
    Gradient<double> g;
    double at(Point2 origin, double x, double y) const {
        return at_origin + g.dx * (x - origin.x) + g.dy * (y - origin.y);
    }
};

/// Runs the chosen Real mapper on one span.
template <class Real, class Emit>
void map_span_real(const PerspectiveSpan<Real>& ps, const AffineSpan<Real>& as,
                   const MapperSettings& settings, Emit&& emit) {
    switch (settings.kind) {
    case MapperKind::exact:
        map_span_exact(ps, emit);
        break;
    case MapperKind::affine:
        map_span_affine(as, emit);
        break;
    case MapperKind::subdivided:
        map_span_subdivided(ps, settings.span, emit);
        break;
    case MapperKind::quadratic:
        map_span_quadratic(ps, emit);
        break;
    case MapperKind::quadratic_subdivided:
        map_span_quadratic_subdivided(ps, settings.span, emit);
        break;
    }
}

/// Runs the chosen fixed-point mapper on one span.
template <class Emit>
void map_span_fixed(const PerspectiveSpan<double>& ps, const AffineSpan<double>& as,
                    const MapperSettings& settings, Emit&& emit) {
    switch (settings.kind) {
    case MapperKind::exact:
        map_span_exact_fixed(ps, emit);
        break;
    case MapperKind::affine:
        map_span_affine_fixed(as, emit);
        break;
    case MapperKind::subdivided:
        map_span_subdivided_fixed(ps, settings.span, emit);
        break;
    case MapperKind::quadratic:
        map_span_quadratic_fixed(ps, emit);
        break;
    case MapperKind::quadratic_subdivided:
        map_span_quadratic_subdivided_fixed(ps, settings.span, emit);
        break;
    }
}

//> for-each-textured-pixel
/// Rasterizes the triangle with chapter 1's fixed-point scanline spans and, for every
/// covered pixel, calls pixel(x, y, i, j, u, v): the texel indices the mapper picked
/// and the coordinate it computed (texels).
template <class PixelFn>
void for_each_textured_pixel(const std::array<TexturedVertex, 3>& v, Viewport viewport,
                             const MapperSettings& settings, PixelFn&& pixel) {
    check_textured_triangle(v, settings);
    std::array<FixedPoint2, 3> snapped{};
    std::array<Point2, 3> p{};
    for (std::size_t k = 0; k < 3; ++k) {
        snapped[k] = snap_to_subpixel(v[k].position);
        p[k] = to_pixels(snapped[k]); // the planes run through the snapped corners
    }
    // u/w, v/w and 1/w are linear in screen space (@eq:linear-in-screen); so are u and
    // v of the affine mapper, by assumption.
    const auto plane = [&](auto value) {
        const std::array<double, 3> c{value(v[0]), value(v[1]), value(v[2])};
        return Plane{c[0], gradient_closed_form<double>(p, c)};
    };
    const Plane u_w = plane([](const TexturedVertex& t) { return t.uv.x / t.w; });
    const Plane v_w = plane([](const TexturedVertex& t) { return t.uv.y / t.w; });
    const Plane one_w = plane([](const TexturedVertex& t) { return 1.0 / t.w; });
    const Plane u = plane([](const TexturedVertex& t) { return t.uv.x; });
    const Plane v_ = plane([](const TexturedVertex& t) { return t.uv.y; });
    scanline_spans(snapped, viewport, [&](Span s) {
        const double x = s.x_begin + 0.5, y = s.y + 0.5; // the first pixel's centre
        const TexelRounding r =
            settings.rounding_per_row ? choose_rounding_on_row(v, y) : settings.rounding;
        const int count = s.x_end - s.x_begin;
        const PerspectiveSpan<double> ps{u_w.at(p[0], x, y),
                                         v_w.at(p[0], x, y),
                                         one_w.at(p[0], x, y),
                                         u_w.g.dx,
                                         v_w.g.dx,
                                         one_w.g.dx,
                                         count};
        const AffineSpan<double> as{u.at(p[0], x, y), v_.at(p[0], x, y), u.g.dx, v_.g.dx,
                                    count};
        const auto real = [&](int k, auto uu, auto vv) {
            pixel(s.x_begin + k, s.y, real_texel_index(uu, r.u_bias),
                  real_texel_index(vv, r.v_bias), double(uu), double(vv));
        };
        switch (settings.precision) {
        case Precision::float32:
            map_span_real(converted<float>(ps), converted<float>(as), settings, real);
            break;
        case Precision::float64:
            map_span_real(ps, as, settings, real);
            break;
        case Precision::fixed:
            map_span_fixed(ps, as, settings, [&](int k, std::int32_t U, std::int32_t V) {
                pixel(s.x_begin + k, s.y, fixed_texel_index(U, r.u_bias),
                      fixed_texel_index(V, r.v_bias), double(U) / texel_scale,
                      double(V) / texel_scale);
            });
            break;
        }
    });
}
//< for-each-textured-pixel

} // namespace

void map_textured_triangle(TexelMap& target, const std::array<TexturedVertex, 3>& v,
                           const MapperSettings& settings) {
    for_each_textured_pixel(v, Viewport{target.width, target.height}, settings,
                            [&](int x, int y, int i, int j, double u, double vv) {
                                const std::size_t at =
                                    static_cast<std::size_t>(y) *
                                        static_cast<std::size_t>(target.width) +
                                    static_cast<std::size_t>(x);
                                target.covered[at] = true;
                                target.i[at] = i;
                                target.j[at] = j;
                                target.u[at] = u;
                                target.v[at] = vv;
                            });
}

//> draw-textured-triangle
void draw_textured_triangle(Framebuffer& target, const std::array<TexturedVertex, 3>& v,
                            const Texture& texture, const MapperSettings& settings) {
    for_each_textured_pixel(v, Viewport{target.width(), target.height()}, settings,
                            [&](int x, int y, int i, int j, double, double) {
                                target.at(x, y) =
                                    fetch_texel(texture, i, j, settings.wrap);
                            });
}
//< draw-textured-triangle

} // namespace exactpixels
