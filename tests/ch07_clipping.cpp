// Chapter 7 tests: clipping against the whole view volume (@sec:scene-clipping). Any
// plane cuts like chapter 6's near plane, shared edges stay bit-exact at every plane,
// triangles wholly outside are rejected, a triangle reaching 1e7 px off screen draws the
// pixels an exact reference gives, and the far plane cuts a floor at the derived row.
#include "ch02_grid.hpp"
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/raster/scanline.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "exactpixels/texture/clipping.hpp"
#include "exactpixels/texture/perspective.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <vector>

using namespace exactpixels;

namespace {

/// The triangles of a clipped polygon, a fan from its first corner.
std::vector<std::array<ViewVertex, 3>> fan_of(const ClippedPolygon& p) {
    std::vector<std::array<ViewVertex, 3>> out;
    for (int k = 1; k + 1 < p.count; ++k) {
        out.push_back({p.corners[0], p.corners[static_cast<std::size_t>(k)],
                       p.corners[static_cast<std::size_t>(k + 1)]});
    }
    return out;
}

/// Projects, snaps and rasterizes a view-space triangle into the grid (chapter 1's
/// fixed-point scanline rasterizer, the renderer's).
void draw_view(ch02::Grid& grid, const Pinhole& camera,
               const std::array<ViewVertex, 3>& t) {
    std::array<FixedPoint2, 3> v{};
    for (std::size_t k = 0; k < 3; ++k) {
        v[k] = snap_in_range(project(camera, t[k].position, t[k].uv).position);
    }
    ch02::draw(grid, v, ch02::Raster::scanline_fixed);
}

/// The focal length render_scene uses for a vertical field of view (@eq:scene-focal).
double focal(int height, double fov_degrees) {
    return 0.5 * height / std::tan(0.5 * fov_degrees * std::acos(-1.0) / 180.0);
}

} // namespace

TEST_CASE("clip_polygon at the near plane is clip_near, bit for bit") {
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> coordinate(-3.0, 3.0);
    int cut = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        std::array<ViewVertex, 3> t{};
        for (ViewVertex& v : t) {
            v = {{coordinate(rng), coordinate(rng), coordinate(rng)},
                 {coordinate(rng), coordinate(rng)}};
        }
        const double near = 0.25;
        const ClippedTriangles expected = clip_near(t, near);
        const auto got = fan_of(clip_triangle(t, {near_plane(near)}));
        REQUIRE(static_cast<int>(got.size()) == expected.count);
        cut += expected.count == 2;
        for (std::size_t i = 0; i < got.size(); ++i) {
            for (std::size_t k = 0; k < 3; ++k) {
                CHECK(got[i][k].position == expected.triangles[i][k].position);
                CHECK(got[i][k].uv == expected.triangles[i][k].uv);
            }
        }
    }
    CHECK(cut > 100); // the trials cut many triangles into two
}

TEST_CASE("clip_triangle refuses non-finite corners and more planes than it can hold") {
    const std::array<ViewVertex, 3> t{{{{0.0, 0.0, 1.0}, {0.0, 0.0}},
                                       {{1.0, 0.0, 1.0}, {0.0, 0.0}},
                                       {{0.0, 1.0, 1.0}, {0.0, 0.0}}}};
    CHECK(clip_triangle(t, std::vector<ViewPlane>(6, near_plane(0.5))).count == 3);
    CHECK_THROWS_WITH_AS(clip_triangle(t, std::vector<ViewPlane>(7, near_plane(0.5))),
                         "clip_triangle: 7 planes (at most 6)", Error);
    std::array<ViewVertex, 3> bad = t;
    bad[1].position.y = std::nan("");
    CHECK_THROWS_WITH_AS(clip_triangle(bad, {near_plane(0.5)}),
                         "clip_triangle: vertex 1 has a coordinate nan (position and uv "
                         "must be finite)",
                         Error);
}

