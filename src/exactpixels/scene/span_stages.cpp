#include "exactpixels/scene/span_stages.hpp"

#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/raster/scanline.hpp"
#include "exactpixels/raster/screen_plane.hpp"
#include "exactpixels/scene/camera.hpp"
#include "exactpixels/scene/filter_stage.hpp"
#include "exactpixels/texture/perspective.hpp"
#include "exactpixels/texture/rounding.hpp"

#include <array>

namespace exactpixels {

namespace {

Rgba8 multiply(Rgba8 texel, const Colour& c) {
    return to_rgba8(
        Colour{texel.r / 255.0 * c.r, texel.g / 255.0 * c.g, texel.b / 255.0 * c.b});
}

/// What the texture stage sets up once per triangle.
struct TextureSetup {
    bool affine_exact = false; ///< the depths are equal: affine is exact (and free)
    /// u/w, v/w, 1/w; u and v where affine runs. Not zeroed first: texture_setup sets
    /// what is read, and zeroing the five planes cost the big torus's frame 2 % of its
    /// time (perf).
    TexturePlanes planes;
    TexelRounding perspective_rounding{}, affine_rounding{}; ///< chapter 4's choice
};

/// Throws Error when a textured triangle with corners `tv` leaves the ranges of chapter
/// 3's mappers as the scene sets them.
void check_mapper_ranges(const MeshContext& m, const std::array<TexturedVertex, 3>& tv) {
    const RenderOptions& options = m.scene.options;
    check_textured_triangle(tv, MapperSettings{.mapper = options.mapper.mapper,
                                               .precision = options.precision,
                                               .rounding = {},
                                               .wrap = m.mesh.wrap});
}

/// The texture stage's setup of a textured triangle whose corners `tv` snap to `p`
/// (its planes run through the snapped corners), once check_mapper_ranges has passed.
/// `one_w` is the depth stage's plane where it stores 1/w (the same plane: the corners'
/// 1/w through p), or null; the planes and the rounding share one divide per quotient.
TextureSetup texture_setup(const MeshContext& m, const std::array<TexturedVertex, 3>& tv,
                           const std::array<Point2, 3>& p, const ScreenPlane* one_w) {
    TextureSetup setup;
    setup.affine_exact =
        constant_depth(tv[0].w, tv[1].w, tv[2].w); // @eq:scene-constant-w
    const RenderOptions& options = m.scene.options;
    // The spans use affine on every span or on none (auto never picks affine where
    // w varies): its planes and rounding only where it runs.
    const bool affine_only = options.mapper.automatic
                                 ? setup.affine_exact
                                 : options.mapper.mapper.kind == MapperKind::affine;
    const CornerQuotients q = corner_quotients(tv);
    setup.planes = texture_planes(
        p, tv, q, one_w != nullptr ? *one_w : plane_through(p, q.one_w), affine_only);
    if (options.rounding) { // chapter 4: ties go right, or down
        if (affine_only) {
            setup.affine_rounding = choose_rounding(tv, MapperKind::affine);
        } else {
            setup.perspective_rounding = choose_rounding(tv, q);
        }
    }
    return setup;
}

/// The mapper a span gets: the scene's, affine where the depth is constant (exact there
/// and no divide), or auto's choice within the budget (counted in the report).
Mapper span_mapper(MeshContext& m, const TextureSetup& setup,
                   const PerspectiveSpan<double>& ps) {
    const MapperChoice& wanted = m.scene.options.mapper;
    if (setup.affine_exact &&
        (wanted.automatic || wanted.mapper.kind == MapperKind::affine)) {
        return {MapperKind::affine, 2};
    }
    if (!wanted.automatic) {
        return wanted.mapper;
    }
    const AutoChoice choice = choose_span_mapper(ps, m.scene.options.budget);
    m.report.auto_choice.spans += 1;
    m.report.auto_choice.pixels += ps.count;
    m.report.auto_choice.divides += choice.divides;
    return choice.mapper;
}

/// Counts a span of `count` pixels mapped by `mapper` into the texture stage and the
/// mapper's counter (its triangle once per triangle: `used` remembers), with `seconds`.
void count_mapped_span(RenderReport& report, Mapper mapper, int count, double seconds,
                       std::array<bool, 5>& used) {
    const auto kind = static_cast<std::size_t>(mapper.kind);
    StageCounter& counter = report.mappers[kind];
    const long long divides = mapper_divides(mapper, count);
    counter.triangles += used[kind] ? 0 : 1;
    used[kind] = true;
    counter.spans += 1;
    counter.pixels += count;
    counter.divides += divides;
    counter.seconds += seconds;
    report.texture.spans += 1;
    report.texture.pixels += count;
    report.texture.divides += divides;
    report.texture.seconds += seconds;
}

//> depth-stage
/// The depth stage on one span: every pixel's nearness (the triangle's plane at the pixel
/// centre, rounded to a key) is tested and, where it passes, written; visible[k] says
/// which passed. Counts the span and its hidden pixels into the report and returns how
/// many pixels are seen: a span with none is not shaded at all. (Always inlined: both
/// drawing paths call it on every span, and called, it cost the big torus's frame 8M
/// instructions, 4 %.)
[[gnu::always_inline]] inline int
depth_test_span(MeshContext& m, const ScreenPlane& nearness, Span s, char* visible) {
    const int count = s.x_end - s.x_begin;
    const double x = s.x_begin + 0.5, y = s.y + 0.5; // the first pixel's centre
    int shown = 0;
    for (int k = 0; k < count; ++k) {
        const float q = nearness_key(nearness.at(x + k, y));
        const bool seen = m.depth->test_and_write(s.x_begin + k, s.y, q);
        visible[k] = seen;
        shown += seen;
    }
    m.report.depth.spans += 1;
    m.report.depth.pixels += count;
    m.report.hidden.spans += shown < count;
    m.report.hidden.pixels += count - shown;
    return shown;
}
//< depth-stage

//> draw-triangle
/// Rasterizes one projected triangle and runs the mesh's stages on its spans.
void draw_triangle(MeshContext& m, const ScreenTriangle& triangle) {
    const std::array<TexturedVertex, 3>& tv = triangle.corners;
    const std::array<Colour, 3>& colours = triangle.colours;
    RenderReport& report = m.report;
    const Clock::time_point start = m.clock.now();
    std::array<FixedPoint2, 3> snapped{};
    std::array<Point2, 3> p{};
    for (std::size_t k = 0; k < 3; ++k) {
        snapped[k] = snap_in_range(tv[k].position); // Error beyond +-2^20 px
        p[k] = to_pixels(snapped[k]); // the planes run through the snapped corners
    }
    const RenderOptions& options = m.scene.options;
    // Texture stage setup: only for textured meshes.
    TextureSetup texture{};
    if (m.stages.texture) {
        check_mapper_ranges(m, tv);
        texture = texture_setup(m, tv, p, nullptr);
        report.texture.triangles += 1;
    }
    // Filter stage setup: only for textured meshes of scenes that ask for a filter.
    std::array<TexturedVertex, 3> snapped_corners = tv; // the corners the planes use
    for (std::size_t k = 0; k < 3; ++k) {
        snapped_corners[k].position = p[k];
    }
    Filter filter = Filter::nearest;
    if (m.stages.texture && options.filter != SceneFilter::nearest) {
        filter = triangle_filter(options.filter, snapped_corners);
        prepare_chain(m, filter);
        report.filter.triangles += 1;
        report.filter_triangles[filter == Filter::bilinear    ? 0
                                : filter == Filter::trilinear ? 1
                                                              : 2] += 1;
    }
    // Colour stage setup: only for meshes with vertex colours.
    std::array<ScreenPlane, 3> rgb{}; // c, or c/w when perspective-correct
    ScreenPlane one_w{};
    if (m.stages.colour) {
        const bool corrected = m.colour_perspective;
        for (int c = 0; c < 3; ++c) {
            std::array<double, 3> value{};
            for (std::size_t k = 0; k < 3; ++k) {
                value[k] = corrected ? colours[k][c] / tv[k].w : colours[k][c];
            }
            rgb[static_cast<std::size_t>(c)] = plane_through(p, value);
        }
        if (corrected) {
            one_w = plane_through(p, {1.0 / tv[0].w, 1.0 / tv[1].w, 1.0 / tv[2].w});
            report.colour_perspective.triangles += 1;
        }
        report.colour.triangles += 1;
    }
    // Depth stage setup: only when the scene runs one. Nearness is linear on screen.
    ScreenPlane nearness{};
    if (m.depth != nullptr) {
        nearness = plane_through(p, triangle.nearness);
        report.depth.triangles += 1;
    }
    // Lighting stage setup, per pixel only: the view-space point and normal as a/w,
    // linear on screen, and 1/w (chapter 3's u/w over 1/w).
    std::array<ScreenPlane, 3> point_w{}, normal_w{};
    ScreenPlane lit_w{};
    if (m.lights != nullptr) {
        const std::array<double, 3> q{1.0 / tv[0].w, 1.0 / tv[1].w, 1.0 / tv[2].w};
        for (int c = 0; c < 3; ++c) {
            std::array<double, 3> a{}, n{};
            for (std::size_t k = 0; k < 3; ++k) {
                a[k] = triangle.points[k][c] * q[k];
                n[k] = triangle.normals[k][c] * q[k];
            }
            point_w[static_cast<std::size_t>(c)] = plane_through(p, a);
            normal_w[static_cast<std::size_t>(c)] = plane_through(p, n);
        }
        lit_w = plane_through(p, q);
        report.lighting.triangles += 1;
    }
    const Rgba8 flat = m.flat;
    if (!m.stages.texture && !m.stages.colour) {
        report.flat.triangles += 1;
    }
    std::array<bool, 5> mapper_used{};
    double shading_seconds = 0.0;
    report.raster.triangles += 1;

    scanline_spans(snapped, Viewport{m.frame.width(), m.frame.height()}, [&](Span s) {
        const int count = s.x_end - s.x_begin;
        const double x = s.x_begin + 0.5, y = s.y + 0.5; // the first pixel's centre
        report.raster.spans += 1;
        report.raster.pixels += count;
        if (m.depth != nullptr) { // test every pixel first: a hidden span is not shaded
            const Clock::time_point t0 = m.clock.now();
            m.visible.resize(static_cast<std::size_t>(count));
            const int shown = depth_test_span(m, nearness, s, m.visible.data());
            const double spent = m.clock.since(t0);
            report.depth.seconds += spent;
            shading_seconds += spent;
            if (shown == 0) {
                return;
            }
        }
        const auto seen = [&](int k) {
            return m.depth == nullptr || m.visible[static_cast<std::size_t>(k)] != 0;
        };
        m.row.assign(static_cast<std::size_t>(count), flat);
        //> texture-stage
        if (m.stages.texture) {
            const Clock::time_point t0 = m.clock.now();
            const PerspectiveSpan<double> ps = perspective_span(texture.planes, s);
            const Mapper mapper = span_mapper(m, texture, ps); // auto: within the budget
            const TexelRounding r = mapper.kind == MapperKind::affine
                                        ? texture.affine_rounding
                                        : texture.perspective_rounding;
            const AffineSpan<double> as = mapper.kind == MapperKind::affine
                                              ? affine_span(texture.planes, s)
                                              : AffineSpan<double>{};
            map_span(mapper, options.precision, r, ps, as,
                     [&](int k, int i, int j, double uu, double vv) {
                         m.row[static_cast<std::size_t>(k)] =
                             m.masked_fetch ? fetch_texel_masked(*m.texture, i, j)
                                            : fetch_texel(*m.texture, i, j, m.mesh.wrap);
                         if (m.coordinates != nullptr && seen(k)) {
                             const std::size_t at =
                                 static_cast<std::size_t>(s.y) *
                                     static_cast<std::size_t>(m.frame.width()) +
                                 static_cast<std::size_t>(s.x_begin + k);
                             m.coordinates->covered[at] = true;
                             m.coordinates->i[at] = i;
                             m.coordinates->j[at] = j;
                             m.coordinates->u[at] = uu;
                             m.coordinates->v[at] = vv;
                         }
                     });
            if (filter !=
                Filter::nearest) { // chapter 8's filter stage (filter_stage.cpp)
                const Clock::time_point f0 = m.clock.now();
                const int filtered = filter_span(
                    *m.chain, {.filter = filter, .wrap = m.mesh.wrap}, snapped_corners, s,
                    m.depth != nullptr ? m.visible.data() : nullptr, m.row.data());
                report.filter.spans += 1;
                report.filter.pixels += filtered;
                report.filter.divides += 3LL * filtered; // u, v and 1/q^2
                report.filter.seconds += m.clock.since(f0);
            }
            const double spent = m.clock.since(t0);
            count_mapped_span(report, mapper, count, spent, mapper_used);
            shading_seconds += spent;
        }
        //< texture-stage
        //> colour-stage
        if (m.stages.colour) { // colours are linear on screen: one add per channel
            const Clock::time_point t0 = m.clock.now();
            Colour c{rgb[0].at(x, y), rgb[1].at(x, y), rgb[2].at(x, y)};
            const Colour dc{rgb[0].g.dx, rgb[1].g.dx, rgb[2].g.dx};
            double q = one_w.at(x, y); // perspective: 1/w, as chapter 3's exact mapper
            for (Rgba8& pixel : m.row) {
                const Colour shade = m.colour_perspective ? c * (1.0 / q) : c;
                pixel = m.stages.texture ? multiply(pixel, shade) : to_rgba8(shade);
                c += dc;
                q += one_w.g.dx;
            }
            if (m.colour_perspective) {
                report.colour_perspective.spans += 1;
                report.colour_perspective.pixels += count;
                report.colour_perspective.divides += count;
            }
            report.colour.spans += 1;
            report.colour.pixels += count;
            const double spent = m.clock.since(t0);
            report.colour.seconds += spent;
            shading_seconds += spent;
        } else if (m.stages.texture && m.stages.tint) {
            for (Rgba8& pixel : m.row) {
                pixel = multiply(pixel, m.mesh.colour);
            }
        } else if (!m.stages.texture) {
            report.flat.spans += 1;
            report.flat.pixels += count;
        }
        //< colour-stage
        //> lighting-stage
        if (m.lights != nullptr) { // Phong: light the pixel the stages above made
            const Clock::time_point t0 = m.clock.now();
            long long lit = 0;
            for (int k = 0; k < count; ++k) {
                if (!seen(k)) {
                    continue;
                }
                const double px = x + k;
                const double w = 1.0 / lit_w.at(px, y); // the one divide per pixel
                const glm::dvec3 point{point_w[0].at(px, y) * w, point_w[1].at(px, y) * w,
                                       point_w[2].at(px, y) * w};
                // n/w is n scaled by 1/w > 0: renormalising removes the scale, so the
                // normal needs no divide of its own.
                const glm::dvec3 normal = glm::normalize(glm::dvec3{
                    normal_w[0].at(px, y), normal_w[1].at(px, y), normal_w[2].at(px, y)});
                Rgba8& pixel = m.row[static_cast<std::size_t>(k)];
                const Colour base{pixel.r / 255.0, pixel.g / 255.0, pixel.b / 255.0};
                pixel =
                    to_rgba8(light_colour(*m.lights, options.ambient, base, m.material,
                                          point, normal, to_eye(m.scene, point)));
                lit += 1;
            }
            report.lighting.spans += 1;
            report.lighting.pixels += lit;
            report.lighting.divides += lit;
            const double spent = m.clock.since(t0);
            report.lighting.seconds += spent;
            shading_seconds += spent;
        }
        //< lighting-stage
        for (int k = 0; k < count; ++k) {
            if (seen(k)) {
                m.frame.at(s.x_begin + k, s.y) = m.row[static_cast<std::size_t>(k)];
            }
        }
        if (m.coordinates != nullptr && !m.stages.texture) {
            for (int k = 0; k < count; ++k) { // an untextured pixel now
                if (!seen(k)) {
                    continue;
                }
                m.coordinates->covered[static_cast<std::size_t>(s.y) *
                                           static_cast<std::size_t>(m.frame.width()) +
                                       static_cast<std::size_t>(s.x_begin + k)] = false;
            }
        }
    });
    report.raster.seconds += m.clock.since(start) - shading_seconds;
}
//< draw-triangle

/// Whether draw_triangle_lean can draw the mesh's triangles: its only stages are the
/// texture stage with nearest texels (or the flat colour) and the depth stage, and no
/// texel coordinates are recorded.
bool lean_drawable(const MeshContext& m) {
    return !m.stages.colour && !m.stages.tint && m.lights == nullptr &&
           m.coordinates == nullptr &&
           (!m.stages.texture || m.scene.options.filter == SceneFilter::nearest);
}

//> draw-triangle-lean
/// draw_triangle for a mesh lean_drawable accepts (FastPaths::lean_spans): the same
/// setup, depth test, mapper choice and mapper on each span, in the same order and
/// arithmetic, with the counts and the sampled times of the plain path; what it leaves
/// out is the row of shaded pixels that the other stages would work on. A visible pixel
/// goes straight from the mapper (or the flat colour) to the frame, a hidden pixel's
/// texel is not read, and the planes are set up only when a span needs them: not at all
/// for a triangle that covers no pixel centre, or (the texture's) whose every pixel the
/// depth test hides.
void draw_triangle_lean(MeshContext& m, const ScreenTriangle& triangle) {
    const std::array<TexturedVertex, 3>& tv = triangle.corners;
    RenderReport& report = m.report;
    const Clock::time_point start = m.clock.now();
    std::array<FixedPoint2, 3> snapped{};
    std::array<Point2, 3> p{};
    for (std::size_t k = 0; k < 3; ++k) {
        snapped[k] = snap_in_range(tv[k].position); // Error beyond +-2^20 px
        p[k] = to_pixels(snapped[k]);
    }
    if (m.stages.texture) {
        check_mapper_ranges(m, tv); // its Error, if any, before the first pixel
        report.texture.triangles += 1;
    } else {
        report.flat.triangles += 1;
    }
    if (m.depth != nullptr) {
        report.depth.triangles += 1;
    }
    // The planes wait for the first span (a tiny triangle may cover no pixel centre),
    // the texture's for the first span the depth test leaves any pixel of.
    ScreenPlane nearness{};
    bool nearness_ready = false;
    // Under perspective the depth stage's plane is the texture's 1/w plane: set up once.
    const bool depth_one_w =
        m.depth != nullptr && m.scene.camera.projection == Projection::perspective;
    TextureSetup texture; // its planes not zeroed (TextureSetup::planes)
    bool texture_ready = false;
    std::array<bool, 5> mapper_used{};
    double shading_seconds = 0.0;
    report.raster.triangles += 1;
    const int width = m.frame.width();
    m.visible.resize(static_cast<std::size_t>(width)); // every entry written before read
    char* const visible = m.visible.data();
    scanline_spans(snapped, Viewport{width, m.frame.height()}, [&](Span s) {
        const int count = s.x_end - s.x_begin;
        report.raster.spans += 1;
        report.raster.pixels += count;
        int shown = count;
        if (m.depth != nullptr) {
            if (!nearness_ready) {
                nearness = plane_through(p, triangle.nearness);
                nearness_ready = true;
            }
            const Clock::time_point t0 = m.clock.now();
            shown = depth_test_span(m, nearness, s, visible);
            const double spent = m.clock.since(t0);
            report.depth.seconds += spent;
            shading_seconds += spent;
            if (shown == 0) {
                return;
            }
        }
        Rgba8* const out = &m.frame.at(s.x_begin, s.y); // the span's pixels in a row
        const bool all_shown = shown == count;
        if (!m.stages.texture) {
            for (int k = 0; k < count; ++k) {
                if (all_shown || visible[k] != 0) {
                    out[k] = m.flat;
                }
            }
            report.flat.spans += 1;
            report.flat.pixels += count;
            return;
        }
        if (!texture_ready) { // the rasterizer's time, as on the plain path
            texture = texture_setup(m, tv, p, depth_one_w ? &nearness : nullptr);
            texture_ready = true;
        }
        const Clock::time_point t0 = m.clock.now();
        const PerspectiveSpan<double> ps = perspective_span(texture.planes, s);
        const Mapper mapper = span_mapper(m, texture, ps);
        const TexelRounding r = mapper.kind == MapperKind::affine
                                    ? texture.affine_rounding
                                    : texture.perspective_rounding;
        const AffineSpan<double> as = mapper.kind == MapperKind::affine
                                          ? affine_span(texture.planes, s)
                                          : AffineSpan<double>{};
        const Texture& texels = *m.texture;
        const Wrap wrap = m.mesh.wrap;
        const bool masked = m.masked_fetch;
        map_span(mapper, m.scene.options.precision, r, ps, as,
                 [&](int k, int i, int j, double, double) {
                     if (all_shown || visible[k] != 0) {
                         out[k] = masked ? fetch_texel_masked(texels, i, j)
                                         : fetch_texel(texels, i, j, wrap);
                     }
                 });
        const double spent = m.clock.since(t0);
        count_mapped_span(report, mapper, count, spent, mapper_used);
        shading_seconds += spent;
    });
    report.raster.seconds += m.clock.since(start) - shading_seconds;
}
//< draw-triangle-lean

} // namespace

void draw_mesh(MeshContext& m, const std::vector<ScreenTriangle>& triangles,
               bool lean_spans) {
    // Stage times: the mesh's drawing is timed whole, and split among the stages as on
    // the timed sample of its triangles (timed_triangles_per_mesh).
    const RenderReport before = m.report;
    const Clock::time_point t0 = Clock::now();
    const bool lean = lean_spans && lean_drawable(m);
    const std::size_t interval = timed_triangle_interval(triangles.size());
    std::size_t until_timed = 0; // triangles before the next timed one
    for (std::size_t k = 0; k < triangles.size(); ++k) {
        m.clock.on = until_timed == 0;
        until_timed = m.clock.on ? interval - 1 : until_timed - 1;
        if (lean) {
            draw_triangle_lean(m, triangles[k]);
        } else {
            draw_triangle(m, triangles[k]);
        }
    }
    share_drawing_time(m.report, before, seconds_since(t0));
}

} // namespace exactpixels
