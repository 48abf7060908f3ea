#include "exactpixels/scene/scene_renderer.hpp"

#include "exactpixels/base/error.hpp"
#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/raster/fill_work.hpp"
#include "exactpixels/raster/scanline.hpp"
#include "exactpixels/raster/screen_plane.hpp"
#include "exactpixels/scene/depth_buffer.hpp"
#include "exactpixels/scene/lighting.hpp"
#include "exactpixels/scene/mesh_transform.hpp"
#include "exactpixels/scene/scene_pipeline.hpp"
#include "exactpixels/texture/clipping.hpp"
#include "exactpixels/texture/filter.hpp"
#include "exactpixels/texture/level_of_detail.hpp"
#include "exactpixels/texture/mipmap.hpp"
#include "exactpixels/texture/perspective.hpp"
#include "exactpixels/texture/rounding.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace exactpixels {

long long RenderReport::divides() const {
    long long total = auto_choice.divides + colour_perspective.divides + filter.divides +
                      lighting.divides;
    for (const StageCounter& m : mappers) {
        total += m.divides;
    }
    return total;
}

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// About this many triangles of each mesh have their stages timed span by span (every
/// triangle of a smaller mesh): reading the clock is not free. Here it costs 24 ns, more
/// than shading a small span, and at one triangle in 16 the big torus's frame spent about
/// 0.8 ms of its 20 reading it (bench_ch07_big_scene); 512 evenly spread triangles split
/// a mesh's time among its stages as well, for almost nothing.
constexpr std::size_t timed_triangles_per_mesh = 512;

/// Which triangles of a mesh of `count` are timed: one in every this many.
std::size_t timed_triangle_interval(std::size_t count) {
    return std::max<std::size_t>(1, count / timed_triangles_per_mesh);
}

/// The clock of the stages inside one triangle: it reads the time only when `on`, and
/// otherwise gives zero durations.
struct SampledClock {
    bool on = true; ///< whether this triangle is one of the timed ones
    /// The time now, or a dummy when off.
    Clock::time_point now() const { return on ? Clock::now() : Clock::time_point{}; }
    /// Seconds since `start`, or 0 when off.
    double since(Clock::time_point start) const {
        return on ? seconds_since(start) : 0.0;
    }
};

/// The camera's axes in world space (@eq:scene-look-at).
struct CameraFrame {
    glm::dvec3 eye, right, up, forward;
};

CameraFrame camera_frame(const SceneCamera& camera) {
    const glm::dvec3 forward = glm::normalize(camera.target - camera.position);
    const glm::dvec3 right = glm::normalize(glm::cross(camera.up, forward));
    return {camera.position, right, glm::cross(forward, right), forward};
}

//> project-vertex
/// Chapter 3's pinhole for a perspective camera: the focal length in pixels from the
/// vertical field of view, the view axis through the image centre (@eq:scene-focal).
Pinhole pinhole(const Scene& scene) {
    const double half_angle = 0.5 * scene.camera.fov_degrees * std::acos(-1.0) / 180.0;
    return {0.5 * scene.height / std::tan(half_angle),
            {0.5 * scene.width, 0.5 * scene.height}};
}

/// View space to screen: pixels (origin top-left, y down) and the depth w. The
/// orthographic camera keeps x and y (scaled) and gives every point w = 1.
TexturedVertex project_vertex(const Scene& scene, const Pinhole& camera,
                              const ViewVertex& v) {
    if (scene.camera.projection == Projection::perspective) {
        return project(camera, v.position, v.uv); // w = z >= near > 0
    }
    const double scale = scene.height / scene.camera.view_height; // pixels per unit
    return {camera.centre + scale * Point2{v.position.x, -v.position.y}, 1.0, v.uv};
}
//< project-vertex

Rgba8 multiply(Rgba8 texel, const Colour& c) {
    return to_rgba8(
        Colour{texel.r / 255.0 * c.r, texel.g / 255.0 * c.g, texel.b / 255.0 * c.b});
}

/// Everything the per-triangle code needs about the mesh and the frame.
struct MeshContext {
    const Scene& scene;
    const SceneMesh& mesh;
    MeshStages stages;
    const Texture* texture;
    Framebuffer& frame;
    TexelMap* coordinates;
    RenderReport& report;
    DepthBuffer* depth;        // the depth stage's buffer, or nullptr when it is off
    bool colour_perspective;   // colours as c/w over 1/w (else linear on screen)
    std::vector<Rgba8> row;    // one span of shaded pixels
    std::vector<char> visible; // depth stage: which pixels of the span passed the test
    MipChain* chain;           // filter stage: the texture in linear light, or nullptr
    bool* full_chain;          // filter stage: whether *chain has all its levels
    const std::vector<ViewLight>* lights; // lighting stage per pixel, or nullptr
    Material material;                    // the mesh's specular colour and exponent
    Rgba8 flat;                           // the mesh's colour, as written
    SampledClock clock;                   // on for the triangles whose stages are timed
    bool masked_fetch = false; // FastPaths::masked_fetch, and the texture allows it
};

/// The unit vector from a view-space point to the eye: towards the origin for a
/// pinhole, along -z everywhere for parallel rays.
glm::dvec3 to_eye(const Scene& scene, glm::dvec3 p) {
    return scene.camera.projection == Projection::perspective
               ? glm::normalize(-p)
               : glm::dvec3{0.0, 0.0, -1.0};
}

