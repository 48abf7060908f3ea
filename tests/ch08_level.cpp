// Chapter 8 tests, part 3: the derivatives of the perspective mapping, the level of
// detail they give, trilinear and anisotropic sampling.
#include "exactpixels/texture/bilinear.hpp"
#include "exactpixels/texture/filter.hpp"
#include "exactpixels/texture/level_of_detail.hpp"
#include "exactpixels/texture/perspective.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <numbers>

using namespace exactpixels;

namespace {

/// Uniform numbers in [lo, hi) from a 64-bit LCG: the same sequence everywhere.
struct Lcg {
    std::uint64_t state;
    double operator()(double lo, double hi) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return lo + (hi - lo) * double(state >> 11) * 0x1p-53;
    }
};

/// A random perspective triangle on a 320 x 240 screen, depths 1 to 20, u and v in
/// [-64, 64).
std::array<TexturedVertex, 3> random_triangle(Lcg& random) {
    std::array<TexturedVertex, 3> t{};
    for (TexturedVertex& v : t) {
        v = {{random(0, 320), random(0, 240)},
             random(1, 20),
             {random(-64, 64), random(-64, 64)}};
    }
    return t;
}

/// u and v of the exact perspective mapping at a screen point: (u/w) / (1/w).
TexCoord exact_uv(const std::array<TexturedVertex, 3>& t, Point2 at) {
    const auto [u, v] = projected_coordinates(t, at);
    return {u.p / u.q, v.p / v.q};
}

/// A square of side 2 units, s texels per unit, at distance `distance` on the view axis,
/// turned by `angle` about the horizontal axis (0: facing the camera).
std::array<TexturedVertex, 3> tilted_plane(const Pinhole& eye, double distance,
                                           double angle, double s) {
    const auto point = [&](double x, double y) {
        const glm::dvec3 p{x, y * std::cos(angle), distance + y * std::sin(angle)};
        return project(eye, p, {s * x, -s * y});
    };
    return {point(-1, -1), point(1, -1), point(0, 1)};
}

} // namespace

TEST_CASE("the derived derivatives match finite differences of the exact mapping" *
          doctest::description("points: 2; exercise: ch08-derivatives")) {
    // Random perspective triangles, depths 1 to 20, at random points inside them. Along
    // x, u = (p + t p_x) / (q + t q_x) is a constant plus a multiple of 1 / (q + t q_x),
    // and the central difference of 1 / (q + t a) over +-h is exactly -a / (q^2 - h^2
    // a^2): relative to the derivative -a / q^2 it is off by r^2 / (1 - r^2), r = h a /
    // q. So the stated tolerance is that truncation term plus rounding, 2^-40 (|u| + |v|
    // + 1) / h (the rounding of u, v divided by the step), and the test also reports the
    // worst difference against the tolerance.
    Lcg random{42};
    double worst = 0.0;
    for (int n = 0; n < 500; ++n) {
        const std::array<TexturedVertex, 3> t = random_triangle(random);
        for (int k = 0; k < 10; ++k) {
            const double a = random(0, 1), b = random(0, 1 - a);
            const Point2 at = t[0].position + a * (t[1].position - t[0].position) +
                              b * (t[2].position - t[0].position);
            const TexelDerivatives d = derivatives_at(t, at);
            // Not a structured binding: the lambda below captures pu (Clang 14 cannot
            // capture a binding); v's coordinate is not needed.
            const auto projected = projected_coordinates(t, at);
            const auto& pu = projected[0];
            const double h = 0x1p-14;
            const TexCoord ddx =
                (exact_uv(t, at + Point2{h, 0}) - exact_uv(t, at - Point2{h, 0})) /
                (2 * h);
            const TexCoord ddy =
                (exact_uv(t, at + Point2{0, h}) - exact_uv(t, at - Point2{0, h})) /
                (2 * h);
            const TexCoord uv = exact_uv(t, at);
            const double rounding = 0x1p-40 * (std::abs(uv.x) + std::abs(uv.y) + 1.0) / h;
            const auto truncation = [&](double a_q) {
                const double r = h * a_q / pu.q;
                return 1.01 * r * r / (1.0 - r * r); // 1% for the rounding of d itself
            };
            const double tx = truncation(pu.dq.dx), ty = truncation(pu.dq.dy);
            const std::array<double, 4> diff{ddx.x - d.du_dx, ddx.y - d.dv_dx,
                                             ddy.x - d.du_dy, ddy.y - d.dv_dy};
            const std::array<double, 4> tol{
                std::abs(d.du_dx) * tx + rounding, std::abs(d.dv_dx) * tx + rounding,
                std::abs(d.du_dy) * ty + rounding, std::abs(d.dv_dy) * ty + rounding};
            for (std::size_t c = 0; c < 4; ++c) {
                worst = std::max(worst, std::abs(diff[c]) / tol[c]);
                REQUIRE(std::abs(diff[c]) <= tol[c]);
            }
        }
    }
    MESSAGE("worst difference / tolerance: " << worst);
}

