// meshes.hpp: triangle sets shared by the coverage tests of several chapters: a grid
// mesh with jittered interior vertices (chapter 2) and a fan of slivers around a hub
// (chapters 2 and 6). Both cover their area exactly once under the top-left rule.
#pragma once

#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/base/types.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace exactpixels::testing {

/// A grid mesh of n x n cells of `cell` px starting at `origin`, every cell split
/// into two triangles along a diagonal (alternating), interior vertices moved by
/// `jitter(i, j)` (a point added in px). The mesh covers the square exactly.
template <class Jitter>
std::vector<std::array<FixedPoint2, 3>> grid_mesh(Point2 origin, int n, double cell,
                                                  Jitter jitter) {
    std::vector<std::vector<FixedPoint2>> p(n + 1, std::vector<FixedPoint2>(n + 1));
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
            const bool border = i == 0 || j == 0 || i == n || j == n;
            const Point2 q = origin + Point2{i * cell, j * cell} +
                             (border ? Point2{0, 0} : jitter(i, j));
            p[j][i] = snap_to_subpixel(q);
        }
    }
    std::vector<std::array<FixedPoint2, 3>> mesh;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            if ((i + j) % 2 == 0) {
                mesh.push_back({p[j][i], p[j][i + 1], p[j + 1][i + 1]});
                mesh.push_back({p[j][i], p[j + 1][i + 1], p[j + 1][i]});
            } else {
                mesh.push_back({p[j][i], p[j][i + 1], p[j + 1][i]});
                mesh.push_back({p[j][i + 1], p[j + 1][i + 1], p[j + 1][i]});
            }
        }
    }
    return mesh;
}

/// `count` slivers sharing the snapped hub, out to a circle of `radius` px snapped at
/// `count` points: triangle k spans the angles 2 pi k / count to 2 pi (k + 1) / count.
inline std::vector<std::array<FixedPoint2, 3>> sliver_fan(Point2 hub, double radius,
                                                          int count) {
    const auto rim = [&](int k) {
        const double angle = 2 * std::numbers::pi * k / count;
        return snap_to_subpixel(hub + radius * Point2{std::cos(angle), std::sin(angle)});
    };
    std::vector<std::array<FixedPoint2, 3>> fan;
    for (int k = 0; k < count; ++k) {
        fan.push_back({snap_to_subpixel(hub), rim(k), rim(k + 1)});
    }
    return fan;
}

} // namespace exactpixels::testing