//> choose-filter
/// The filter a triangle gets under the scene's `filter` key. `auto` looks at the
/// exact derivatives at the three corners (@eq:derivatives): where no corner is
/// minified (lambda <= 0 at each, @eq:level) bilinear on level 0 is all a pixel needs
/// and no mip chain is built; else trilinear, or anisotropic where a minified corner's
/// footprint is at least twice as long as it is wide (@eq:anisotropy).
Filter triangle_filter(SceneFilter wanted, const std::array<TexturedVertex, 3>& t) {
    switch (wanted) {
    case SceneFilter::nearest:
        return Filter::nearest;
    case SceneFilter::bilinear:
        return Filter::bilinear;
    case SceneFilter::trilinear:
        return Filter::trilinear;
    case SceneFilter::anisotropic:
        return Filter::anisotropic;
    case SceneFilter::automatic:
        break;
    }
    Filter chosen = Filter::bilinear;
    for (const TexturedVertex& corner : t) {
        const TexelDerivatives d = derivatives_at(t, corner.position);
        if (isotropic_level(d) > 0.0) {
            if (anisotropy(d, 8).probes >= 2) {
                return Filter::anisotropic;
            }
            chosen = Filter::trilinear;
        }
    }
    return chosen;
}
//< choose-filter

/// Makes the mesh's chain ready for `filter`: level 0 for bilinear, every level (built
/// once per texture, limits checked by build_mip_chain) for the mip filters.
void prepare_chain(MeshContext& m, Filter filter) {
    if (filter != Filter::bilinear && !*m.full_chain) {
        *m.chain = build_mip_chain(*m.texture);
        *m.full_chain = true;
        m.report.mip_chains += 1;
    } else if (m.chain->levels.empty()) {
        m.chain->levels.push_back(decode_texture(*m.texture));
    }
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
            //> filter-stage
            if (filter != Filter::nearest) { // the exact coordinate and derivatives
                const Clock::time_point f0 = m.clock.now();
                const FilterSettings fs{.filter = filter, .wrap = m.mesh.wrap};
                int filtered = 0;
                for (int k = 0; k < count; ++k) {
                    if (!seen(k)) {
                        continue;
                    }
                    filtered += 1;
                    const auto [u, v] =
                        projected_coordinates(snapped_corners, Point2{x + k, y});
                    const TexCoord uv{u.p / u.q, v.p / v.q}; // q = 1/w > 0
                    m.row[static_cast<std::size_t>(k)] = encode_linear(
                        sample_filtered(*m.chain, uv, exact_derivatives(u, v), fs));
                }
                report.filter.spans += 1;
                report.filter.pixels += filtered;
                report.filter.divides += 3LL * filtered; // u, v and 1/q^2
                report.filter.seconds += m.clock.since(f0);
            }
            //< filter-stage
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

/// A triangle in view space with the colour and the normal of each corner.
struct ClippedCorners {
    std::array<ViewVertex, 3> view;
    std::array<Colour, 3> colours;
    std::array<glm::dvec3, 3> normals;
};

/// The triangles of a clipped polygon, a fan from its first corner (as clip_near's).
std::vector<std::array<ViewVertex, 3>> fan(const ClippedPolygon& polygon) {
    std::vector<std::array<ViewVertex, 3>> out;
    for (int k = 1; k + 1 < polygon.count; ++k) {
        out.push_back({polygon.corners[0], polygon.corners[static_cast<std::size_t>(k)],
                       polygon.corners[static_cast<std::size_t>(k + 1)]});
    }
    return out;
}

/// Chapter 6's clipping, at every plane of `planes`, of a triangle, its vertex colours
/// and its normals. clip_triangle carries the texture coordinate; colours and normals
/// are linear along view-space edges too, so more passes with them in place of uv, two
/// numbers at a time, cut them at the same parameters (the cuts depend only on the
/// positions). A cut normal is shorter than 1; the lighting stage renormalises it.
std::vector<ClippedCorners> clip_corners(const std::array<ViewVertex, 3>& view,
                                         const std::array<Colour, 3>& colours,
                                         const std::array<glm::dvec3, 3>& normals,
                                         const std::vector<ViewPlane>& planes,
                                         bool with_colours, bool with_normals) {
    const auto clip = [&](const std::array<ViewVertex, 3>& v) {
        return fan(clip_triangle(v, planes));
    };
    const std::vector<std::array<ViewVertex, 3>> uv = clip(view);
    std::vector<ClippedCorners> pieces(uv.size());
    for (std::size_t t = 0; t < pieces.size(); ++t) {
        pieces[t].view = uv[t];
        pieces[t].colours = colours; // unused unless with_colours
        pieces[t].normals = normals; // unused unless with_normals
    }
    if (with_normals) {
        std::array<ViewVertex, 3> xy = view, z = view;
        for (std::size_t k = 0; k < 3; ++k) {
            xy[k].uv = {normals[k].x, normals[k].y};
            z[k].uv = {normals[k].z, 0.0};
        }
        const auto cxy = clip(xy), cz = clip(z);
        for (std::size_t t = 0; t < pieces.size(); ++t) {
            for (std::size_t k = 0; k < 3; ++k) {
                pieces[t].normals[k] = {cxy[t][k].uv.x, cxy[t][k].uv.y, cz[t][k].uv.x};
            }
        }
    }
    if (with_colours) {
        std::array<ViewVertex, 3> rg = view, b = view;
        for (std::size_t k = 0; k < 3; ++k) {
            rg[k].uv = {colours[k].r, colours[k].g};
            b[k].uv = {colours[k].b, 0.0};
        }
        const auto crg = clip(rg), cb = clip(b);
        for (std::size_t t = 0; t < pieces.size(); ++t) {
            for (std::size_t k = 0; k < 3; ++k) {
                assert(crg[t][k].position == pieces[t].view[k].position);
                pieces[t].colours[k] = {crg[t][k].uv.x, crg[t][k].uv.y, cb[t][k].uv.x};
            }
        }
    }
    return pieces;
}

//> view-volume
/// The planes of view space that bound what a camera draws (@eq:scene-guard-band).
struct ViewVolume {
    /// The screen's four edges, then near and far: a triangle wholly outside any one
    /// covers no pixel.
    std::vector<ViewPlane> reject;
    /// Near, far, then the guard band's four planes: the planes a triangle is cut at.
    std::vector<ViewPlane> clip;
};

/// The view volume of the scene's camera. A screen line x = s is the view-space plane
/// (cx - s) z + f x = 0 under perspective (multiplied by z > 0, which keeps the sign),
/// (cx - s) + k x = 0 orthographic; y = s likewise with y pointing up in view space.
/// An orthographic camera has no near or far plane (it never had).
ViewVolume view_volume(const Scene& scene, const Pinhole& lens) {
    const bool perspective = scene.camera.projection == Projection::perspective;
    const double scale =
        perspective ? lens.focal : scene.height / scene.camera.view_height;
    const auto plane = [&](glm::dvec2 axis, double offset) { // offset times z or 1
        return perspective ? ViewPlane{{scale * axis.x, scale * axis.y, offset}, 0.0}
                           : ViewPlane{{scale * axis.x, scale * axis.y, 0.0}, offset};
    };
    const double cx = lens.centre.x, cy = lens.centre.y;
    const auto x_at_least = [&](double s) { return plane({1.0, 0.0}, cx - s); };
    const auto x_at_most = [&](double s) { return plane({-1.0, 0.0}, s - cx); };
    const auto y_at_least = [&](double s) { return plane({0.0, -1.0}, cy - s); };
    const auto y_at_most = [&](double s) { return plane({0.0, 1.0}, s - cy); };
    ViewVolume volume;
    volume.reject = {x_at_least(0.0), x_at_most(scene.width), y_at_least(0.0),
                     y_at_most(scene.height)};
    if (perspective) {
        volume.clip.push_back(near_plane(scene.camera.near)); // first: then z > 0
        if (std::isfinite(scene.camera.far)) {
            volume.clip.push_back({{0.0, 0.0, -1.0}, scene.camera.far});
        }
        volume.reject.insert(volume.reject.end(), volume.clip.begin(), volume.clip.end());
    }
    const double band = guard_band_px;
    for (const ViewPlane& p :
         {x_at_least(-band), x_at_most(band), y_at_least(-band), y_at_most(band)}) {
        volume.clip.push_back(p);
    }
    return volume;
}

/// Whether all three corners lie outside one plane (each plane_value < 0).
bool outside_one(const std::vector<ViewPlane>& planes,
                 const std::array<ViewVertex, 3>& v) {
    return std::any_of(planes.begin(), planes.end(), [&](const ViewPlane& p) {
        return plane_value(p, v[0].position) < 0.0 &&
               plane_value(p, v[1].position) < 0.0 && plane_value(p, v[2].position) < 0.0;
    });
}

/// Whether some corner lies outside some plane.
bool any_outside(const std::vector<ViewPlane>& planes,
                 const std::array<ViewVertex, 3>& v) {
    return std::any_of(planes.begin(), planes.end(), [&](const ViewPlane& p) {
        return plane_value(p, v[0].position) < 0.0 ||
               plane_value(p, v[1].position) < 0.0 || plane_value(p, v[2].position) < 0.0;
    });
}
//< view-volume

//> screen-accept
/// How far inside the screen's edges and the guard band's the fast test wants projected
/// corners, px: one sub-pixel step. A corner's plane value for the screen line x = s is
/// z (px - s) (z = 1 orthographic); computed in double, it and px are off by a few
/// units of 2^-53 times numbers below 2^21 px, some 2^-30 px, so a corner this far
/// inside a line on screen is inside its plane too (@eq:scene-screen-accept).
constexpr double screen_accept_margin_px = 1.0 / 256.0;

/// The fast variant of the view-volume tests (FastPaths::screen_accept) for the common
/// triangle. True when every corner lies between the near and far planes (compared as
/// the planes compare: z >= near, z <= far) and projects at least
/// screen_accept_margin_px inside the guard band, and the projected corners' box
/// overlaps the screen by that margin on each side: then no plane of volume.clip has a
/// corner outside and no plane of volume.reject has all three outside, as any_outside
/// and outside_one would find (tests/ch07_fast_paths.cpp). Writes the projected corners
/// (project_vertex's values, not yet checked for finite 1/w and uv/w) when it says yes;
/// false means undecided, and the plain tests run. NaN and infinities fail a compare.
bool screen_accept(const Scene& scene, const Pinhole& lens,
                   const std::array<ViewVertex, 3>& view,
                   std::array<TexturedVertex, 3>& corners) {
    const bool perspective = scene.camera.projection == Projection::perspective;
    for (const ViewVertex& v : view) {
        const double z = v.position.z;
        if (perspective && !(z >= scene.camera.near && z <= scene.camera.far)) {
            return false; // before project_vertex, which refuses z <= 0
        }
        if (!std::isfinite(v.position.x) || !std::isfinite(v.position.y) ||
            !std::isfinite(z)) {
            return false; // project_vertex refuses these too
        }
    }
    const double margin = screen_accept_margin_px;
    const double band = guard_band_px - margin;
    Point2 lo{band, band}, hi{-band, -band};
    for (std::size_t k = 0; k < 3; ++k) {
        corners[k] = project_vertex(scene, lens, view[k]);
        const Point2 p = corners[k].position;
        if (!(std::abs(p.x) <= band && std::abs(p.y) <= band)) {
            return false;
        }
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    return hi.x >= margin && lo.x <= scene.width - margin && hi.y >= margin &&
           lo.y <= scene.height - margin;
}
//< screen-accept

/// A mesh position as unlit_geometry moves it once for all the corners at it: in view
/// space, projected, whether PerspectiveAccept::corner accepts it, and 1/w.
struct MovedPosition {
    glm::dvec3 view;       ///< view space
    Point2 at;             ///< on screen (meaningful where `inside`)
    double nearness = 0.0; ///< 1 / view.z
    bool inside = false;   ///< between the planes and within the band
};

/// screen_accept_perspective's two tests: on each corner, and on the box of the three.
struct PerspectiveAccept {
    double near, far;     ///< the camera's planes (far at most the largest double)
    double margin, band;  ///< screen_accept_margin_px; the guard band less it
    double width, height; ///< the screen
    const Pinhole& lens;  ///< the projection
    PerspectiveAccept(const Scene& scene, const Pinhole& pinhole)
        : near(scene.camera.near),
          far(std::min(scene.camera.far, std::numeric_limits<double>::max())),
          margin(screen_accept_margin_px), band(guard_band_px - screen_accept_margin_px),
          width(scene.width), height(scene.height), lens(pinhole) {}
    /// Whether the view-space point p lies between the planes and projects to `at`
    /// within the band (false for anything not finite).
    bool corner(const glm::dvec3& p, Point2& at) const {
        if (!(p.z >= near && p.z <= far)) {
            return false;
        }
        at = {lens.centre.x + lens.focal * p.x / p.z, // as project()
              lens.centre.y - lens.focal * p.y / p.z};
        return std::abs(at.x) <= band && std::abs(at.y) <= band;
    }
    /// Whether the box from (lo_x, lo_y) to (hi_x, hi_y) overlaps the screen by more
    /// than the margin.
    bool box(double lo_x, double lo_y, double hi_x, double hi_y) const {
        return hi_x >= margin && lo_x <= width - margin && hi_y >= margin &&
               lo_y <= height - margin;
    }
};

/// screen_accept under a perspective camera in fewer instructions, for
/// FastPaths::unlit_geometry: the same compares on the same values in the same
/// precision, with each finite test folded into a compare (false for NaN and infinity:
/// z <= min(far, the largest double) is false for an infinite z, and a corner that is
/// not finite projects to a value that fails the band's compare) and project()'s two
/// divides written out. The same answer, and the same corners when it is yes
/// (tests/ch07_fast_paths.cpp).
bool screen_accept_perspective(const Scene& scene, const Pinhole& lens,
                               const std::array<ViewVertex, 3>& view,
                               std::array<TexturedVertex, 3>& corners) {
    const PerspectiveAccept accept(scene, lens);
    double lo_x = accept.band, lo_y = accept.band, hi_x = -accept.band,
           hi_y = -accept.band;
    for (std::size_t k = 0; k < 3; ++k) {
        const glm::dvec3 p = view[k].position;
        Point2 at{};
        if (!accept.corner(p, at)) {
            return false;
        }
        corners[k] = {at, p.z, view[k].uv};
        lo_x = std::min(lo_x, at.x);
        lo_y = std::min(lo_y, at.y);
        hi_x = std::max(hi_x, at.x);
        hi_y = std::max(hi_y, at.y);
    }
    return accept.box(lo_x, lo_y, hi_x, hi_y);
}

/// Twice the signed screen area of the triangle; negative when it faces the camera
/// (its corners run counter-clockwise as seen from its front).
double screen_area2(const std::array<TexturedVertex, 3>& t) {
    const Point2 a = t[1].position - t[0].position, b = t[2].position - t[0].position;
    return a.x * b.y - a.y * b.x;
}

/// Stops NaN and infinity before the first pixel: throws Error when a projected corner
/// has a coordinate, depth, 1/w or u/w, v/w that is not finite in the precision the
/// mappers will use (float overflows above 3.4e38, long before double does).
void check_finite(const TexturedVertex& v, Precision precision, std::size_t triangle) {
    const double limit = precision == Precision::float32
                             ? double(std::numeric_limits<float>::max())
                             : std::numeric_limits<double>::max();
    const double inverse_w = 1.0 / v.w;
    for (const double value : {v.position.x, v.position.y, v.w, inverse_w,
                               v.uv.x * inverse_w, v.uv.y * inverse_w}) {
        if (!(std::abs(value) <= limit)) { // false for NaN too
            throw Error(fmt::format(
                "triangle {}: a corner projects to a value that is not "
                "finite in {} (w = {}, 1/w = {})",
                triangle, precision == Precision::float32 ? "float" : "double", v.w,
                inverse_w));
        }
    }
}

} // namespace

// plan_mesh's stages, and under Gouraud lighting the colour stage, which interpolates
// the lit colours (they hold the mesh's colour).
MeshStages mesh_stages(const Scene& scene, const SceneMesh& mesh) {
    MeshStages stages = plan_mesh(mesh);
    if (!scene.lights.empty() && mesh_shading(scene, mesh) == Shading::gouraud) {
        stages.colour = true;
        stages.tint = false;
    }
    return stages;
}

//> geometry-stage
SceneGeometry run_geometry(const Scene& scene, RenderReport& report, FastPaths fast) {
    SceneGeometry geometry;
    const CameraFrame camera = camera_frame(scene.camera);
    const bool perspective = scene.camera.projection == Projection::perspective;
    const Pinhole lens = pinhole(scene);
    const ViewVolume volume = view_volume(scene, lens);
    // World to view space: a translation for points, then the camera's rotation.
    const auto to_view = [&](glm::dvec3 v, bool is_point) {
        const glm::dvec3 d = is_point ? v - camera.eye : v;
        return glm::dvec3{glm::dot(d, camera.right), glm::dot(d, camera.up),
                          glm::dot(d, camera.forward)};
    };
    const bool lit = !scene.lights.empty(); // no light, no lighting stage
    if (lit) {
        geometry.lights = lights_in_view(scene.lights, to_view);
    }
    const std::vector<ViewLight>& lights = geometry.lights;
    report.lighting_on = lit;
    report.lights = static_cast<int>(lights.size());
    // Every mesh first: the depth stage's plan needs to know where on screen each mesh
    // lands.
    geometry.meshes.resize(scene.meshes.size());
    geometry.footprints.resize(scene.meshes.size());
    std::vector<MovedPosition> moved; // unlit_geometry's positions, mesh by mesh
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const SceneMesh& mesh = scene.meshes[i];
        std::vector<ScreenTriangle>& out = geometry.meshes[i];
        MeshFootprint& footprint = geometry.footprints[i];
        const bool with_colours = mesh_stages(scene, mesh).colour;
        const bool gouraud = lit && mesh_shading(scene, mesh) == Shading::gouraud;
        const bool phong = lit && !gouraud;
        report.gouraud_meshes += gouraud;
        report.phong_meshes += phong;
        const std::vector<CornerNormals> normals =
            lit ? mesh_normals(mesh) : std::vector<CornerNormals>{};
        footprint.name = fmt::format("mesh[{}]", i); // as messages name it
        // Only `depth = "auto"` asks (a scan of every corner per corner of one face).
        footprint.can_overlap_itself =
            scene.options.depth == DepthMode::automatic && can_overlap_itself(mesh);
        // Stops a projected corner that is not finite (naming the mesh).
        const auto checked = [&](const TexturedVertex& corner, std::size_t index) {
            try {
                check_finite(corner, scene.options.precision, index);
            } catch (const Error& error) {
                throw Error(fmt::format("{}: {}", mesh.origin, error.what()));
            }
            return corner;
        };
        const auto project_checked = [&](const ViewVertex& v, std::size_t index) {
            return checked(project_vertex(scene, lens, v), index);
        };
        // Every step of one triangle, the plain way (the fast paths inside it are
        // screen_accept's). Inlined into the plain loop below, and called out of line
        // where unlit_geometry hands a triangle over (plain_triangle_call): inlined
        // there too, it would crowd the fast loop (callgrind: 2.6M instructions more
        // on the big torus's frame).
        const auto plain_triangle = [&](std::size_t index)
            __attribute__((always_inline)) {
            const std::array<SceneVertex, 3>& triangle = mesh.triangles[index];
            std::array<ViewVertex, 3> view{};
            std::array<Colour, 3> colours{};
            for (std::size_t k = 0; k < 3; ++k) {
                view[k] = {to_view(triangle[k].position, true), triangle[k].uv};
                colours[k] = triangle[k].colour;
            }
            report.geometry.triangles += 1;
            std::array<TexturedVertex, 3> corners{}; // of a triangle not clipped
            bool needs_clip = false;
            if (fast.screen_accept && screen_accept(scene, lens, view, corners)) {
                for (std::size_t k = 0; k < 3; ++k) { // inside: neither rejected nor cut
                    corners[k] = checked(corners[k], index);
                }
            } else {                                    // the plain path
                if (outside_one(volume.reject, view)) { // covers no pixel: not projected
                    report.rejected.triangles += 1;
                    return;
                }
                needs_clip = any_outside(volume.clip, view);
                if (!needs_clip) {
                    for (std::size_t k = 0; k < 3; ++k) {
                        corners[k] = project_checked(view[k], index);
                    }
                }
            }
            // A whole triangle is culled before it is lit: the same projected corners
            // decide it here and below, so the decision cannot differ.
            if (!needs_clip) {
                if (mesh.cull_back && screen_area2(corners) >= 0.0) {
                    report.culling.triangles += 1;
                    return;
                }
            }
            std::array<glm::dvec3, 3> view_normals{};
            if (lit) {
                const Clock::time_point l0 = Clock::now();
                for (std::size_t k = 0; k < 3; ++k) {
                    view_normals[k] = to_view(normals[index][k], false);
                }
                //> gouraud-vertices
                if (gouraud) { // the lit colour replaces the corner's colour
                    const Material material{mesh.specular, mesh.shininess};
                    for (std::size_t k = 0; k < 3; ++k) {
                        const Colour diffuse =
                            mesh.vertex_colours ? colours[k] : mesh.colour;
                        const glm::dvec3 at = view[k].position;
                        colours[k] =
                            light_colour(lights, scene.options.ambient, diffuse, material,
                                         at, view_normals[k], to_eye(scene, at));
                    }
                    report.lit_vertices += 3;
                }
                //< gouraud-vertices
                report.lighting.seconds += seconds_since(l0);
            }
            //> clip-only-when-needed
            const ClippedCorners whole{view, colours, view_normals}; // uncut: one piece
            std::vector<ClippedCorners> cut; // the pieces of a cut triangle
            if (needs_clip) {                // the only triangles that pay for it
                const Clock::time_point c0 = Clock::now();
                cut = clip_corners(view, colours, view_normals, volume.clip, with_colours,
                                   phong);
                report.clipping.triangles += 1;
                report.clipping.seconds += seconds_since(c0);
            }
            //< clip-only-when-needed
            const std::size_t piece_count = needs_clip ? cut.size() : 1;
            for (std::size_t p = 0; p < piece_count; ++p) {
                const ClippedCorners& piece = needs_clip ? cut[p] : whole;
                ScreenTriangle t{};
                for (std::size_t k = 0; k < 3; ++k) {
                    t.corners[k] = needs_clip ? project_checked(piece.view[k], index)
                                              : corners[k]; // piece.view is view
                    t.nearness[k] =
                        perspective ? 1.0 / t.corners[k].w : -piece.view[k].position.z;
                    t.points[k] = piece.view[k].position;
                }
                t.colours = piece.colours;
                t.normals = piece.normals;
                if (mesh.cull_back && screen_area2(t.corners) >= 0.0) {
                    report.culling.triangles += 1; // a clipped piece seen from behind
                    continue;
                }
                for (const TexturedVertex& v : t.corners) {
                    footprint.box.add(v.position);
                }
                out.push_back(t);
            }
        };
        const auto plain_triangle_call = [&](std::size_t index)
            __attribute__((noinline)) {
            plain_triangle(index);
        };
        //> unlit-geometry
        // FastPaths::unlit_geometry: an unlit mesh under a perspective camera. A corner
        // screen_accept accepts has a finite w >= near > 0 and a finite position inside
        // the band, so of check_finite's values only w, 1/w and uv/w are left to
        // compare with the limit, and 1/w <= 1/near, |uv| (1/w) <= |uv| (1/near)
        // (rounding is monotone): a few compares per triangle, without 1/w, and
        // check_finite itself where one fails (it throws as on the plain path).
        const double limit = scene.options.precision == Precision::float32
                                 ? double(std::numeric_limits<float>::max())
                                 : std::numeric_limits<double>::max();
        const double most_inverse_w = 1.0 / scene.camera.near;
        // to_view for points, each dot product written out in glm::dot's order (the same
        // doubles: callgrind counted 52 instructions a corner through glm, 8M a frame).
        const glm::dvec3 eye = camera.eye, right = camera.right, up = camera.up,
                         forward = camera.forward;
        const auto point_to_view = [&](const glm::dvec3& v) {
            const double dx = v.x - eye.x, dy = v.y - eye.y, dz = v.z - eye.z;
            return glm::dvec3{dx * right.x + dy * right.y + dz * right.z,
                              dx * up.x + dy * up.y + dz * up.z,
                              dx * forward.x + dy * forward.y + dz * forward.z};
        };
        // After the accept test: the finite check, culling and the stored triangle, of
        // corners whose view-space positions are `at` and whose 1/w is nearness(k).
        const auto keep_unlit = [&](std::size_t index,
                                    const std::array<glm::dvec3, 3>& at,
                                    std::array<TexturedVertex, 3>& corners,
                                    const auto& nearness) {
            const std::array<SceneVertex, 3>& triangle = mesh.triangles[index];
            report.geometry.triangles += 1;
            bool within = most_inverse_w <= limit; // each compare false for NaN
            for (const TexturedVertex& c : corners) {
                within = within && c.w <= limit &&
                         std::abs(c.uv.x) * most_inverse_w <= limit &&
                         std::abs(c.uv.y) * most_inverse_w <= limit;
            }
            if (!within) {
                for (std::size_t k = 0; k < 3; ++k) {
                    corners[k] = checked(corners[k], index); // throws as the plain path
                }
            }
            if (mesh.cull_back && screen_area2(corners) >= 0.0) {
                report.culling.triangles += 1;
                return;
            }
            ScreenTriangle& t = out.emplace_back();
            for (std::size_t k = 0; k < 3; ++k) {
                t.corners[k] = corners[k];
                t.nearness[k] = nearness(k);
                t.points[k] = at[k];
                t.colours[k] = triangle[k].colour;
                footprint.box.add(corners[k].position);
            }
        };
        const auto unlit_triangle = [&](std::size_t index) {
            const std::array<SceneVertex, 3>& triangle = mesh.triangles[index];
            std::array<ViewVertex, 3> view{};
            for (std::size_t k = 0; k < 3; ++k) {
                view[k] = {point_to_view(triangle[k].position), triangle[k].uv};
            }
            std::array<TexturedVertex, 3> corners{};
            if (!screen_accept_perspective(scene, lens, view, corners)) {
                plain_triangle_call(index); // near a plane or off screen: plane tests
                return;
            }
            keep_unlit(index, {view[0].position, view[1].position, view[2].position},
                       corners, [&](std::size_t k) { return 1.0 / corners[k].w; });
        };
        // Where the mesh lists its distinct positions (SceneMesh::positions), each is
        // moved, projected, tested and divided into 1/w once, not once per corner (six
        // corners share a position of a closed grid), with the same arithmetic.
        const PerspectiveAccept accept(scene, lens);
        const auto move_positions = [&] {
            moved.resize(mesh.positions.size());
            for (std::size_t i = 0; i < moved.size(); ++i) {
                MovedPosition& m = moved[i];
                m.view = point_to_view(mesh.positions[i]);
                m.inside = accept.corner(m.view, m.at);
                m.nearness = 1.0 / m.view.z;
            }
        };
        const auto unlit_shared = [&](std::size_t index) {
            const std::array<SceneVertex, 3>& triangle = mesh.triangles[index];
            const std::array<std::uint32_t, 3>& ids = mesh.corner_positions[index];
            for (std::size_t k = 0; k < 3; ++k) { // a corner changed since: on its own
                if (!same_bits(triangle[k].position, mesh.positions[ids[k]])) {
                    unlit_triangle(index);
                    return;
                }
            }
            const MovedPosition &a = moved[ids[0]], &b = moved[ids[1]],
                                &c = moved[ids[2]];
            if (!(a.inside && b.inside && c.inside &&
                  accept.box(std::min({a.at.x, b.at.x, c.at.x}),
                             std::min({a.at.y, b.at.y, c.at.y}),
                             std::max({a.at.x, b.at.x, c.at.x}),
                             std::max({a.at.y, b.at.y, c.at.y})))) {
                plain_triangle_call(index); // near a plane or off screen: plane tests
                return;
            }
            std::array<TexturedVertex, 3> corners{{{a.at, a.view.z, triangle[0].uv},
                                                   {b.at, b.view.z, triangle[1].uv},
                                                   {c.at, c.view.z, triangle[2].uv}}};
            const std::array<const MovedPosition*, 3> from{&a, &b, &c};
            keep_unlit(index, {a.view, b.view, c.view}, corners,
                       [&](std::size_t k) { return from[k]->nearness; });
        };
        //< unlit-geometry
        const Clock::time_point t0 = Clock::now(); // the whole mesh: clocks cost time
        if (fast.unlit_geometry && perspective && !lit) {
            out.reserve(mesh.triangles.size() / 2); // about half face the camera
            if (mesh.corner_positions.size() == mesh.triangles.size() &&
                !mesh.triangles.empty()) {
                move_positions();
                for (std::size_t index = 0; index < mesh.triangles.size(); ++index) {
                    unlit_shared(index);
                }
            } else {
                for (std::size_t index = 0; index < mesh.triangles.size(); ++index) {
                    unlit_triangle(index);
                }
            }
        } else {
            for (std::size_t index = 0; index < mesh.triangles.size(); ++index) {
                plain_triangle(index);
            }
        }
        report.geometry.seconds += seconds_since(t0);
    }
    return geometry;
}
//< geometry-stage