TEST_CASE("on a plane at a known distance and angle the level matches its closed form" *
          doctest::description("points: 2; exercise: ch08-derivatives")) {
    // At the screen centre a plane at distance d, s texels per unit, seen through focal
    // length f, maps one pixel to s d / f texels across, and s d / (f cos a) texels along
    // the tilt: lambda = log2(s d / (f cos a)).
    const Pinhole eye{200.0, {160.0, 120.0}};
    for (double distance : {2.0, 5.0, 50.0, 400.0}) {
        for (double degrees : {0.0, 25.0, 50.0, 80.0}) {
            for (double s : {1.0, 16.0}) {
                const double a = degrees * std::numbers::pi / 180.0;
                const auto t = tilted_plane(eye, distance, a, s);
                const TexelDerivatives d = derivatives_at(t, eye.centre);
                const double across = s * distance / eye.focal;
                const double along = across / std::cos(a);
                CHECK(std::abs(d.du_dx) == doctest::Approx(across).epsilon(1e-12));
                CHECK(std::abs(d.dv_dy) == doctest::Approx(along).epsilon(1e-12));
                CHECK(d.dv_dx == doctest::Approx(0.0).epsilon(1e-12));
                CHECK(isotropic_level(d) ==
                      doctest::Approx(std::log2(along)).epsilon(1e-12));
                const Anisotropy an = anisotropy(d, 16);
                CHECK(an.probes == static_cast<int>(std::ceil(1.0 / std::cos(a))));
            }
        }
    }
}

TEST_CASE("the level is continuous across pixels") {
    // lambda = log2 max(|side x|, |side y|) is a maximum of continuous functions, so it
    // has no jumps: its change over a step h shrinks with h. On the receding floor below,
    // the largest change over h is at most h times the largest change over 1/16 px,
    // times 16 (plus a margin of 5%), for h from 1 px down to 2^-10 px.
    const Pinhole eye{200.0, {160.0, 120.0}};
    const auto floor_point = [&](double x, double z) {
        return project(eye, {x, -1.0, z}, {4.0 * x, 4.0 * z});
    };
    const std::array<TexturedVertex, 3> t{floor_point(-20, 1.2), floor_point(20, 1.2),
                                          floor_point(0, 60)};
    const auto largest_change = [&](double h) {
        double worst = 0.0;
        for (int y = 125; y < 240; y += 3) {
            for (int x = 40; x < 280; x += 3) {
                const Point2 p = pixel_centre(x, y);
                const double l = isotropic_level(derivatives_at(t, p));
                for (Point2 step : {Point2{h, 0}, Point2{0, h}, Point2{h, h}}) {
                    worst = std::max(
                        worst,
                        std::abs(isotropic_level(derivatives_at(t, p + step)) - l));
                }
            }
        }
        return worst;
    };
    const double reference = largest_change(1.0 / 16);
    for (int k = 0; k <= 10; ++k) {
        const double h = std::ldexp(1.0, -k);
        CHECK(largest_change(h) <= 1.05 * 16 * h * reference + 1e-12);
    }
    MESSAGE("largest change of the level between neighbouring pixels: "
            << largest_change(1.0));
}

