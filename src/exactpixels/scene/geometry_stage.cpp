// geometry_stage.cpp: chapter 7's geometry stage (scene_renderer.hpp declares it). Every
// mesh is an indexed mesh: each distinct position is moved to view space, given its
// outcode, projected and checked once; each triangle is then rejected, lit per vertex,
// clipped and culled from its corners' outcodes, projections and attributes.
#include "exactpixels/base/error.hpp"
#include "exactpixels/fast/worker_pool.hpp"
#include "exactpixels/raster/fill_work.hpp"
#include "exactpixels/scene/camera.hpp"
#include "exactpixels/scene/geometry_lanes.hpp"
#include "exactpixels/scene/lighting.hpp"
#include "exactpixels/scene/mesh_transform.hpp"
#include "exactpixels/scene/render_report.hpp"
#include "exactpixels/scene/scene_pipeline.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "exactpixels/texture/clipping.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>
#include <type_traits>
#include <vector>

namespace exactpixels {

namespace {

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

/// Three numbers per corner of `view` (a colour, a normal) at the corners of the pieces
/// clip_triangle cuts `view` into at `planes`: clip_triangle carries two numbers as the
/// texture coordinate, and the cuts depend only on the positions, so two more passes
/// with the values in place of uv cut them at the same parameters.
std::vector<std::array<glm::dvec3, 3>>
clip_values(const std::array<ViewVertex, 3>& view,
            const std::array<glm::dvec3, 3>& values,
            const std::vector<ViewPlane>& planes) {
    std::array<ViewVertex, 3> xy = view, z = view;
    for (std::size_t k = 0; k < 3; ++k) {
        xy[k].uv = {values[k].x, values[k].y};
        z[k].uv = {values[k].z, 0.0};
    }
    const auto cxy = fan(clip_triangle(xy, planes)), cz = fan(clip_triangle(z, planes));
    assert(cxy.size() == cz.size());
    std::vector<std::array<glm::dvec3, 3>> out(cxy.size());
    for (std::size_t t = 0; t < out.size(); ++t) {
        for (std::size_t k = 0; k < 3; ++k) {
            assert(cxy[t][k].position == cz[t][k].position);
            out[t][k] = {cxy[t][k].uv.x, cxy[t][k].uv.y, cz[t][k].uv.x};
        }
    }
    return out;
}

/// Chapter 6's clipping, at every plane of `planes`, of a triangle with its texture
/// coordinates, and its vertex colours and normals where asked (clip_values). A cut
/// normal is shorter than 1; the lighting stage renormalises it.
std::vector<ClippedCorners> clip_corners(const ClippedCorners& whole,
                                         const std::vector<ViewPlane>& planes,
                                         bool with_colours, bool with_normals) {
    const std::vector<std::array<ViewVertex, 3>> uv =
        fan(clip_triangle(whole.view, planes));
    std::vector<ClippedCorners> pieces(uv.size(),
                                       whole); // colours, normals unused unless asked
    for (std::size_t t = 0; t < pieces.size(); ++t) {
        pieces[t].view = uv[t];
    }
    if (with_normals) {
        const auto normals = clip_values(whole.view, whole.normals, planes);
        for (std::size_t t = 0; t < pieces.size(); ++t) {
            pieces[t].normals = normals[t];
        }
    }
    if (with_colours) {
        const auto colours = clip_values(whole.view, whole.colours, planes);
        for (std::size_t t = 0; t < pieces.size(); ++t) {
            pieces[t].colours = colours[t];
        }
    }
    return pieces;
}

//> outcodes
/// The most planes a view volume has: the screen's four edges, near, far, and the
/// guard band's four.
constexpr std::size_t max_outcode_planes = 10;

/// The view volume's planes as bits of an outcode: bit i is set when a point lies
/// outside plane i. A plane in both of the volume's lists (near, far) has one bit. The
/// planes a x + b y + c z + d are held as four rows of coefficients, each plane once,
/// then planes no point lies outside (0 x + 0 y + 0 z + 1: 1, or NaN where a coordinate
/// is not finite), so that every outcode runs the same ten sums, two at a time.
struct OutcodePlanes {
    std::array<double, max_outcode_planes> a{}, b{}, c{}, d{};
    std::uint32_t reject = 0; ///< the bits of ViewVolume::reject's planes
    std::uint32_t clip = 0;   ///< the bits of ViewVolume::clip's planes
};

/// The outcode planes of `volume`.
OutcodePlanes outcode_planes(const ViewVolume& volume) {
    std::vector<ViewPlane> planes;
    const auto bit_of = [&planes](const ViewPlane& p) {
        std::size_t i = 0;
        while (i < planes.size() &&
               !(planes[i].normal == p.normal && planes[i].offset == p.offset)) {
            ++i;
        }
        if (i == planes.size()) {
            planes.push_back(p);
        }
        return std::uint32_t{1} << i;
    };
    OutcodePlanes codes;
    for (const ViewPlane& p : volume.reject) {
        codes.reject |= bit_of(p);
    }
    for (const ViewPlane& p : volume.clip) {
        codes.clip |= bit_of(p);
    }
    assert(planes.size() <= max_outcode_planes);
    codes.d.fill(1.0);
    for (std::size_t i = 0; i < planes.size(); ++i) {
        codes.a[i] = planes[i].normal.x;
        codes.b[i] = planes[i].normal.y;
        codes.c[i] = planes[i].normal.z;
        codes.d[i] = planes[i].offset;
    }
    return codes;
}

/// The outcode of the view-space point p: a bit for each plane whose value there,
/// computed as plane_value computes it, is < 0 (false for NaN): the test outside_one
/// and any_outside make at each corner.
std::uint32_t outcode(const OutcodePlanes& codes, const glm::dvec3& p) {
    std::array<double, max_outcode_planes> value{};
    for (std::size_t i = 0; i < max_outcode_planes; ++i) { // vectorised: no branch
        value[i] = codes.a[i] * p.x + codes.b[i] * p.y + codes.c[i] * p.z + codes.d[i];
    }
    std::uint32_t code = 0;
    for (std::size_t i = 0; i < max_outcode_planes; ++i) {
        code |= static_cast<std::uint32_t>(value[i] < 0.0) << i;
    }
    return code;
}
//< outcodes

/// The outcode planes in pairs: PlanePairs::negative_bits is outcode's lean form (the
/// same sums in the same order; tests/ch07_fast_paths.cpp compares the two).
using OutcodePairs = PlanePairs<max_outcode_planes>;

/// Twice the signed screen area of the triangle p0 p1 p2; negative when it faces the
/// camera (its corners run counter-clockwise as seen from its front).
double screen_area2(Point2 p0, Point2 p1, Point2 p2) {
    const Point2 a = p1 - p0, b = p2 - p0;
    return a.x * b.y - a.y * b.x;
}

/// The largest magnitude a mapper can hold in `precision` (float overflows above
/// 3.4e38, long before double does).
double largest(Precision precision) {
    return precision == Precision::float32 ? double(std::numeric_limits<float>::max())
                                           : std::numeric_limits<double>::max();
}

/// Stops NaN and infinity before the first pixel: throws Error when a projected corner
/// has a coordinate, depth, 1/w or u/w, v/w that is not finite in the precision the
/// mappers will use.
void check_finite(const TexturedVertex& v, Precision precision, std::size_t triangle) {
    const double limit = largest(precision);
    const double one_w = 1.0 / v.w;
    for (const double value :
         {v.position.x, v.position.y, v.w, one_w, v.uv.x * one_w, v.uv.y * one_w}) {
        if (!(std::abs(value) <= limit)) { // false for NaN too
            throw Error(fmt::format(
                "triangle {}: a corner projects to a value that is not "
                "finite in {} (w = {}, 1/w = {})",
                triangle, precision == Precision::float32 ? "float" : "double", v.w,
                one_w));
        }
    }
}

/// World to view space along the camera's axes: the components of d on right, up and
/// forward, each dot product in glm::dot's order. A point p is moved as p - eye.
glm::dvec3 to_view(const CameraFrame& camera, const glm::dvec3& d) {
    const glm::dvec3 &r = camera.right, &u = camera.up, &f = camera.forward;
    return {d.x * r.x + d.y * r.y + d.z * r.z, d.x * u.x + d.y * u.y + d.z * u.z,
            d.x * f.x + d.y * f.y + d.z * f.z};
}

/// What the geometry stage knows of the scene, the same for every mesh.
struct StageSetup {
    const Scene& scene;
    const CameraFrame camera;
    const bool perspective;
    const Pinhole lens;
    const ViewVolume volume;
    const OutcodePlanes codes;
    const double limit; ///< largest(scene.options.precision)
    const std::vector<ViewLight>& lights;
    const bool lit;           ///< no light, no lighting stage
    const bool lean;          ///< run_geometry's `lean`: the lean forms
    const OutcodePairs pairs; ///< `codes` in pairs
    StageSetup(const Scene& s, const CameraFrame& frame, const std::vector<ViewLight>& l,
               bool lean_forms)
        : scene(s), camera(frame),
          perspective(s.camera.projection == Projection::perspective), lens(pinhole(s)),
          volume(view_volume(s, lens)), codes(outcode_planes(volume)),
          limit(largest(s.options.precision)), lights(l), lit(!s.lights.empty()),
          lean(lean_forms), pairs(codes.a, codes.b, codes.c, codes.d) {}
};

/// A mesh position as the geometry stage moves it, once for all the corners at it.
/// (No default values: MeshPass's list of them is made without writing it, and
/// move_position writes every field.)
struct MovedPosition {
    glm::dvec3 view;    ///< view space
    Point2 at;          ///< on screen (where `projected`)
    double w;           ///< project_vertex's depth (where `projected`)
    double one_w;       ///< 1/w, as check_finite computes it
    double nearness;    ///< 1/w (perspective) or -z (orthographic)
    std::uint32_t code; ///< the planes it lies outside (OutcodePlanes)
    bool projected;     ///< inside every clipping plane, and project_vertex took it
    bool finite;        ///< projected, and at, w and 1/w within the precision's limit
};
static_assert(std::is_trivially_default_constructible_v<MovedPosition>);

/// Position p moved: to view space, its outcode, and where no clipping plane has it
/// outside (only then is a corner at it projected as it is) project_vertex's value and
/// check_finite's tests of it (all but u/w and v/w, which belong to a corner).
MovedPosition move_position(const StageSetup& s, const glm::dvec3& p) {
    MovedPosition m{}; // zero where not projected
    m.view = to_view(s.camera, p - s.camera.eye);
    m.code = s.lean ? s.pairs.negative_bits(m.view) : outcode(s.codes, m.view);
    const bool finite =
        std::isfinite(m.view.x) && std::isfinite(m.view.y) && std::isfinite(m.view.z);
    // project() refuses a point that is not finite; the triangle asks it again, to throw.
    m.projected = (m.code & s.codes.clip) == 0 && (finite || !s.perspective);
    if (m.projected) {
        // project_vertex; under perspective project()'s two divides written out, since
        // z >= near > 0 and finite pass its checks (tests/ch07_fast_paths.cpp compares).
        const TexturedVertex c =
            s.perspective
                ? TexturedVertex{{s.lens.centre.x + s.lens.focal * m.view.x / m.view.z,
                                  s.lens.centre.y - s.lens.focal * m.view.y / m.view.z},
                                 m.view.z,
                                 {}}
                : project_vertex(s.scene, s.lens, {m.view, {}});
        m.at = c.position;
        m.w = c.w;
        m.one_w = 1.0 / c.w;
        m.nearness = s.perspective ? m.one_w : -m.view.z;
        m.finite = std::abs(m.at.x) <= s.limit && std::abs(m.at.y) <= s.limit &&
                   std::abs(m.w) <= s.limit && std::abs(m.one_w) <= s.limit;
    }
    return m;
}

/// The three moved positions at a triangle's corners.
using MovedCorners = std::array<const MovedPosition*, 3>;

/// Where the geometry stage puts what a run of a mesh's triangles makes: the mesh's own
/// lists in SceneGeometry, or (threaded) one thread's part, joined in order after.
struct MeshOutput {
    std::vector<ScreenTriangle>& out;
    std::vector<ShadedCorners>& shading; ///< filled only where the mesh is `shaded`
    ScreenBox& box;                      ///< the mesh's footprint
    RenderReport& report;
};

/// The geometry stage on one mesh: its positions moved once, then its triangles
/// decided, lit, cut and stored.
class MeshPass {
  public:
    MeshPass(const StageSetup& setup, const SceneMesh& mesh, std::size_t i,
             RenderReport& report, SceneGeometry& geometry);
    void run();