namespace {

/// Splits `spent`, the time of drawing one mesh, among the drawing stages in the
/// proportions of the seconds the timed triangles added to them since `before`.
void share_drawing_time(RenderReport& report, const RenderReport& before, double spent) {
    double sampled = 0.0; // texture's seconds hold its mappers' and filter's: not again
    for (const auto stage :
         {&RenderReport::depth, &RenderReport::raster, &RenderReport::colour,
          &RenderReport::texture, &RenderReport::lighting}) {
        sampled += (report.*stage).seconds - (before.*stage).seconds;
    }
    const double scale = sampled > 0.0 ? spent / sampled : 0.0;
    const auto rescale = [&](StageCounter& now, const StageCounter& then) {
        now.seconds = then.seconds + scale * (now.seconds - then.seconds);
    };
    for (const auto stage :
         {&RenderReport::depth, &RenderReport::raster, &RenderReport::colour,
          &RenderReport::texture, &RenderReport::filter, &RenderReport::lighting}) {
        rescale(report.*stage, before.*stage);
    }
    for (std::size_t k = 0; k < report.mappers.size(); ++k) {
        rescale(report.mappers[k], before.mappers[k]);
    }
}

} // namespace

std::vector<long long> fill_work(const SceneGeometry& geometry, Viewport image) {
    std::vector<long long> work;
    for (const std::vector<ScreenTriangle>& mesh : geometry.meshes) {
        long long sum = 0;
        for (const ScreenTriangle& t : mesh) {
            sum += fill_work(
                {t.corners[0].position, t.corners[1].position, t.corners[2].position},
                image);
        }
        work.push_back(sum);
    }
    return work;
}

