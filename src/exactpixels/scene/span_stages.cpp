#include "exactpixels/scene/span_stages.hpp"

#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/fast/exact_lanes.hpp"
#include "exactpixels/raster/scanline.hpp"
#include "exactpixels/raster/screen_plane.hpp"
#include "exactpixels/scene/camera.hpp"
#include "exactpixels/scene/corner_quotients.hpp"
#include "exactpixels/scene/filter_stage.hpp"
#include "exactpixels/texture/perspective.hpp"
#include "exactpixels/texture/rounding.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <tuple>

namespace exactpixels {

namespace {

/// The texel scaled by the colour c, channel by channel.
Rgba8 multiply(Rgba8 texel, const Colour& c) {
    return to_rgba8(
        Colour{texel.r / 255.0 * c.r, texel.g / 255.0 * c.g, texel.b / 255.0 * c.b});
}

/// A span's mapper, and what auto's choice of it cost.
struct MappedSpan {
    Mapper mapper;                ///< the mapper that ran
    bool chosen = false;          ///< whether auto chose it (on this span)
    long long choice_divides = 0; ///< auto's divides when it chose
};

/// What the texture stage sets up once per triangle.
struct TextureSetup {
    bool affine_exact = false; ///< the depths are equal: affine is exact (and free)
    /// auto: affine's bound over the whole triangle fits the budget, so every span of
    /// it is affine (@eq:scene-triangle-bound)
    bool affine_fits = false;
    /// Whether every span gets the same mapper, `mapped` (all but auto's per-span
    /// choice): chosen once here instead of on each span.
    bool per_triangle = false;
    MappedSpan mapped; ///< the mapper of every span, where per_triangle
    /// u/w, v/w, 1/w where a perspective mapper may run; u and v where affine runs. Not
    /// zeroed first: texture_setup sets what is read, and zeroing the five planes cost
    /// the big torus's frame 2 % of its time (perf).
    TexturePlanes planes;
    TexelRounding perspective_rounding{}, affine_rounding{}; ///< chapter 4's choice
};

/// Whether check_textured_triangle passes corners `tv` whose positions snap_in_range
/// has already taken (so they are in range): each w finite and > 0, each texture
/// coordinate finite and below the limit, the piece length in range. Its comparisons
/// without the message's machinery: the checked triangle costs no call (3M instructions
/// on the big torus's frame).
bool mapper_ranges_hold(const RenderOptions& options,
                        const std::array<TexturedVertex, 3>& tv) {
    const double limit = texture_coordinate_limit(options.precision);
    const int piece = options.mapper.mapper.piece;
    bool hold = piece >= min_mapper_piece && piece <= max_mapper_piece;
    for (const TexturedVertex& v : tv) { // each false for NaN too
        hold = hold && v.w > 0.0 && v.w <= std::numeric_limits<double>::max() &&
               std::abs(v.uv.x) < limit && std::abs(v.uv.y) < limit;
    }
    return hold;
}

/// Throws Error when a textured triangle with corners `tv` (snapped in range) leaves
/// the ranges of chapter 3's mappers as the scene sets them.
/// (Always inlined: called, the checks that pass cost the big torus's frame 0.9M
/// instructions; the message's machinery stays out of line.)
[[gnu::always_inline]] inline void
check_mapper_ranges(const MeshContext& m, const std::array<TexturedVertex, 3>& tv) {
    const RenderOptions& options = m.scene.options;
    if (mapper_ranges_hold(options, tv)) [[likely]] {
        return;
    }
    check_textured_triangle(tv, MapperSettings{.mapper = options.mapper.mapper,
                                               .precision = options.precision,
                                               .rounding = {},
                                               .wrap = m.mesh.wrap});
}

/// The texture stage's setup of a textured triangle whose corners `tv` snap to `p`
/// (its planes run through the snapped corners), once check_mapper_ranges has passed.
/// `one_w` is the triangle's 1/w plane (the corners' 1/w through p); the planes and
/// the rounding share one divide per quotient. Sets up `setup`, default-constructed,
/// in place (returned, the setup was copied: 0.3M instructions on the big torus).
void texture_setup(TextureSetup& setup, const RenderOptions& options,
                   const std::array<TexturedVertex, 3>& tv,
                   const std::array<Point2, 3>& p, const ScreenPlane& one_w) {
    setup.affine_exact =
        constant_depth(tv[0].w, tv[1].w, tv[2].w); // @eq:scene-constant-w
    // auto: the whole triangle affine where its bound fits (no divide), else per span.
    setup.affine_fits = options.mapper.automatic && options.mapper.per_triangle &&
                        !setup.affine_exact && triangle_affine_fits(tv, options.budget);
    const MapperChoice& wanted = options.mapper;
    if (setup.affine_exact &&
        (wanted.automatic || wanted.mapper.kind == MapperKind::affine)) {
        setup.per_triangle = true, setup.mapped = {{MapperKind::affine, 2}};
    } else if (!wanted.automatic) {
        setup.per_triangle = true, setup.mapped = {wanted.mapper};
    } else if (setup.affine_fits) { // chosen once for the triangle, without a divide
        setup.per_triangle = true, setup.mapped = {{MapperKind::affine, 2}, true, 0};
    }
    // The spans use affine on every span or on none (auto's per-span choice never picks
    // affine): its planes and rounding only where it runs, and only its.
    if (setup.per_triangle && setup.mapped.mapper.kind == MapperKind::affine) {
        std::tie(setup.planes.u, setup.planes.v) = affine_planes(p, tv);
        if (options.rounding) { // chapter 4: ties go right, or down
            setup.affine_rounding = choose_affine_rounding(tv);
        }
        return; // u/w, v/w and 1/w unset: no span reads them
    }
    const CornerQuotients quotients = corner_quotients(tv);
    setup.planes = texture_planes(p, tv, quotients, one_w, false);
    if (options.rounding) {
        setup.perspective_rounding = choose_rounding(tv, quotients);
    }
}

/// The vertex colours' planes: c, or c/w when perspective-correct (then divided by the
/// triangle's 1/w plane at each pixel).
struct ColourPlanes {
    std::array<ScreenPlane, 3> rgb; ///< one per channel
    const ScreenPlane* one_w;       ///< 1/w when perspective-correct, else nullptr
};

/// Per-pixel lighting's planes: the view-space point and normal as a/w, linear on
/// screen, and 1/w (chapter 3's u/w over 1/w).
struct LightingPlanes {
    std::array<ScreenPlane, 3> point_w, normal_w; ///< x, y, z of p/w and n/w
    const ScreenPlane* one_w;                     ///< 1/w
};

/// One triangle on the pixel grid and its planes, each set up the first time a span
/// asks for it: a triangle that covers no pixel centre sets up none, one whose every
/// pixel the depth test hides none but the depth's. All run through the corners snapped
/// to 1/256 px, and one 1/w plane serves the texture, perspective-correct colours and
/// lighting; under perspective it is the depth stage's nearness, which is 1/w too.
class TrianglePlanes {
  public:
    /// Snaps the corners (Error beyond +-2^20 px) and checks a textured triangle against
    /// the mappers' ranges: both before the first pixel. (Always inlined: both drawing
    /// paths construct it once per triangle, and GCC would call it out of line.)
    /// `shading` is the triangle's ShadedCorners, or nullptr for a mesh that has none
    /// (whose colour and lighting stages do not run).
    [[gnu::always_inline]] TrianglePlanes(const MeshContext& m,
                                          const ScreenTriangle& triangle,
                                          const ShadedCorners* shading)
        : m_(m), triangle_(triangle), shading_(shading) {
        for (std::size_t k = 0; k < 3; ++k) {
            snapped[k] = snap_in_range(triangle.corners[k].position);
            p[k] = to_pixels(snapped[k]);
        }
        if (m.stages.texture) {
            check_mapper_ranges(m, triangle.corners);
        }
        if (m.stages.texture && m.scene.options.filter != SceneFilter::nearest) {
            snapped_corners = triangle.corners;
            for (std::size_t k = 0; k < 3; ++k) {
                snapped_corners[k].position = p[k];
            }
        }
    }

