// Chapter 6, vertices at or behind the eye: clipping at the near plane before
// projection. Tolerances: every output depth >= near exactly; texture coordinates
// through the clip agree with a ray traced through each pixel centre within what uv
// changes over 1/256 px there (the snap of the projected corners); shared cut edges
// agree bit for bit.
#include "exactpixels/base/error.hpp"
#include "exactpixels/texture/clipping.hpp"
#include "support/printing.hpp"
#include "support/measured_facts.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace exactpixels;
using exactpixels::testing::record_fact;

namespace {
std::uint64_t state = 7;
double uniform(double lo, double hi) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return lo + (hi - lo) * double(state >> 11) * 0x1p-53;
}

/// Where the ray from the eye through screen point s meets the plane of triangle t:
/// barycentric weights (b0, b1, b2) and the depth z of the hit. Camera as
/// perspective.hpp.
struct Hit {
    glm::dvec3 b;
    double z;
};
Hit trace(const Pinhole& camera, const std::array<ViewVertex, 3>& t, Point2 s) {
    const glm::dvec3 d{(s.x - camera.centre.x) / camera.focal,
                       -(s.y - camera.centre.y) / camera.focal, 1.0}; // z = 1
    const glm::dvec3 a = t[0].position, e1 = t[1].position - a, e2 = t[2].position - a;
    // Solve a + b1 e1 + b2 e2 = z d (Cramer's rule on [e1 e2 -d]).
    const glm::dmat3 m(e1, e2, -d);
    const double det = glm::determinant(m);
    const glm::dvec3 r = -a;
    const double b1 = glm::determinant(glm::dmat3(r, e2, -d)) / det;
    const double b2 = glm::determinant(glm::dmat3(e1, r, -d)) / det;
    const double z = glm::determinant(glm::dmat3(e1, e2, r)) / det;
    return {{1.0 - b1 - b2, b1, b2}, z};
}
} // namespace

TEST_CASE("clipping keeps, drops or cuts a triangle into one or two, all at z >= near" *
          doctest::description("points: 10; exercise: ch06-clip-near")) {
    // Every combination of depths behind the eye, at it, on the plane and in front.
    const double near = 0.5;
    const double depths[] = {-1.0, 0.0, 0.25, near, 2.0};
    for (const double z0 : depths) {
        for (const double z1 : depths) {
            for (const double z2 : depths) {
                const std::array<ViewVertex, 3> t{{{{-1.0, -1.0, z0}, {0.0, 0.0}},
                                                   {{2.0, -1.0, z1}, {30.0, 0.0}},
                                                   {{0.0, 1.5, z2}, {0.0, 20.0}}}};
                const int in = (z0 >= near) + (z1 >= near) + (z2 >= near);
                const ClippedTriangles c = clip_near(t, near);
                INFO("depths " << z0 << " " << z1 << " " << z2);
                CHECK(c.count == (in == 3 ? 1 : in == 2 ? 2 : in == 1 ? 1 : 0));
                for (int k = 0; k < c.count; ++k) {
                    for (const ViewVertex& p : c.triangles[static_cast<std::size_t>(k)]) {
                        CHECK(p.position.z >= near);
                        // On the original triangle: the weights (b0, b1, b2) of its x and
                        // y are those of a point inside it, its z is the triangle's depth
                        // there (so a crossing is where the edge meets the plane, not
                        // merely some point with z set to near), and uv matches the
                        // corners' affine map.
                        const double b1 = (p.position.x - t[0].position.x -
                                           (p.position.y - t[0].position.y) / 2.5) /
                                          3.0;
                        const double b2 = (p.position.y - t[0].position.y) / 2.5;
                        CHECK(std::min({1.0 - b1 - b2, b1, b2}) >= -1e-12);
                        CHECK(p.position.z ==
                              doctest::Approx(z0 + b1 * (z1 - z0) + b2 * (z2 - z0))
                                  .epsilon(1e-12));
                        CHECK(p.uv.x == doctest::Approx(30.0 * b1).epsilon(1e-12));
                        CHECK(p.uv.y == doctest::Approx(20.0 * b2).epsilon(1e-12));
                    }
                }
                if (in == 3) {
                    CHECK(c.triangles[0][0].position == t[0].position); // untouched
                    CHECK(c.triangles[0][2].uv == t[2].uv);
                }
            }
        }
    }
}