namespace {

/// Refuses, before anything is drawn, a scene whose triangles ask for more than
/// max_fill_work pixels of drawing, naming the mesh that takes the sum past it.
void check_fill_work(const Scene& scene, const SceneGeometry& geometry) {
    const std::vector<long long> work =
        fill_work(geometry, Viewport{scene.width, scene.height});
    long long sum = 0;
    for (std::size_t i = 0; i < work.size(); ++i) {
        sum += work[i];
        if (sum > max_fill_work) {
            throw Error(fmt::format(
                "{}: the triangles up to this mesh ask for {} pixels of drawing (their "
                "bounding boxes in the image), more than the {} allowed",
                scene.meshes[i].origin, sum, max_fill_work));
        }
    }
}

} // namespace

//> render-scene
RenderResult render_scene(const Scene& scene, TexelMap* coordinates, FastPaths fast) {
    const Clock::time_point start = Clock::now();
    RenderResult result{
        Framebuffer(scene.width, scene.height, to_rgba8(scene.background)), {}};
    RenderReport& report = result.report;
    const bool lit = !scene.lights.empty();
    const SceneGeometry geometry = run_geometry(scene, report, fast);
    check_fill_work(scene, geometry); // before the first pixel is drawn
    const DepthPlan depth_plan = plan_depth(scene.options.depth, geometry.footprints,
                                            Viewport{scene.width, scene.height});
    report.depth_on = depth_plan.on;
    report.depth_reason = depth_plan.reason;
    std::vector<MipChain> chains(scene.textures.size()); // filled on demand
    std::vector<bool> full_chains(scene.textures.size(), false);
    std::optional<DepthBuffer> depth;
    if (depth_plan.on) {
        depth.emplace(scene.width, scene.height);
    }
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const SceneMesh& mesh = scene.meshes[i];
        //> choose-colours
        bool corrected = scene.options.colours == ColourInterpolation::perspective;
        if (mesh_stages(scene, mesh).colour) { // the screen path's bound, vs the budget
            for (const ScreenTriangle& t : geometry.meshes[i]) {
                const double bound = colour_error_bound(
                    {t.corners[0].w, t.corners[1].w, t.corners[2].w}, t.colours);
                report.colour_bound = std::max(report.colour_bound, bound);
                corrected = corrected ||
                            (scene.options.colours == ColourInterpolation::automatic &&
                             bound > scene.options.budget);
            }
        }
        //< choose-colours
        MeshContext m{scene,
                      mesh,
                      mesh_stages(scene, mesh),
                      mesh.texture ? &scene.textures[*mesh.texture].texture : nullptr,
                      result.image,
                      coordinates,
                      report,
                      depth ? &*depth : nullptr,
                      corrected,
                      {},
                      {},
                      mesh.texture ? &chains[*mesh.texture] : nullptr,
                      nullptr,
                      lit && mesh_shading(scene, mesh) == Shading::phong
                          ? &geometry.lights
                          : nullptr,
                      Material{mesh.specular, mesh.shininess},
                      to_rgba8(mesh.colour),
                      {}};
        m.masked_fetch = fast.masked_fetch && m.texture != nullptr &&
                         can_fetch_masked(*m.texture, mesh.wrap);
        bool full_chain = mesh.texture && full_chains[*mesh.texture];
        m.full_chain = &full_chain;
        try {
            // Stage times: the mesh's drawing is timed whole, and split among the stages
            // as on the timed sample of its triangles (timed_triangles_per_mesh).
            const RenderReport before = report;
            const Clock::time_point t0 = Clock::now();
            const std::vector<ScreenTriangle>& triangles = geometry.meshes[i];
            const bool lean = fast.lean_spans && lean_drawable(m);
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
            share_drawing_time(report, before, seconds_since(t0));
            if (mesh.texture) {
                full_chains[*mesh.texture] = full_chain;
            }
        } catch (const Error& error) {
            throw Error(fmt::format("{}: {}", mesh.origin, error.what()));
        }
    }
    report.seconds = seconds_since(start);
    return result;
}
//< render-scene