    std::array<FixedPoint2, 3> snapped{}; ///< the corners, 1/256 px
    std::array<Point2, 3> p{};            ///< the same in pixels
    /// The corners at p (the filter stage's; set only where it runs).
    std::array<TexturedVertex, 3> snapped_corners;

    /// The depth stage's nearness (1/w, or -z orthographic), linear on screen.
    const ScreenPlane& nearness() {
        if (!has_nearness_) {
            nearness_ = plane_through(p, triangle_.nearness);
            has_nearness_ = true;
        }
        return nearness_;
    }
    /// 1/w.
    const ScreenPlane& one_w() {
        if (m_.scene.camera.projection == Projection::perspective) {
            return nearness(); // the same values through the same corners
        }
        if (!has_one_w_) {
            const std::array<TexturedVertex, 3>& tv = triangle_.corners;
            one_w_ = plane_through(p, {1.0 / tv[0].w, 1.0 / tv[1].w, 1.0 / tv[2].w});
            has_one_w_ = true;
        }
        return one_w_;
    }
    /// The texture stage's planes and rounding.
    const TextureSetup& texture() {
        if (!has_texture_) {
            texture_setup(texture_, m_.scene.options, triangle_.corners, p, one_w());
            has_texture_ = true;
        }
        return texture_;
    }
    /// The colour stage's planes.
    const ColourPlanes& colour() {
        if (!has_colour_) {
            const std::array<TexturedVertex, 3>& tv = triangle_.corners;
            const bool corrected = m_.colour_perspective;
            for (int c = 0; c < 3; ++c) {
                std::array<double, 3> value{};
                for (std::size_t k = 0; k < 3; ++k) {
                    const double channel = shading_->colours[k][c];
                    value[k] = corrected ? channel / tv[k].w : channel;
                }
                colour_.rgb[static_cast<std::size_t>(c)] = plane_through(p, value);
            }
            colour_.one_w = corrected ? &one_w() : nullptr;
            has_colour_ = true;
        }
        return colour_;
    }
    /// The lighting stage's planes.
    const LightingPlanes& lighting() {
        if (!has_lighting_) {
            const std::array<TexturedVertex, 3>& tv = triangle_.corners;
            const std::array<double, 3> corner_one_w{1.0 / tv[0].w, 1.0 / tv[1].w,
                                                     1.0 / tv[2].w};
            for (int c = 0; c < 3; ++c) {
                std::array<double, 3> a{}, n{};
                for (std::size_t k = 0; k < 3; ++k) {
                    a[k] = shading_->points[k][c] * corner_one_w[k];
                    n[k] = shading_->normals[k][c] * corner_one_w[k];
                }
                lighting_.point_w[static_cast<std::size_t>(c)] = plane_through(p, a);
                lighting_.normal_w[static_cast<std::size_t>(c)] = plane_through(p, n);
            }
            lighting_.one_w = &one_w();
            has_lighting_ = true;
        }
        return lighting_;
    }