TEST_CASE("drawn through the clip, every pixel gets the texel a traced ray finds" *
          doctest::description("points: 4; exercise: ch06-clip-near")) {
    // Random triangles with one or two corners behind the eye (some exactly at z = 0).
    const Pinhole camera{200.0, {160.0, 120.0}};
    const double near = 0.25;
    int pixels = 0, misses = 0, holes = 0;
    double worst = 0.0;
    for (int trial = 0; trial < 60; ++trial) {
        std::array<ViewVertex, 3> t{};
        for (ViewVertex& p : t) {
            const double z = trial % 5 == 0 && &p == &t[0] ? 0.0 : uniform(-3.0, 6.0);
            p = {{uniform(-4.0, 4.0), uniform(-3.0, 3.0), z},
                 {uniform(0.0, 64.0), uniform(0.0, 64.0)}};
        }
        const ProjectedTriangles pieces = clip_and_project(camera, t, near);
        TexelMap map(320, 240);
        for (int k = 0; k < pieces.count; ++k) {
            for (const TexturedVertex& v :
                 pieces.triangles[static_cast<std::size_t>(k)]) {
                REQUIRE(v.w >= near);
                REQUIRE(std::isfinite(v.position.x));
                REQUIRE(std::isfinite(v.position.y));
            }
            map_textured_triangle(
                map, pieces.triangles[static_cast<std::size_t>(k)],
                {{MapperKind::exact}, Precision::float64, {}, Wrap::repeat});
        }
        for (int y = 0; y < 240; ++y) {
            for (int x = 0; x < 320; ++x) {
                const std::size_t at = std::size_t(y) * 320 + std::size_t(x);
                const Hit h = trace(camera, t, pixel_centre(x, y));
                if (map.covered[at]) {
                    ++pixels;
                    // The ray meets the triangle (up to the 1/512 px snap of its
                    // corners) in front of the near plane...
                    misses += !(h.z >= near * (1.0 - 1e-9)) ||
                              !(std::min({h.b.x, h.b.y, h.b.z}) > -0.02);
                    // ... and the texel coordinate is the one at the hit.
                    // The mapper's planes run through the corners snapped to 1/256 px,
                    // so the allowance is what uv changes over 1/256 px here.
                    const auto uv_at = [&](double dx, double dy) {
                        const Hit g =
                            trace(camera, t, pixel_centre(x, y) + Point2{dx, dy});
                        return g.b.x * t[0].uv + g.b.y * t[1].uv + g.b.z * t[2].uv;
                    };
                    const TexCoord uv = uv_at(0.0, 0.0);
                    const TexCoord gx = uv_at(1.0 / 256, 0.0) - uv;
                    const TexCoord gy = uv_at(0.0, 1.0 / 256) - uv;
                    const double allowance = std::abs(gx.x) + std::abs(gx.y) +
                                             std::abs(gy.x) + std::abs(gy.y) + 1e-9;
                    worst = std::max({worst, std::abs(map.u[at] - uv.x) / allowance,
                                      std::abs(map.v[at] - uv.y) / allowance});
                } else if (h.z > 1.01 * near && std::min({h.b.x, h.b.y, h.b.z}) > 0.02) {
                    ++holes; // inside, in front of the plane, and not drawn
                }
            }
        }
    }
    MESSAGE(pixels << " pixels drawn through the clip; largest uv error " << worst
                   << " of the allowance");
    record_fact("ch06_clip_pixels", pixels);
    record_fact("ch06_clip_trials", 60);
    record_fact("ch06_clip_misses", misses);
    record_fact("ch06_clip_holes", holes);
    record_fact("ch06_clip_uv_of_allowance", worst);
    CHECK(pixels > 10000);
    CHECK(misses == 0); // no drawn pixel whose ray misses the triangle or hits behind
    CHECK(holes == 0);  // no pixel clearly inside left undrawn
    CHECK(worst <= 1.0);
}

TEST_CASE("two triangles sharing a cut edge get the same crossing, bit for bit" *
          doctest::description("points: 3; exercise: ch06-clip-near")) {
    // The quad a b c d straddles the near plane; its two triangles share the edge a-c,
    // given in opposite directions. Both crossings go from the inside corner outwards.
    const double near = 0.5;
    const ViewVertex a{{-1.0, -1.0, -0.7}, {0.0, 0.0}}, b{{1.3, -1.1, 0.3}, {10.0, 0.0}},
        c{{1.1, 0.9, 3.1}, {10.0, 10.0}}, d{{-0.9, 1.2, 2.2}, {0.0, 10.0}};
    const ClippedTriangles first = clip_near({a, b, c}, near);
    const ClippedTriangles second = clip_near({c, d, a}, near);
    const ViewVertex shared = near_crossing(c, a, near);
    int found = 0;
    for (const ClippedTriangles* part : {&first, &second}) {
        for (int k = 0; k < part->count; ++k) {
            for (const ViewVertex& p : part->triangles[static_cast<std::size_t>(k)]) {
                found += p.position == shared.position && p.uv == shared.uv;
            }
        }
    }
    CHECK(found >= 2); // the same point appears in a piece of each triangle
    CHECK(shared.position.z == near);
}

TEST_CASE("a vertex at or behind the eye never reaches a divide; bad input is an Error" *
          doctest::description("points: 3; exercise: ch06-clip-near")) {
    const Pinhole camera{};
    const std::array<ViewVertex, 3> at_eye{{{{0.0, 0.5, 0.0}, {0.0, 0.0}}, // w = 0
                                            {{1.0, -1.0, 2.0}, {8.0, 0.0}},
                                            {{-1.0, -1.0, 2.0}, {0.0, 8.0}}}};
    // Unclipped, projection refuses the corner at the eye ...
    CHECK_THROWS_AS(project(camera, at_eye[0].position, at_eye[0].uv), Error);
    // ... clipped, the triangle is drawn, every pixel finite.
    Framebuffer frame(320, 240, rgba(0, 0, 0));
    draw_view_triangle(frame, camera, at_eye, 0.1, f_texture(2), {});
    const auto drawn = std::count_if(frame.pixels().begin(), frame.pixels().end(),
                                     [](Rgba8 p) { return p != rgba(0, 0, 0); });
    CHECK(drawn > 1000);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const double bad : {nan, std::numeric_limits<double>::infinity()}) {
        auto t = at_eye;
        t[1].position.z = bad;
        CHECK_THROWS_WITH_AS(clip_near(t, 0.1), doctest::Contains("vertex 1"), Error);
        t = at_eye;
        t[2].uv.y = bad;
        CHECK_THROWS_AS(clip_near(t, 0.1), Error);
        CHECK_THROWS_AS(clip_near(at_eye, bad), Error);
    }
    CHECK_THROWS_WITH_AS(clip_near(at_eye, 0.0), doctest::Contains("near = 0"), Error);
    CHECK_THROWS_AS(clip_near(at_eye, -1.0), Error);
}