    // The threaded stage's two steps (run_geometry with threads > 1).
    std::size_t position_count() const { return positions->size(); }
    std::size_t triangle_count() const { return mesh.triangles.size(); }
    /// Positions first .. end - 1 moved, into `moved` (made position_count() long).
    void move_positions(std::size_t first, std::size_t end);
    /// Triangles first .. end - 1 decided in order into `to`, once every position moved.
    void triangles(std::size_t first, std::size_t end, MeshOutput& to) const;

  private:
    void triangle(std::size_t index, MeshOutput& to) const;
    void triangles_lean(std::size_t first, std::size_t end, MeshOutput& to) const;
    void move_positions_lean(std::size_t first, std::size_t end);
    void check_corners(std::size_t index, const MovedCorners& m) const;
    void light(std::size_t index, const std::array<glm::dvec3, 3>& points,
               std::array<Colour, 3>& colours, std::array<glm::dvec3, 3>& normals,
               RenderReport& report) const;
    void cut_triangle(std::size_t index, const MovedCorners& m, MeshOutput& to) const;
    void keep_piece(std::size_t index, const ClippedCorners& piece, MeshOutput& to) const;
    TexturedVertex checked(const TexturedVertex& corner, std::size_t index) const;

    const StageSetup& s;
    const SceneMesh& mesh;
    MeshOutput lists; ///< the mesh's lists in SceneGeometry, and the report
    bool with_colours = false, gouraud = false, phong = false;
    bool shaded = false; ///< the colour or the lighting stage reads ShadedCorners
    std::vector<CornerNormals> normals; ///< world space, per triangle (lit meshes)
    SharedPositions own; ///< the mesh's positions indexed here, when it has no index
    const std::vector<glm::dvec3>* positions = nullptr; ///< the mesh's or own's
    const std::vector<std::array<std::uint32_t, 3>>* corners = nullptr; ///< likewise
    const std::vector<std::array<TexCoord, 3>>* uvs = nullptr;          ///< likewise
    std::unique_ptr<MovedPosition[]> moved; ///< per position, by move_positions
};

MeshPass::MeshPass(const StageSetup& setup, const SceneMesh& m, std::size_t i,
                   RenderReport& r, SceneGeometry& geometry)
    : s(setup), mesh(m), lists{geometry.meshes[i], geometry.shading[i],
                               geometry.footprints[i].box, r} {
    RenderReport& report = lists.report;
    MeshFootprint& footprint = geometry.footprints[i];
    with_colours = mesh_stages(s.scene, mesh).colour;
    shaded = with_colours || s.lit;
    gouraud = s.lit && mesh_shading(s.scene, mesh) == Shading::gouraud;
    phong = s.lit && !gouraud;
    report.gouraud_meshes += gouraud;
    report.phong_meshes += phong;
    footprint.name = fmt::format("mesh[{}]", i); // as messages name it
    // Only `depth = "auto"` asks (a scan of every corner per corner of one face).
    footprint.can_overlap_itself =
        s.scene.options.depth == DepthMode::automatic && can_overlap_itself(mesh);
    positions = &mesh.positions;
    corners = &mesh.corner_positions;
    uvs = &mesh.corner_uvs; // a mesh made in code has none of the three:
    if (corners->size() != mesh.triangles.size() || uvs->size() != corners->size()) {
        own = shared_positions(mesh.triangles);
        positions = &own.positions;
        corners = &own.corners;
        uvs = &own.uvs;
    }
    assert(index_matches(mesh.triangles, {*positions, *corners, *uvs}));
    if (s.lit) { // lean: smooth normals summed per shared position
        normals =
            s.lean ? mesh_normals_shared(mesh, *positions, *corners) : mesh_normals(mesh);
    }
    moved.reset(new MovedPosition[positions->size()]); // unwritten: move_positions fills
}

TexturedVertex MeshPass::checked(const TexturedVertex& corner, std::size_t index) const {
    try {
        check_finite(corner, s.scene.options.precision, index);
    } catch (const Error& error) { // naming the mesh
        throw Error(fmt::format("{}: {}", mesh.origin, error.what()));
    }
    return corner;
}

//> geometry-mesh
/// Every position moved once, then every triangle.
void MeshPass::run() {
    const Clock::time_point t0 = Clock::now(); // the whole mesh: clocks cost time
    move_positions(0, position_count());
    triangles(0, triangle_count(), lists);
    lists.report.geometry.seconds += seconds_since(t0);
}

/// One triangle: rejected when its corners' outcodes share a plane of the screen or
/// the depth range, cut when one of them is outside a clipping plane, else projected
/// as it is, culled, stored and lit.
void MeshPass::triangle(std::size_t index, MeshOutput& to) const {
    const std::array<std::uint32_t, 3>& at = (*corners)[index];
    const MovedCorners m{&moved[at[0]], &moved[at[1]], &moved[at[2]]};
    to.report.geometry.triangles += 1;
    if ((m[0]->code & m[1]->code & m[2]->code & s.codes.reject) != 0) {
        to.report.rejected.triangles += 1; // all outside one plane: covers no pixel
        return;
    }
    if (((m[0]->code | m[1]->code | m[2]->code) & s.codes.clip) != 0) {
        cut_triangle(index, m, to); // lit, then cut into pieces
        return;
    }
    check_corners(index, m); // projected as they are: each finite, or an error
    if (mesh.cull_back && screen_area2(m[0]->at, m[1]->at, m[2]->at) >= 0.0) {
        to.report.culling.triangles += 1; // before it is lit
        return;
    }
    const std::array<SceneVertex, 3>& triangle = mesh.triangles[index];
    ScreenTriangle& t = to.out.emplace_back();
    for (std::size_t k = 0; k < 3; ++k) {
        t.corners[k] = {m[k]->at, m[k]->w, triangle[k].uv};
        t.nearness[k] = m[k]->nearness;
        to.box.add(m[k]->at);
    }
    if (shaded) {
        ShadedCorners& c = to.shading.emplace_back();
        for (std::size_t k = 0; k < 3; ++k) {
            c.points[k] = m[k]->view;
            c.colours[k] = triangle[k].colour;
        }
        if (s.lit) {
            light(index, c.points, c.colours, c.normals, to.report);
        }
    }
}
//< geometry-mesh

void MeshPass::move_positions(std::size_t first, std::size_t end) {
    if (s.lean && s.perspective) {
        move_positions_lean(first, end);
        return;
    }
    for (std::size_t p = first; p < end; ++p) {
        moved[p] = move_position(s, (*positions)[p]);
    }
}

/// Lean form of move_position on positions first .. end - 1 under perspective: the
/// same values, with the camera, the lens and the planes in locals and each position
/// written in place.
void MeshPass::move_positions_lean(std::size_t first, std::size_t end) {
    const CameraFrame camera = s.camera;
    const OutcodePairs pairs = s.pairs;
    const std::uint32_t clip = s.codes.clip;
    const Point2 centre = s.lens.centre;
    const double focal = s.lens.focal, limit = s.limit;
    const glm::dvec3* const position = positions->data();
    for (std::size_t p = first; p < end; ++p) {
        MovedPosition& m = moved[p];
        const glm::dvec3 view = to_view(camera, position[p] - camera.eye);
        m.view = view;
        m.code = pairs.negative_bits(view);
        m.projected = (m.code & clip) == 0 && std::isfinite(view.x) &&
                      std::isfinite(view.y) && std::isfinite(view.z);
        if (!m.projected) {
            m.at = {0.0, 0.0};
            m.w = m.one_w = m.nearness = 0.0;
            m.finite = false;
            continue;
        }
        m.at = {centre.x + focal * view.x / view.z, centre.y - focal * view.y / view.z};
        m.w = view.z;
        m.one_w = 1.0 / view.z;
        m.nearness = m.one_w;
        m.finite = std::abs(m.at.x) <= limit && std::abs(m.at.y) <= limit &&
                   std::abs(m.w) <= limit && std::abs(m.one_w) <= limit;
    }
}

void MeshPass::triangles(std::size_t first, std::size_t end, MeshOutput& to) const {
    to.out.reserve(to.out.size() + (end - first) / 2); // a closed mesh shows about half
    to.shading.reserve(shaded ? to.out.capacity() : 0);
    if (s.lean && !shaded) {
        triangles_lean(first, end, to);
        return;
    }
    for (std::size_t index = first; index < end; ++index) {
        triangle(index, to);
    }
}

/// Lean form of triangle() on a stretch of an unshaded mesh: the same decisions, lists,
/// box, counts and errors, with the loop's constants and the box held in locals, the
/// corners' finite tests and the box two values at a time.
void MeshPass::triangles_lean(std::size_t first, std::size_t end, MeshOutput& to) const {
    const std::array<std::uint32_t, 3>* const at = corners->data();
    const std::array<TexCoord, 3>* const uv = uvs->data(); // packed: see SceneMesh
    const MovedPosition* const position = moved.get();
    const std::uint32_t reject = s.codes.reject, clip = s.codes.clip;
    const bool cull_back = mesh.cull_back;
    const PlanePair limit{s.limit, s.limit};
    StretchCounts counts{to.report};
    // The box as two pairs, (x0, y0) and (x1, y1), grown as ScreenBox::add grows it.
    PlanePair low{to.box.x0, to.box.y0}, high{to.box.x1, to.box.y1};
    const auto box = [&] { return ScreenBox{low[0], low[1], high[0], high[1]}; };
    for (std::size_t index = first; index < end; ++index) {
        const MovedPosition &m0 = position[at[index][0]], &m1 = position[at[index][1]],
                            &m2 = position[at[index][2]];
        if ((m0.code & m1.code & m2.code & reject) != 0) {
            counts.rejected += 1;
            continue;
        }
        if (((m0.code | m1.code | m2.code) & clip) != 0) {
            counts.triangles = index + 1 - first; // cut_triangle may throw
            to.box = box();
            cut_triangle(index, {&m0, &m1, &m2}, to);
            low = PlanePair{to.box.x0, to.box.y0};
            high = PlanePair{to.box.x1, to.box.y1};
            continue;
        }
        const std::array<TexCoord, 3>& t = uv[index];
        const BitsPair uv_within = within(PlanePair{t[0].x, t[0].y} * m0.one_w, limit) &
                                   within(PlanePair{t[1].x, t[1].y} * m1.one_w, limit) &
                                   within(PlanePair{t[2].x, t[2].y} * m2.one_w, limit);
        const bool uvs_within = (uv_within[0] & uv_within[1]) != 0;
        if (!(m0.finite & m1.finite & m2.finite & uvs_within)) {
            counts.triangles = index + 1 - first;
            check_corners(index, {&m0, &m1, &m2}); // throws check_finite's error
        }
        if (cull_back && screen_area2(m0.at, m1.at, m2.at) >= 0.0) {
            counts.culled += 1;
            continue;
        }
        const MovedCorners m{&m0, &m1, &m2};
        ScreenTriangle& kept = to.out.emplace_back(); // field by field: no copy
        for (std::size_t k = 0; k < 3; ++k) {
            kept.corners[k].position = m[k]->at;
            kept.corners[k].w = m[k]->w;
            kept.corners[k].uv = t[k];
            kept.nearness[k] = m[k]->nearness;
            const PlanePair p{m[k]->at.x, m[k]->at.y};
            low = p < low ? p : low;    // std::min(x0, p.x): the first of equals
            high = high < p ? p : high; // std::max(x1, p.x): likewise
        }
    }
    counts.triangles = end - first;
    to.box = box();
}

/// Stops a triangle drawn uncut whose corner fails check_finite's tests, with its
/// error (or project()'s, for a position not finite): the tests of the corner's
/// position (MovedPosition::finite) and of its u/w and v/w, in its order.
void MeshPass::check_corners(std::size_t index, const MovedCorners& m) const {
    const std::array<SceneVertex, 3>& triangle = mesh.triangles[index];
    for (std::size_t k = 0; k < 3; ++k) {
        const MovedPosition& p = *m[k];
        const TexCoord uv = triangle[k].uv;
        if (!(p.finite && std::abs(uv.x * p.one_w) <= s.limit &&
              std::abs(uv.y * p.one_w) <= s.limit)) { // each throws
            checked(p.projected ? TexturedVertex{p.at, p.w, uv}
                                : project_vertex(s.scene, s.lens, {p.view, uv}),
                    index);
        }
    }
}

/// The normals at the view-space `points` of a triangle, and under Gouraud the lit
/// colours in place of `colours`.
void MeshPass::light(std::size_t index, const std::array<glm::dvec3, 3>& points,
                     std::array<Colour, 3>& colours,
                     std::array<glm::dvec3, 3>& at_normals, RenderReport& report) const {
    const Clock::time_point l0 = Clock::now();
    for (std::size_t k = 0; k < 3; ++k) {
        at_normals[k] = to_view(s.camera, normals[index][k]);
    }
    //> gouraud-vertices
    if (gouraud) { // the lit colour replaces the corner's colour
        const Material material{mesh.specular, mesh.shininess};
        for (std::size_t k = 0; k < 3; ++k) {
            const Colour diffuse = mesh.vertex_colours ? colours[k] : mesh.colour;
            colours[k] =
                light_colour(s.lights, s.scene.options.ambient, diffuse, material,
                             points[k], at_normals[k], to_eye(s.scene, points[k]));
        }
        report.lit_vertices += 3;
    }
    //< gouraud-vertices
    report.lighting.seconds += seconds_since(l0);
}

/// A triangle with a corner outside a clipping plane: lit, then cut into pieces.
void MeshPass::cut_triangle(std::size_t index, const MovedCorners& m,
                            MeshOutput& to) const {
    const std::array<SceneVertex, 3>& triangle = mesh.triangles[index];
    ClippedCorners whole{};
    for (std::size_t k = 0; k < 3; ++k) {
        whole.view[k] = {m[k]->view, triangle[k].uv};
        whole.colours[k] = triangle[k].colour;
    }
    if (s.lit) {
        light(index, {m[0]->view, m[1]->view, m[2]->view}, whole.colours, whole.normals,
              to.report);
    }
    //> clip-only-when-needed
    const Clock::time_point c0 = Clock::now(); // only a triangle that is cut pays
    const std::vector<ClippedCorners> pieces =
        clip_corners(whole, s.volume.clip, with_colours, phong);
    to.report.clipping.triangles += 1;
    to.report.clipping.seconds += seconds_since(c0);
    for (const ClippedCorners& piece : pieces) {
        keep_piece(index, piece, to); // projected, checked, culled
    }
    //< clip-only-when-needed
}

/// Projects, checks, culls and stores one piece of a triangle that was cut.
void MeshPass::keep_piece(std::size_t index, const ClippedCorners& piece,
                          MeshOutput& to) const {
    ScreenTriangle t{};
    ShadedCorners c{};
    for (std::size_t k = 0; k < 3; ++k) {
        t.corners[k] = checked(project_vertex(s.scene, s.lens, piece.view[k]), index);
        t.nearness[k] = s.perspective ? 1.0 / t.corners[k].w : -piece.view[k].position.z;
        c.points[k] = piece.view[k].position;
    }
    c.colours = piece.colours;
    c.normals = piece.normals;
    if (mesh.cull_back && screen_area2(t.corners[0].position, t.corners[1].position,
                                       t.corners[2].position) >= 0.0) {
        to.report.culling.triangles += 1; // a piece seen from behind
        return;
    }
    for (const TexturedVertex& v : t.corners) {
        to.box.add(v.position);
    }
    to.out.push_back(t);
    if (shaded) {
        to.shading.push_back(c);
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

namespace {

/// What one thread's stretch of one mesh's triangles made (run_geometry, threads > 1).
struct GeometryPart {
    std::size_t mesh = 0;
    std::vector<ScreenTriangle> out;
    std::vector<ShadedCorners> shading;
    ScreenBox box;
    RenderReport report; ///< the geometry stage's counts and times of the stretch
    std::optional<Error> error; ///< the stretch's first error: it stopped there
};

/// Adds the geometry stage's per-triangle counts and times of `part` to `report`.
void add_geometry_counts(RenderReport& report, const RenderReport& part) {
    for (auto stage : {&RenderReport::geometry, &RenderReport::rejected,
                       &RenderReport::clipping, &RenderReport::culling,
                       &RenderReport::lighting}) {
        (report.*stage).triangles += (part.*stage).triangles;
        (report.*stage).seconds += (part.*stage).seconds;
    }
    report.lit_vertices += part.lit_vertices;
}

/// The threaded geometry stage: every mesh's positions, all meshes as one list, split
/// evenly among the threads and moved; then every mesh's triangles likewise, each
/// thread's stretch of a mesh decided in order into a part of its own; the parts joined
/// in scene order, so the lists are the serial stage's; the first error in scene order
/// thrown (a thread stops at its first: what follows it is not needed).
void run_meshes_threaded(std::vector<std::unique_ptr<MeshPass>>& passes,
                         SceneGeometry& geometry, RenderReport& report, int threads) {
    std::vector<std::size_t> positions, triangles;
    for (const auto& pass : passes) {
        positions.push_back(pass->position_count());
        triangles.push_back(pass->triangle_count());
    }
    std::vector<std::vector<GeometryPart>> parts(static_cast<std::size_t>(threads));
    std::vector<double> moving(static_cast<std::size_t>(threads)); // seconds
    run_on_shared_pool(threads, [&](int t) {
        const Clock::time_point t0 = Clock::now();
        for_thread_stretch(positions, t, threads,
                           [&](std::size_t i, std::size_t a, std::size_t b) {
                               passes[i]->move_positions(a, b);
                           });
        moving[static_cast<std::size_t>(t)] = seconds_since(t0);
    });
    report.geometry.seconds += std::accumulate(moving.begin(), moving.end(), 0.0);
    run_on_shared_pool(threads, [&](int t) {
        std::vector<GeometryPart>& mine = parts[static_cast<std::size_t>(t)];
        bool failed = false;
        for_thread_stretch(triangles, t, threads,
                           [&](std::size_t i, std::size_t a, std::size_t b) {
                               if (failed) {
                                   return;
                               }
                               GeometryPart& part = mine.emplace_back();
                               part.mesh = i;
                               MeshOutput to{part.out, part.shading, part.box,
                                             part.report};
                               const Clock::time_point t0 = Clock::now();
                               try {
                                   passes[i]->triangles(a, b, to);
                               } catch (const Error& error) {
                                   part.error = error;
                                   failed = true;
                               }
                               part.report.geometry.seconds += seconds_since(t0);
                           });
    });
    for (std::vector<GeometryPart>& thread_parts : parts) { // in scene order
        for (GeometryPart& part : thread_parts) {
            if (part.error) {
                throw *part.error;
            }
            std::vector<ScreenTriangle>& out = geometry.meshes[part.mesh];
            std::vector<ShadedCorners>& shading = geometry.shading[part.mesh];
            if (out.empty()) {
                out = std::move(part.out);
            } else {
                out.insert(out.end(), part.out.begin(), part.out.end());
            }
            if (shading.empty()) {
                shading = std::move(part.shading);
            } else {
                shading.insert(shading.end(), part.shading.begin(), part.shading.end());
            }
            // min and max keep the first of equals
            ScreenBox& box = geometry.footprints[part.mesh].box;
            box.x0 = std::min(box.x0, part.box.x0);
            box.y0 = std::min(box.y0, part.box.y0);
            box.x1 = std::max(box.x1, part.box.x1);
            box.y1 = std::max(box.y1, part.box.y1);
            add_geometry_counts(report, part.report);
        }
    }
}

} // namespace

SceneGeometry run_geometry(const Scene& scene, RenderReport& report, int threads,
                           bool lean) {
    SceneGeometry geometry;
    const CameraFrame camera = camera_frame(scene.camera);
    if (!scene.lights.empty()) {
        geometry.lights = lights_in_view(scene.lights, [&](glm::dvec3 v, bool is_point) {
            return to_view(camera, is_point ? v - camera.eye : v);
        });
    }
    report.lighting_on = !scene.lights.empty();
    report.lights = static_cast<int>(geometry.lights.size());
    const StageSetup setup(scene, camera, geometry.lights, lean);
    // Every mesh first: the depth stage's plan needs to know where on screen each lands.
    geometry.meshes.resize(scene.meshes.size());
    geometry.shading.resize(scene.meshes.size());
    geometry.footprints.resize(scene.meshes.size());
    if (threads <= 1) {
        for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
            MeshPass(setup, scene.meshes[i], i, report, geometry).run();
        }
        return geometry;
    }
    std::vector<std::unique_ptr<MeshPass>> passes; // each mesh's setup, in order
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        passes.push_back(
            std::make_unique<MeshPass>(setup, scene.meshes[i], i, report, geometry));
    }
    run_meshes_threaded(passes, geometry, report, threads);
    return geometry;
}

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

} // namespace exactpixels