TEST_CASE("at every plane, shared edges are cut at one point: no pixel twice, no gap") {
    // A floor y = -1 from z = 0.3 to z = 8 in view space, 16 x 16 cells split along
    // alternating diagonals, interior corners jittered within the floor.
    const Pinhole camera{.focal = 100.0, .centre = {160.0, 120.0}};
    const int n = 16;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> jitter(-0.3, 0.3);
    std::vector<glm::dvec3> corners;
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
            const bool inner = i > 0 && i < n && j > 0 && j < n;
            const double u = i + (inner ? jitter(rng) : 0.0),
                         v = j + (inner ? jitter(rng) : 0.0);
            corners.push_back({-4.0 + 8.0 * u / n, -1.0, 0.3 + 7.7 * v / n});
        }
    }
    std::vector<std::array<int, 3>> triangles;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            if ((i + j) % 2 == 0) {
                triangles.push_back({a, b, d});
                triangles.push_back({a, d, c});
            } else {
                triangles.push_back({a, b, c});
                triangles.push_back({b, d, c});
            }
        }
    }
    // How many triangles use each edge: 1 on the outline, 2 inside.
    std::map<std::pair<int, int>, int> edge_uses;
    for (const auto& t : triangles) {
        for (std::size_t k = 0; k < 3; ++k) {
            const int p = t[k], q = t[(k + 1) % 3];
            ++edge_uses[{std::min(p, q), std::max(p, q)}];
        }
    }
    const auto view = [&](int index) {
        const glm::dvec3 p = corners[static_cast<std::size_t>(index)];
        return ViewVertex{p, {p.x, p.z}};
    };
    // The outline, as two triangles: what the mesh must cover.
    const int last = (n + 1) * (n + 1) - 1;
    const std::array<std::array<int, 3>, 2> outline{{{0, n, last}, {0, last, last - n}}};
    const double f = camera.focal;
    // Each plane alone, in the form view_volume gives the screen's and the guard band's
    // sides (offset times z), then the whole view volume at once, in the renderer's
    // order (near, far, then the sides), where a later plane cuts corners an earlier
    // one made.
    const ViewPlane x_at_most_200{{-f, 0.0, 200.0 - 160.0}, 0.0},
        x_at_least_90{{f, 0.0, 160.0 - 90.0}, 0.0},
        y_at_least_140{{0.0, -f, 120.0 - 140.0}, 0.0},
        y_at_most_210{{0.0, f, 210.0 - 120.0}, 0.0};
    const std::vector<std::pair<const char*, std::vector<ViewPlane>>> cases{
        {"near z >= 1", {near_plane(1.0)}},
        {"far z <= 5", {near_plane(0.3), {{0.0, 0.0, -1.0}, 5.0}}},
        {"screen x <= 200", {near_plane(0.3), x_at_most_200}},
        {"screen x >= 90", {near_plane(0.3), x_at_least_90}},
        {"screen y >= 140", {near_plane(0.3), y_at_least_140}},
        {"screen y <= 210", {near_plane(0.3), y_at_most_210}},
        {"oblique", {near_plane(0.3), {{1.0, 0.5, -0.3}, 0.2}}},
        {"the whole volume: near 1, far 3, 90 <= x <= 200, 140 <= y <= 210",
         {near_plane(1.0), {{0.0, 0.0, -1.0}, 3.0}, x_at_least_90, x_at_most_200,
          y_at_least_140, y_at_most_210}}};
    for (const auto& entry : cases) {
        // Named copies, not structured bindings: INFO captures them in a lambda, which
        // Clang accepts only from version 16.
        const char* const name = entry.first;
        const std::vector<ViewPlane>& list = entry.second;
        INFO(name);
        // Every plane here but near keeps the mesh in front of the eye; near needs
        // itself, the others clip at z >= 0.3 first (a no-op: the floor starts there).
        // With one plane after it, every new corner lies on an edge of the mesh, so
        // corners can be counted; with several, a later plane also cuts the new edges
        // an earlier one made inside a triangle, and the pixels alone are checked.
        const bool one_plane = list.size() <= 2;
        const ViewPlane& plane = list.back();
        ch02::Grid mesh{320, 240}, whole{320, 240};
        std::map<std::tuple<double, double, double>, int> crossings;
        for (const auto& t : triangles) {
            const std::array<ViewVertex, 3> v{view(t[0]), view(t[1]), view(t[2])};
            const ClippedPolygon polygon = clip_triangle(v, list);
            for (int k = 0; k < polygon.count; ++k) {
                const glm::dvec3 p =
                    polygon.corners[static_cast<std::size_t>(k)].position;
                const bool original = std::any_of(
                    v.begin(), v.end(), [&](const auto& c) { return c.position == p; });
                if (!original) {
                    ++crossings[{p.x, p.y, p.z}];
                }
            }
            for (const auto& piece : fan_of(polygon)) {
                draw_view(mesh, camera, piece);
            }
        }
        for (const auto& t : outline) {
            for (const auto& piece :
                 fan_of(clip_triangle({view(t[0]), view(t[1]), view(t[2])}, list))) {
                draw_view(whole, camera, piece);
            }
        }
        // Each crossed edge gives one new corner, shared by the triangles on both sides:
        // a cut depending on the walking direction would split interior ones in two.
        int outline_cuts = 0, interior_cuts = 0;
        for (const auto& [edge, uses] : edge_uses) {
            const double a =
                plane_value(plane, corners[static_cast<std::size_t>(edge.first)]);
            const double b =
                plane_value(plane, corners[static_cast<std::size_t>(edge.second)]);
            if ((a >= 0.0) != (b >= 0.0)) {
                (uses == 1 ? outline_cuts : interior_cuts) += 1;
            }
        }
        int once = 0, twice = 0, other = 0;
        for (const auto& [point, count] : crossings) {
            (count == 1 ? once : count == 2 ? twice : other) += 1;
        }
        if (one_plane) {
            CHECK(interior_cuts > 10);
            CHECK(once == outline_cuts);
            CHECK(twice == interior_cuts);
            CHECK(other == 0);
        }
        // Pixels: none drawn twice, and every pixel deep inside the clipped outline
        // (it and its 8 neighbours covered by the outline's two triangles) drawn once.
        int inside = 0;
        for (int y = 0; y < 240; ++y) {
            for (int x = 0; x < 320; ++x) {
                INFO("pixel (" << x << ", " << y << ")");
                REQUIRE(mesh.at(x, y) <= 1);
                bool deep = x > 0 && y > 0 && x + 1 < 320 && y + 1 < 240;
                for (int dy = -1; deep && dy <= 1; ++dy) {
                    for (int dx = -1; dx <= 1; ++dx) {
                        deep = deep && whole.at(x + dx, y + dy) >= 1;
                    }
                }
                if (deep) {
                    ++inside;
                    REQUIRE(mesh.at(x, y) == 1);
                }
            }
        }
        CHECK(inside > 1000);
    }
}

