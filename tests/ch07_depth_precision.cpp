// Chapter 7, @sec:scene-depth: the depth step of the renderer's float 1/w, of z/w in
// 24-bit fixed point and of reversed z in float (depth_precision.hpp), found again by
// searching for where each stored key changes, and the comparisons the chapter's figure
// and its prose draw from them.
#include "exactpixels/scene/depth_buffer.hpp"
#include "exactpixels/scene/depth_precision.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <functional>

using namespace exactpixels;

namespace {

constexpr double near = 0.1, far = 1000.0;

/// The three keys as each scheme stores them (its definition, written out again here).
double key_ours(double w) {
    return nearness_key(1.0 / w);
}
double key_fixed(double w) {
    return std::nearbyint(far * (w - near) / ((far - near) * w) * (std::ldexp(1.0, 24) - 1));
}
double key_reversed(double w) {
    return static_cast<float>(near * (far - w) / ((far - near) * w));
}

/// The first depth beyond w, towards `direction` (+1 farther, -1 nearer), whose key
/// differs from w's: found by doubling a step until the key changes, then halving the
/// bracket 80 times.
double key_edge(const std::function<double(double)>& key, double w, double direction) {
    double inside = w, step = w * std::ldexp(1.0, -40);
    while (key(w + direction * step) == key(w)) {
        inside = w + direction * step;
        step *= 2.0;
    }
    double outside = w + direction * step;
    for (int k = 0; k < 80; ++k) {
        const double middle = 0.5 * (inside + outside);
        (key(middle) == key(w) ? inside : outside) = middle;
    }
    return 0.5 * (inside + outside);
}

/// The width of the range of depths that store w's key, found by search.
double searched_step(const std::function<double(double)>& key, double w) {
    return key_edge(key, w, 1.0) - key_edge(key, w, -1.0);
}

} // namespace

TEST_CASE("each depth step is the width of the depths sharing one key") {
    for (double w = 0.13; w < 900.0; w *= 1.7) {
        INFO(w);
        CHECK(nearness_depth_step(w) ==
              doctest::Approx(searched_step(key_ours, w)).epsilon(1e-6));
        CHECK(fixed_z_depth_step(w, near, far, 24) ==
              doctest::Approx(searched_step(key_fixed, w)).epsilon(1e-6));
        CHECK(reversed_z_depth_step(w, near, far) ==
              doctest::Approx(searched_step(key_reversed, w)).epsilon(1e-6));
    }
}

TEST_CASE("fixed z/w loses depth as the square of the distance, float 1/w as the distance") {
    for (double w = 0.2; w < 10.0; w *= 1.3) {
        INFO(w);
        // Ten times farther: the fixed step about a hundred times larger, ours and
        // reversed z's about ten times (a float's relative spacing varies by 2).
        const double fixed = fixed_z_depth_step(10 * w, near, far, 24) /
                             fixed_z_depth_step(w, near, far, 24);
        CHECK(fixed > 99.0);
        CHECK(fixed < 101.0);
        for (const double ratio :
             {nearness_depth_step(10 * w) / nearness_depth_step(w),
              reversed_z_depth_step(10 * w, near, far) / reversed_z_depth_step(w, near, far)}) {
            CHECK(ratio > 5.0);
            CHECK(ratio < 20.0);
        }
        // Ours and reversed z within a factor of 2.5 of each other up to 100 units;
        // nearer the far plane reversed z is finer still (its d tends to 0).
        const double ours_over_reversed =
            nearness_depth_step(w) / reversed_z_depth_step(w, near, far);
        CHECK(ours_over_reversed > 0.4);
        CHECK(ours_over_reversed < 2.5);
    }
    // Past twice the near distance the fixed step is the larger (exercise 7's answer).
    CHECK(fixed_z_depth_step(0.25, near, far, 24) > nearness_depth_step(0.25));
    CHECK(fixed_z_depth_step(0.11, near, far, 24) < nearness_depth_step(0.11));
}