  private:
    const MeshContext& m_;
    const ScreenTriangle& triangle_;
    const ShadedCorners* shading_;
    bool has_nearness_ = false, has_one_w_ = false, has_texture_ = false,
         has_colour_ = false, has_lighting_ = false;
    ScreenPlane nearness_, one_w_;
    TextureSetup texture_;
    ColourPlanes colour_;
    LightingPlanes lighting_;
};

/// The mapper a span gets: the triangle's (texture_setup chose it: the scene's, affine
/// where the depth is constant, exact there and no divide, or auto's affine where the
/// triangle's bound fits), else auto's choice on the span within the budget.
MappedSpan span_mapper(const RenderOptions& options, const TextureSetup& setup,
                       const PerspectiveSpan<double>& ps) {
    if (setup.per_triangle) {
        return setup.mapped;
    }
    const AutoChoice choice = choose_span_mapper(ps, options.budget);
    return {choice.mapper, true, choice.divides};
}

/// Counts a span of `count` pixels mapped as `mapped` into auto's counter, the texture
/// stage's and the mapper's (its triangle once per triangle: `used` remembers), with
/// `seconds`. (Always inlined: called, it cost the big torus's frame 0.8M instructions.)
[[gnu::always_inline]] inline void count_mapped_span(RenderReport& report,
                                                     const MappedSpan& mapped, int count,
                                                     double seconds,
                                                     std::array<bool, 5>& used) {
    if (mapped.chosen) {
        report.auto_choice.spans += 1;
        report.auto_choice.pixels += count;
        report.auto_choice.divides += mapped.choice_divides;
    }
    const auto kind = static_cast<std::size_t>(mapped.mapper.kind);
    WorkCount& counter = report.mappers[kind];
    // mapper_divides's count; affine's none without the call (most spans of the big
    // torus)
    const long long divides = mapped.mapper.kind == MapperKind::affine
                                  ? 0
                                  : mapper_divides(mapped.mapper, count);
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

/// Whether pixel k of a span is seen: `visible` null means every pixel is.
inline bool seen(const char* visible, int k) {
    return visible == nullptr || visible[k] != 0;
}

//> depth-stage
/// The depth stage on one span: every pixel's nearness (the triangle's plane at the pixel
/// centre, rounded to a key) is tested and, where it passes, written; visible[k] says
/// which passed. Returns how many pixels are seen: a span with none is not shaded at
/// all. (Always inlined: it runs on every span, and called, it cost the big torus's
/// frame 8M instructions, 4 %.)
[[gnu::always_inline]] inline int
depth_stage(DepthBuffer& depth, const ScreenPlane& nearness, Span s, char* visible) {
    const int count = s.x_end - s.x_begin;
    const double x = s.x_begin + 0.5, y = s.y + 0.5; // the first pixel's centre
    const ScreenPlane q = nearness; // a copy: writing visible[k] cannot change it
    float* const keys = depth.row(s.y) + s.x_begin; // the span's keys (likewise)
    int shown = 0;
    for (int k = 0; k < count; ++k) {
        const float key = nearness_key(q.at(x + k, y));
        const bool seen = DepthBuffer::test_and_write(keys[k], key);
        visible[k] = seen;
        shown += seen;
    }
    return shown;
}
//< depth-stage

/// The shortest span the exact mapper's lanes take: a shorter one costs more in chunk
/// set-up than its divides save. On the big torus (spans of 2.7 pixels on average) the
/// lanes on every span took 188.0M instructions a frame, from 8 pixels 180.4M
/// (callgrind, AVX2); 4 gave 180.8M, 16 the same as 8.
constexpr int min_exact_lanes_pixels = 8;

/// map_span, except the exact mapper in double under FastPaths::exact_lanes (`lanes` not
/// portable) on spans of min_exact_lanes_pixels or more: its divides 2, 4 or 8 pixels at
/// once (exact_lanes.hpp), the same u and v, rounded to texels as map_span rounds them.
template <class TexelOut>
[[gnu::always_inline]] inline void
map_texture_span(SimdVariant lanes, Mapper mapper, Precision precision, TexelRounding r,
                 const PerspectiveSpan<double>& ps, const AffineSpan<double>& as,
                 TexelOut&& texel) {
    if (lanes != SimdVariant::portable && mapper.kind == MapperKind::exact &&
        precision == Precision::float64 && ps.count >= min_exact_lanes_pixels) {
        map_span_exact_lanes(lanes, ps, [&](int k, double u, double v) {
            texel(k, real_texel_index(u, r.u_modifier), real_texel_index(v, r.v_modifier),
                  u, v);
        });
        return;
    }
    map_span(mapper, precision, r, ps, as, texel);
}

//> texture-stage
/// The texture stage on one span: the span's mapper maps each pixel k to the indices i, j
/// of its texel and the coordinate u, v, which texel(k, i, j, u, v) takes (the exact
/// mapper in the instruction set `lanes`, portable on the teaching path). Returns the
/// mapper, for the report.
template <class TexelOut>
[[gnu::always_inline]] inline MappedSpan
texture_stage(const RenderOptions& options, const TextureSetup& texture, Span s,
              SimdVariant lanes, TexelOut&& texel) {
    if (texture.per_triangle && texture.mapped.mapper.kind == MapperKind::affine) {
        // Affine on the whole triangle: u and v step along the span, no 1/w is read.
        map_span(texture.mapped.mapper, options.precision, texture.affine_rounding,
                 PerspectiveSpan<double>{}, affine_span(texture.planes, s), texel);
        return texture.mapped;
    }
    const PerspectiveSpan<double> ps = perspective_span(texture.planes, s);
    const MappedSpan mapped =
        span_mapper(options, texture, ps); // auto: within the budget
    map_texture_span(lanes, mapped.mapper, options.precision,
                     texture.perspective_rounding, ps, AffineSpan<double>{}, texel);
    return mapped;
}
//< texture-stage

/// The texel (i, j) of the mesh's texture, under its wrap or by the masked fetch.
[[gnu::always_inline]] inline Rgba8 texel_at(const Texture& texture, bool masked,
                                             Wrap wrap, int i, int j) {
    return masked ? fetch_texel_masked(texture, i, j) : fetch_texel(texture, i, j, wrap);
}

/// Records pixel k of span `s` in the texel map: the texel's indices and coordinate.
void record_texel(TexelMap& map, int width, Span s, int k, int i, int j, double u,
                  double v) {
    const std::size_t at =
        static_cast<std::size_t>(s.y) * static_cast<std::size_t>(width) +
        static_cast<std::size_t>(s.x_begin + k);
    map.covered[at] = true;
    map.i[at] = i;
    map.j[at] = j;
    map.u[at] = u;
    map.v[at] = v;
}

//> colour-stage
/// The colour stage on a span of `row`: the colour planes at each pixel, one add per
/// channel per pixel (and the 1/w plane's, divided into c/w where perspective-correct).
/// The colour multiplies the texel where the mesh is textured and is the pixel where not.
void colour_stage(const ColourPlanes& planes, bool textured, Span s, Rgba8* row) {
    const double x = s.x_begin + 0.5, y = s.y + 0.5; // the first pixel's centre
    const std::array<ScreenPlane, 3>& rgb = planes.rgb;
    Colour c{rgb[0].at(x, y), rgb[1].at(x, y), rgb[2].at(x, y)};
    const Colour dc{rgb[0].g.dx, rgb[1].g.dx, rgb[2].g.dx};
    const bool corrected = planes.one_w != nullptr;
    double one_w = corrected ? planes.one_w->at(x, y) : 0.0; // as the exact mapper
    const double d_one_w = corrected ? planes.one_w->g.dx : 0.0;
    for (int k = 0; k < s.x_end - s.x_begin; ++k) {
        const Colour shade = corrected ? c * (1.0 / one_w) : c;
        row[k] = textured ? multiply(row[k], shade) : to_rgba8(shade);
        c += dc;
        one_w += d_one_w;
    }
}
//< colour-stage

//> lighting-stage
/// The lighting stage (Phong) on a span of `row`: lights each pixel seen that the stages
/// before made, at the view-space point and normal its planes give. Returns how many it
/// lit (one divide each, 1/w).
int lighting_stage(const MeshContext& m, const LightingPlanes& planes, Span s,
                   const char* visible, Rgba8* row) {
    const double x = s.x_begin + 0.5, y = s.y + 0.5; // the first pixel's centre
    const std::array<ScreenPlane, 3>&point_w = planes.point_w,
                                  &normal_w = planes.normal_w;
    int lit = 0;
    for (int k = 0; k < s.x_end - s.x_begin; ++k) {
        if (!seen(visible, k)) {
            continue;
        }
        const double px = x + k;
        const double w = 1.0 / planes.one_w->at(px, y); // the one divide per pixel
        const glm::dvec3 point{point_w[0].at(px, y) * w, point_w[1].at(px, y) * w,
                               point_w[2].at(px, y) * w};
        // n/w is n scaled by 1/w > 0: renormalising removes the scale, so the normal
        // needs no divide of its own.
        const glm::dvec3 normal = glm::normalize(glm::dvec3{
            normal_w[0].at(px, y), normal_w[1].at(px, y), normal_w[2].at(px, y)});
        const Colour base{row[k].r / 255.0, row[k].g / 255.0, row[k].b / 255.0};
        row[k] =
            to_rgba8(light_colour(*m.lights, m.scene.options.ambient, base, m.material,
                                  point, normal, to_eye(m.scene, point)));
        lit += 1;
    }
    return lit;
}
//< lighting-stage

/// The filter the triangle gets (chapter 8; nearest without a texture), with the mesh's
/// chain made ready for it.
Filter prepare_filter(MeshContext& m, const TrianglePlanes& planes) {
    if (!m.stages.texture || m.scene.options.filter == SceneFilter::nearest) {
        return Filter::nearest;
    }
    const Filter filter = triangle_filter(m.scene.options.filter, planes.snapped_corners);
    prepare_chain(m, filter);
    return filter;
}

/// Counts a triangle into every stage that will run on it. (Always inlined: called, it
/// cost the big torus's frame 1.2M instructions.)
[[gnu::always_inline]] inline void count_triangle(MeshContext& m, Filter filter) {
    if (!m.counts_triangle) {
        return; // another band of the threaded driver counts it
    }
    RenderReport& report = m.report;
    report.raster.triangles += 1;
    report.depth.triangles += m.depth != nullptr;
    report.texture.triangles += m.stages.texture;
    report.flat.triangles += !m.stages.texture && !m.stages.colour;
    report.colour.triangles += m.stages.colour;
    report.colour_perspective.triangles += m.stages.colour && m.colour_perspective;
    report.lighting.triangles += m.lights != nullptr;
    if (filter != Filter::nearest) {
        report.filter.triangles += 1;
        report.filter_triangles[filter == Filter::bilinear    ? 0
                                : filter == Filter::trilinear ? 1
                                                              : 2] += 1;
    }
}

/// A triangle's rasterized spans, those the depth test hid pixels of and those the
/// direct span mapped with the triangle's affine mapper, counted in locals span by span
/// and added to the report once (add_to): per span into the report, they cost the big
/// torus's frame 1.6M instructions more.
struct SpanCounts {
    long long spans = 0, pixels = 0;        ///< rasterized (and depth-tested)
    long long hidden_spans = 0, hidden = 0; ///< spans with a hidden pixel, those pixels
    /// Spans mapped by `affine`, the triangle's mapper (affine, no divide), their pixels
    /// and seconds: count_mapped_span's counts of each, added up.
    long long affine_spans = 0, affine_pixels = 0;
    double affine_seconds = 0.0;
    const MappedSpan* affine = nullptr;

    /// Adds them to the raster counts of `report`, to the depth stage's where it ran
    /// (`depth`: it tests every span rasterized) and to the texture stage's, auto's and
    /// the mapper's (the only mapper of the triangle: its triangle counted once).
    void add_to(RenderReport& report, bool depth) const {
        report.raster.spans += spans;
        report.raster.pixels += pixels;
        if (depth) {
            report.depth.spans += spans;
            report.depth.pixels += pixels;
            report.hidden.spans += hidden_spans;
            report.hidden.pixels += hidden;
        }
        if (affine_spans == 0) {
            return;
        }
        if (affine->chosen) {
            report.auto_choice.spans += affine_spans;
            report.auto_choice.pixels += affine_pixels;
            report.auto_choice.divides += affine->choice_divides * affine_spans;
        }
        WorkCount& counter = report.mappers[static_cast<std::size_t>(MapperKind::affine)];
        for (WorkCount* stage : {&counter, &report.texture}) {
            stage->spans += affine_spans;
            stage->pixels += affine_pixels;
            stage->seconds += affine_seconds;
        }
        counter.triangles += 1;
    }
};

/// The direct span's texels where the whole triangle is mapped affine in double:
/// map_span's affine mapper (u and v stepped from pixel 0, indices by real_texel_index),
/// inline, its rounding set up once per span and a hidden pixel's index not taken.
[[gnu::always_inline]] inline void direct_affine_span(const TextureSetup& texture, Span s,
                                                      const char* visible,
                                                      const Texture& texels, bool masked,
                                                      Wrap wrap, Rgba8* out) {
    const AffineSpan<double> as = affine_span(texture.planes, s);
    const RealTexelIndex index_u(texture.affine_rounding.u_modifier),
        index_v(texture.affine_rounding.v_modifier);
    double u = as.u, v = as.v;
    for (int k = 0; k < as.count; ++k) {
        if (seen(visible, k)) {
            out[k] = texel_at(texels, masked, wrap, index_u(u), index_v(v));
        }
        u += as.du;
        v += as.dv;
    }
}

/// The direct span (FastPaths::lean_spans, for a mesh lean_drawable accepts): the one
/// stage that makes the colour, nearest texels or the flat colour, writes each visible
/// pixel straight to the frame; a hidden pixel's texel is not read.
[[gnu::always_inline]] inline void
direct_span(MeshContext& m, TrianglePlanes& planes, StageTimer& timer, Span s,
            const char* visible, std::array<bool, 5>& used, SpanCounts& counts) {
    const int count = s.x_end - s.x_begin;
    Rgba8* const out = &m.frame.at(s.x_begin, s.y); // the span's pixels in a row
    if (!m.stages.texture) {
        const Rgba8 flat = m.flat;
        for (int k = 0; k < count; ++k) {
            if (seen(visible, k)) {
                out[k] = flat;
            }
        }
        m.report.flat.spans += 1;
        m.report.flat.pixels += count;
        return;
    }
    const TextureSetup& texture = planes.texture(); // set up in the rasterizer's time
    // Locals: a write through `out` may alias anything, and would reload them per pixel.
    const Texture& texels = *m.texture;
    const Wrap wrap = m.mesh.wrap;
    const bool masked = m.masked_fetch;
    double spent = 0.0;
    if (texture.per_triangle && texture.mapped.mapper.kind == MapperKind::affine &&
        m.scene.options.precision == Precision::float64) {
        timer.timed(spent, [&] {
            direct_affine_span(texture, s, visible, texels, masked, wrap, out);
            return 0;
        });
        counts.affine_spans += 1; // count_mapped_span's counts, once per triangle
        counts.affine_pixels += count;
        counts.affine_seconds += spent;
        counts.affine = &texture.mapped;
        return;
    }
    const MappedSpan mapped = timer.timed(spent, [&] {
        return texture_stage(m.scene.options, texture, s, m.lanes,
                             [&](int k, int i, int j, double, double) {
                                 if (seen(visible, k)) {
                                     out[k] = texel_at(texels, masked, wrap, i, j);
                                 }
                             });
    });
    count_mapped_span(m.report, mapped, count, spent, used);
}

/// The shaded span: the stages shade a row of pixels in turn (texture, filter, colour or
/// tint, lighting), and the row's visible pixels go to the frame.
void shaded_span(MeshContext& m, TrianglePlanes& planes, Filter filter, StageTimer& timer,
                 Span s, const char* visible, std::array<bool, 5>& used) {
    const int count = s.x_end - s.x_begin;
    RenderReport& report = m.report;
    m.row.assign(static_cast<std::size_t>(count), m.flat);
    Rgba8* const row = m.row.data();
    if (m.stages.texture) {
        const TextureSetup& texture = planes.texture();
        double spent = 0.0;
        const MappedSpan mapped = timer.timed(spent, [&] {
            return texture_stage(
                m.scene.options, texture, s, m.lanes,
                [&](int k, int i, int j, double u, double v) {
                    row[k] = texel_at(*m.texture, m.masked_fetch, m.mesh.wrap, i, j);
                    if (m.coordinates != nullptr && seen(visible, k)) {
                        record_texel(*m.coordinates, m.frame.width(), s, k, i, j, u, v);
                    }
                });
        });
        count_mapped_span(report, mapped, count, spent, used);
    }
    if (filter != Filter::nearest) { // chapter 8's filter stage (filter_stage.cpp)
        const int filtered = timer.timed(report.filter.seconds, [&] {
            return filter_span(*m.chain, {.filter = filter, .wrap = m.mesh.wrap},
                               planes.snapped_corners, s, visible, row);
        });
        report.filter.spans += 1;
        report.filter.pixels += filtered;
        report.filter.divides += 3LL * filtered; // u, v and 1/q^2
    }
    if (m.stages.colour) { // colours are linear on screen: one add per channel
        const ColourPlanes& colour = planes.colour();
        timer.timed(report.colour.seconds, [&] {
            colour_stage(colour, m.stages.texture, s, row);
            return 0;
        });
        report.colour.spans += 1;
        report.colour.pixels += count;
        if (m.colour_perspective) {
            report.colour_perspective.spans += 1;
            report.colour_perspective.pixels += count;
            report.colour_perspective.divides += count;
        }
    } else if (m.stages.texture && m.stages.tint) {
        for (int k = 0; k < count; ++k) {
            row[k] = multiply(row[k], m.mesh.colour);
        }
    } else if (!m.stages.texture) {
        report.flat.spans += 1;
        report.flat.pixels += count;
    }
    if (m.lights != nullptr) { // Phong: light the pixel the stages above made
        const LightingPlanes& lighting = planes.lighting();
        const int lit = timer.timed(report.lighting.seconds, [&] {
            return lighting_stage(m, lighting, s, visible, row);
        });
        report.lighting.spans += 1;
        report.lighting.pixels += lit;
        report.lighting.divides += lit;
    }
    for (int k = 0; k < count; ++k) {
        if (seen(visible, k)) {
            m.frame.at(s.x_begin + k, s.y) = row[k];
            if (m.coordinates != nullptr && !m.stages.texture) { // an untextured pixel
                m.coordinates->covered[static_cast<std::size_t>(s.y) *
                                           static_cast<std::size_t>(m.frame.width()) +
                                       static_cast<std::size_t>(s.x_begin + k)] = false;
            }
        }
    }
}

//> draw-triangle
/// Rasterizes one projected triangle and runs the mesh's stages on each span: the depth
/// test, then the direct span (`direct`) or the shaded one. The stages return what they
/// did and are counted here; the timer wraps each stage call (StageTimer).
template <bool direct>
void draw_triangle(MeshContext& m, const ScreenTriangle& triangle,
                   const ShadedCorners* shading) {
    TrianglePlanes planes(m, triangle, shading); // Error before the first pixel
    const Filter filter = direct ? Filter::nearest : prepare_filter(m, planes);
    count_triangle(m, filter);
    StageTimer timer{m.timed};
    const Clock::time_point start = timer.now();
    std::array<bool, 5> mapper_used{};
    SpanCounts counts; // added to the report after the last span
    const Viewport screen{m.frame.width(), std::min(m.frame.height(), m.end_row)};
    scanline_spans_in_range(planes.snapped, screen, [&](Span s) { // snapped in range
        if (s.y < m.first_row) {
            return; // above the threaded driver's band
        }
        const int count = s.x_end - s.x_begin;
        counts.spans += 1;
        counts.pixels += count;
        const char* visible = nullptr; // every pixel seen
        // The depth test first, on every pixel: a span it hides is not shaded.
        if (m.depth != nullptr) {
            char* const tested = m.visible.data();
            const int shown = timer.timed(m.report.depth.seconds, [&] {
                return depth_stage(*m.depth, planes.nearness(), s, tested);
            });
            counts.hidden_spans += shown < count;
            counts.hidden += count - shown;
            if (shown == 0) {
                return;
            }
            visible = shown < count ? tested : nullptr;
        }
        if constexpr (direct) {
            direct_span(m, planes, timer, s, visible, mapper_used, counts);
        } else {
            shaded_span(m, planes, filter, timer, s, visible, mapper_used);
        }
    });
    counts.add_to(m.report, m.depth != nullptr);
    m.report.raster.seconds += timer.since(start) - timer.shading;
}
//< draw-triangle

/// Whether the direct span can draw the mesh's triangles: its only stages are the
/// texture stage with nearest texels (or the flat colour) and the depth stage, and no
/// texel coordinates are recorded.
bool lean_drawable(const MeshContext& m) {
    return !m.stages.colour && !m.stages.tint && m.lights == nullptr &&
           m.coordinates == nullptr &&
           (!m.stages.texture || m.scene.options.filter == SceneFilter::nearest);
}

} // namespace

void draw_mesh(MeshContext& m, const std::vector<ScreenTriangle>& triangles,
               const std::vector<ShadedCorners>& shading, bool lean_spans) {
    // Stage times: the mesh's drawing is timed whole, and split among the stages as on
    // the timed sample of its triangles (timed_triangles_per_mesh).
    const RenderReport before = m.report;
    const Clock::time_point t0 = Clock::now();
    const bool direct = lean_spans && lean_drawable(m);
    m.visible.resize(static_cast<std::size_t>(m.frame.width())); // written before read
    const std::size_t interval = timed_triangle_interval(triangles.size());
    std::size_t until_timed = 0; // triangles before the next timed one
    for (std::size_t k = 0; k < triangles.size(); ++k) {
        m.timed = until_timed == 0;
        until_timed = m.timed ? interval - 1 : until_timed - 1;
        assert(shading.empty() || shading.size() == triangles.size());
        const ShadedCorners* corners = shading.empty() ? nullptr : &shading[k];
        if (direct) {
            draw_triangle<true>(m, triangles[k], corners);
        } else {
            draw_triangle<false>(m, triangles[k], corners);
        }
    }
    share_drawing_time(m.report, before, seconds_since(t0));
}

bool draws_direct(const MeshContext& m, bool lean_spans) {
    return lean_spans && lean_drawable(m);
}

void draw_one_triangle(MeshContext& m, const ScreenTriangle& triangle,
                       const ShadedCorners* shading, bool direct) {
    if (direct) {
        draw_triangle<true>(m, triangle, shading);
    } else {
        draw_triangle<false>(m, triangle, shading);
    }
}

void prepare_mesh_chain(MeshContext& m, const std::vector<ScreenTriangle>& triangles) {
    for (const ScreenTriangle& triangle : triangles) {
        if (*m.full_chain) {
            return; // nothing a later triangle asks for can change it
        }
        const TrianglePlanes planes(m, triangle, nullptr);
        prepare_filter(m, planes);
    }
}

} // namespace exactpixels