TEST_CASE("a triangle reaching 1e7 px off screen draws the exact triangle's pixels") {
    // Camera at the origin looking along +z: view space is world space. At depth 1 a
    // point (x, y) lands on (32 + f x, 24 - f y), f = 24: the first corner is ~1e7 px to
    // the left, 10 times beyond the fixed-point range, so the triangle must be cut at the
    // guard band.
    const Scene scene = parse_scene(R"(
[image]
width = 64
height = 48
[camera]
position = [0, 0, 0]
target = [0, 0, 1]
fov = 90
[[mesh]]
primitive = "triangles"
colour = [1, 1, 1]
positions = [[-416667, 0.3, 1], [1.1, 0.9, 1], [0.7, -0.8, 1]]
)",
                                    "huge.toml", ".");
    const RenderResult result = render_scene(scene);
    CHECK(result.report.clipping.triangles == 1);
    CHECK(result.report.rejected.triangles == 0);
    // The reference: the unclipped screen triangle, corners inside the range snapped as
    // the renderer snaps them, the far one exact; a pixel is covered when its centre is
    // inside. Every centre is at least 1e-3 px from an edge, so no tie rule is needed
    // and the cut (its error far below 1e-6 px on screen) cannot change a pixel.
    const double f = focal(48, 90.0);
    const auto screen = [&](double x, double y) {
        return Point2{32.0 + f * x, 24.0 - f * y};
    };
    const std::array<Point2, 3> p{screen(-416667.0, 0.3),
                                  to_pixels(snap_to_subpixel(screen(1.1, 0.9))),
                                  to_pixels(snap_to_subpixel(screen(0.7, -0.8)))};
    CHECK(p[0].x < -0.99e7);
    int covered = 0;
    double closest = 1e9;
    for (int y = 0; y < 48; ++y) {
        for (int x = 0; x < 64; ++x) {
            const Point2 c{x + 0.5, y + 0.5};
            bool in = true;
            for (std::size_t k = 0; k < 3; ++k) {
                const Point2 a = p[k], b = p[(k + 1) % 3];
                const double e = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
                const double distance = std::abs(e) / std::hypot(b.x - a.x, b.y - a.y);
                closest = std::min(closest, distance);
                in = in && e > 0.0; // clockwise on a y-down screen
            }
            covered += in;
            INFO("pixel (" << x << ", " << y << ")");
            CHECK(result.image.at(x, y) == (in ? rgba(255, 255, 255) : rgba(0, 0, 0)));
        }
    }
    CHECK(closest >= 1e-3);
    CHECK(covered > 200);
    CHECK(result.report.raster.pixels == covered);
}

