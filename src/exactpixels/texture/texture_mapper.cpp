#include "exactpixels/texture/texture_mapper.hpp"

#include "exactpixels/base/error.hpp"
#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/raster/scanline.hpp"

#include <fmt/format.h>

#include <cmath>

namespace exactpixels {

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
    const double uv_limit = texture_coordinate_limit(settings.precision);
    const int piece = settings.mapper.piece;
    for (int k = 0; k < 3; ++k) {
        const TexturedVertex& p = v[static_cast<std::size_t>(k)];
        try {
            check_pixel_range(p.position.x);
            check_pixel_range(p.position.y);
        } catch (const Error& error) {
            throw Error(fmt::format("textured triangle: vertex {}: {}", k, error.what()));
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
    if (piece < min_mapper_piece || piece > max_mapper_piece) {
        throw Error(
            fmt::format("mapper settings: piece = {} pixels (must be in [{}, {}])", piece,
                        min_mapper_piece, max_mapper_piece));
    }
}

TexturePlanes texture_planes(const std::array<Point2, 3>& corners,
                             const std::array<TexturedVertex, 3>& v, bool affine) {
    // u/w, v/w and 1/w are linear in screen space (@eq:linear-in-screen); so are u and
    // v of the affine mapper, by assumption.
    TexturePlanes planes{
        plane_through(corners,
                      {v[0].uv.x / v[0].w, v[1].uv.x / v[1].w, v[2].uv.x / v[2].w}),
        plane_through(corners,
                      {v[0].uv.y / v[0].w, v[1].uv.y / v[1].w, v[2].uv.y / v[2].w}),
        plane_through(corners, {1.0 / v[0].w, 1.0 / v[1].w, 1.0 / v[2].w}),
        {},
        {}};
    if (affine) {
        planes.u = plane_through(corners, {v[0].uv.x, v[1].uv.x, v[2].uv.x});
        planes.v = plane_through(corners, {v[0].uv.y, v[1].uv.y, v[2].uv.y});
    }
    return planes;
}

namespace {

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
    const TexturePlanes planes = texture_planes(p, v);
    scanline_spans(snapped, viewport, [&](Span s) {
        const TexelRounding r = settings.row_rounding
                                    ? settings.row_rounding(v, s.y + 0.5)
                                    : settings.rounding;
        map_span(settings.mapper, settings.precision, r, perspective_span(planes, s),
                 affine_span(planes, s), [&](int k, int i, int j, double u, double vv) {
                     pixel(s.x_begin + k, s.y, i, j, u, vv);
                 });
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