std::string format_report(const RenderReport& r) {
    std::string out = fmt::format("{:<18} {:>10} {:>8} {:>10} {:>10} {:>10}\n", "stage",
                                  "triangles", "spans", "pixels", "divides", "ms");
    const auto line = [&](const std::string& name, const StageCounter& c, bool always) {
        if (always || c.triangles > 0 || c.spans > 0) {
            out +=
                fmt::format("{:<18} {:>10} {:>8} {:>10} {:>10} {:>10.3f}\n", name,
                            c.triangles, c.spans, c.pixels, c.divides, 1e3 * c.seconds);
        }
    };
    line("geometry", r.geometry, true);
    line("rejected", r.rejected, false);
    line("clipping", r.clipping, true);
    line("culling", r.culling, false);
    line("depth", r.depth, false);
    line("  hidden", r.hidden, false);
    line("raster", r.raster, true);
    line("flat colour", r.flat, true);
    line("vertex colour", r.colour, true);
    line("  perspective", r.colour_perspective, false);
    line("texture", r.texture, true);
    line("auto choice", r.auto_choice, false);
    for (std::size_t k = 0; k < r.mappers.size(); ++k) {
        line(fmt::format("  mapper {}", mapper_kind_name(static_cast<MapperKind>(k))),
             r.mappers[k], false);
    }
    line("filter", r.filter, false);
    line("lighting", r.lighting, false);
    if (r.filter.triangles > 0) {
        out += fmt::format("filter stage: {} bilinear, {} trilinear, {} anisotropic "
                           "triangles; {} mip chains built\n",
                           r.filter_triangles[0], r.filter_triangles[1],
                           r.filter_triangles[2], r.mip_chains);
    }
    out +=
        fmt::format("depth stage: {} ({})\n", r.depth_on ? "on" : "off", r.depth_reason);
    if (r.lighting_on) {
        out += fmt::format("lighting stage: on ({} light{}; phong {} mesh{}, gouraud {} "
                           "mesh{}); {} corners lit per vertex\n",
                           r.lights, r.lights == 1 ? "" : "s", r.phong_meshes,
                           r.phong_meshes == 1 ? "" : "es", r.gouraud_meshes,
                           r.gouraud_meshes == 1 ? "" : "es", r.lit_vertices);
    } else {
        out += "lighting stage: off (no [[light]])\n";
    }
    out += fmt::format("total: {} divides, {:.3f} ms\n", r.divides(), 1e3 * r.seconds);
    return out;
}

TexelError check_against_exact(Scene scene) {
    TexelMap map(scene.width, scene.height), reference(scene.width, scene.height);
    render_scene(scene, &map);
    scene.options.mapper = {false, {MapperKind::exact}};
    scene.options.precision = Precision::float64;
    render_scene(scene, &reference);
    return compare_texel_maps(reference, map);
}

} // namespace exactpixels