TEST_CASE("a triangle wholly outside one plane of the view volume is rejected, counted") {
    const std::string mesh = R"(
[image]
width = 64
height = 48
[camera]
position = [0, 0, 0]
target = [0, 0, 1]
fov = 90
far = 10
[[mesh]]
primitive = "triangles"
colour = [1, 0, 0]
positions = [[-1, -1, 2], [1, -1, 2], [0, 1, 2]]
)";
    const std::string outside = R"(
[[mesh]]
primitive = "triangles"
colour = [0, 1, 0]
positions = [[-9, -1, 2], [-3, -1, 2], [-5, 1, 2],
             [-1, -1, -2], [1, -1, -2], [0, 1, -2],
             [-1, -1, 20], [1, -1, 20], [0, 1, 20],
             [-1, 2.01, 2], [1, 3, 2], [0, 5, 2]]
)";
    const RenderResult alone = render_scene(parse_scene(mesh, "alone.toml", "."));
    const RenderResult with = render_scene(parse_scene(mesh + outside, "with.toml", "."));
    // Left of the screen, behind the eye, beyond far, above the screen: 4 rejected.
    CHECK(with.report.rejected.triangles == 4);
    CHECK(with.report.geometry.triangles == 5);
    CHECK(with.report.clipping.triangles == 0);
    CHECK(with.report.raster.triangles == 1);
    CHECK(with.image == alone.image);
    CHECK(alone.report.rejected.triangles == 0);
    CHECK(format_report(with.report).find("rejected") != std::string::npos);
    CHECK(format_report(alone.report).find("rejected") == std::string::npos);
    // One corner back on screen: not rejected, and (inside the guard band) not clipped.
    const RenderResult straddling = render_scene(parse_scene(
        mesh + "[[mesh]]\nprimitive = \"triangles\"\npositions = [[-9, -1, 2], "
               "[-0.5, -1, 2], [-5, 1, 2]]\n",
        "straddling.toml", "."));
    CHECK(straddling.report.rejected.triangles == 0);
    CHECK(straddling.report.clipping.triangles == 0);
}

TEST_CASE("the far plane cuts a long floor at the derived row") {
    // A floor y = -1 from z = 1 to z = 100, x in [-2, 2]; the camera at the origin looks
    // along +z with f = 24 px at 64 x 48. A floor point at depth z lands on row
    // y = 24 + 24 / z (@eq:scene-far-row): with far = 10 the floor ends at y = 26.4, so
    // row 25 (centre 25.5, depth 16) is empty and row 26 (centre 26.5, depth 9.6) is the
    // first drawn. There the floor spans x = 32 +- 24 * 2 / 9.6 = 27 .. 37: the centres
    // 27.5 .. 36.5, pixels 27 to 36.
    const auto floor_scene = [](const std::string& far) {
        return parse_scene(fmt::format(R"(
[image]
width = 64
height = 48
[camera]
position = [0, 0, 0]
target = [0, 0, 1]
fov = 90
{}
[[mesh]]
primitive = "quad"
colour = [1, 1, 1]
corners = [[-2, -1, 1], [-2, -1, 100], [2, -1, 100], [2, -1, 1]]
)",
                                       far),
                           "floor.toml", ".");
    };
    const RenderResult cut = render_scene(floor_scene("far = 10"));
    const RenderResult whole = render_scene(floor_scene(""));
    const RenderResult beyond = render_scene(floor_scene("far = 1000"));
    const Rgba8 white = rgba(255, 255, 255);
    for (int x = 0; x < 64; ++x) {
        INFO("x = " << x);
        CHECK(cut.image.at(x, 25) != white);
        CHECK((cut.image.at(x, 26) == white) == (x >= 27 && x <= 36));
        CHECK(cut.image.at(x, 27) == whole.image.at(x, 27)); // below the cut: unchanged
    }
    // Without the far plane the floor reaches the horizon's rows.
    CHECK(whole.image.at(32, 25) == white);
    CHECK(whole.image.at(32, 24) == white);
    CHECK(cut.report.clipping.triangles == 2);
    // The floor's near corners land off screen (x = -16 and 80) but inside the guard
    // band, and far = 1000 lies behind it: no triangle is cut.
    CHECK(whole.report.clipping.triangles == 0);
    CHECK(beyond.report.clipping.triangles == 0);
    CHECK(beyond.image == whole.image);
}
