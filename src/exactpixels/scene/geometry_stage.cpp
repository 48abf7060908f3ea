// geometry_stage.cpp: chapter 7's geometry stage (scene_renderer.hpp declares it): every
// triangle of every mesh to view space, rejected, lit per vertex, clipped, projected and
// culled, with the fast variants of FastPaths beside the plain steps.
#include "exactpixels/base/error.hpp"
#include "exactpixels/raster/fill_work.hpp"
#include "exactpixels/scene/camera.hpp"
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
#include <limits>
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