TEST_CASE("trilinear blends two levels and is continuous across a level boundary") {
    const Texture f = f_texture(8); // 40 x 56: levels 40x56, 20x28, 10x14, 5x7, 2x3, 1x1
    const MipChain chain = build_mip_chain(f);
    REQUIRE(chain.levels.size() == 6);
    const TexCoord uv{13.3, 27.9};
    const LinearTexel l1 = sample_trilinear(chain, uv, 1.0, Wrap::repeat);
    const LinearTexel l2 = sample_trilinear(chain, uv, 2.0, Wrap::repeat);
    // Whole levels: bilinear on that level at the scaled coordinate (u * w_k / w_0).
    CHECK(l1 == sample_bilinear(chain.levels[1], TexCoord{13.3 * 20 / 40, 27.9 * 28 / 56},
                                Wrap::repeat));
    const LinearTexel mid = sample_trilinear(chain, uv, 1.25, Wrap::repeat);
    for (int c = 0; c < 4; ++c) {
        CHECK(mid[c] == doctest::Approx(0.75 * l1[c] + 0.25 * l2[c]).epsilon(1e-12));
        // Just below and just above level 2 the samples meet.
        const double below = sample_trilinear(chain, uv, 2.0 - 1e-9, Wrap::repeat)[c];
        CHECK(std::abs(below - l2[c]) < 1e-9 * linear_full);
    }
    // Outside the chain the level is clamped: magnification is level 0, far is 1 x 1.
    CHECK(sample_trilinear(chain, uv, -3.0, Wrap::repeat) ==
          sample_bilinear(chain.levels[0], uv, Wrap::repeat));
    CHECK(sample_trilinear(chain, uv, 99.0, Wrap::repeat) ==
          chain.levels.back().at(0, 0));
}

TEST_CASE(
    "anisotropic filtering spreads ceil(longer / shorter) probes along the long side") {
    const TexelDerivatives square{2.0, 0.0, 0.0, 2.0};
    CHECK(anisotropy(square, 8).probes == 1);
    CHECK(anisotropy(square, 8).level == 1.0);
    const TexelDerivatives stretched{0.5, 0.0, 0.0, 6.0}; // 12:1, along v
    const Anisotropy a = anisotropy(stretched, 8);
    CHECK(a.probes == 8); // capped
    CHECK(a.level == doctest::Approx(std::log2(6.0 / 8)));
    CHECK(a.axis == glm::dvec2{0.0, 6.0});
    CHECK(anisotropy(TexelDerivatives{3.0, 0.0, 0.0, 1.0}, 8).probes == 3);
    // With one probe allowed it is trilinear at the isotropic level.
    const MipChain chain = build_mip_chain(f_texture(4));
    const FilterSettings one{Filter::anisotropic, Wrap::repeat, 1};
    const FilterSettings tri{Filter::trilinear, Wrap::repeat, 1};
    const TexelDerivatives d{0.7, 0.2, -0.3, 3.1};
    CHECK(sample_filtered(chain, {5.5, 9.25}, d, one) ==
          sample_filtered(chain, {5.5, 9.25}, d, tri));
}

// The stub of ch08-derivatives (no derivatives, no change) breaks it.
TEST_CASE("the level's change between two points obeys its derived bound" *
          doctest::description("points: 1; exercise: ch08-derivatives")) {
    // @eq:level-bound on random perspective triangles, between random points inside
    // them at most 40 pixels apart: |lambda(at) - lambda(from)| <= 2 |log2(q(at) /
    // q(from))| + log2 max(g+ / g, g / g-). The bound is exact arithmetic on real
    // numbers; the only slack is rounding, 1e-9 of a level. The test also reports how
    // tight the bound is (the largest ratio of the change to its bound).
    Lcg random{18};
    int checked = 0;
    double tightest = 0.0;
    for (int n = 0; n < 500; ++n) {
        const std::array<TexturedVertex, 3> t = random_triangle(random);
        const auto inside = [&] {
            const double a = random(0, 1), b = random(0, 1 - a);
            return t[0].position + a * (t[1].position - t[0].position) +
                   b * (t[2].position - t[0].position);
        };
        for (int k = 0; k < 10; ++k) {
            const Point2 from = inside();
            Point2 at = inside();
            if (k % 2 == 0) {
                at.y = from.y; // along a span, as the per-span approximation uses it
            }
            if (std::max(std::abs(at.x - from.x), std::abs(at.y - from.y)) > 40.0) {
                continue;
            }
            const double bound = level_change_bound(t, from, at);
            if (!std::isfinite(bound)) {
                continue;
            }
            const double change = std::abs(isotropic_level(derivatives_at(t, at)) -
                                           isotropic_level(derivatives_at(t, from)));
            CHECK(change <= bound + 1e-9);
            tightest = std::max(tightest, bound > 0.0 ? change / bound : 0.0);
            ++checked;
        }
    }
    MESSAGE("pairs checked: " << checked << ", tightest change / bound: " << tightest);
    CHECK(checked > 2000);
    CHECK(tightest > 0.5); // the bound is not loose by orders of magnitude
}
