// geometry_lanes.hpp: two doubles side by side, for the geometry stage's lean forms
// (geometry_stage.cpp: outcodes two planes at a time, a corner's u/w and v/w tested
// together, the screen box grown in x and y at once).
//
// Usage:
//   const PlanePairs<10> pairs(a, b, c, d);          // planes a x + b y + c z + d
//   std::uint32_t code = pairs.negative_bits(p);      // bit i: plane i's value < 0
//   BitsPair ok = within(PlanePair{u, v} * one_w, PlanePair{limit, limit});
//
// Each lane is multiplied, added and compared as a double is (GCC's and Clang's vector
// extension; no FMA: the build forbids contraction), so a lane's value has the bits of
// the scalar expression written in the same order, and a comparison its truth.
#pragma once

#include "exactpixels/scene/render_report.hpp"

#include <glm/glm.hpp>

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace exactpixels {

/// Two doubles side by side.
using PlanePair = double __attribute__((vector_size(16)));
/// Two int64 lanes: a comparison's -1 (true) or 0 per lane.
using BitsPair = std::int64_t __attribute__((vector_size(16)));

/// Bit i set when lane i of `value` is < 0 (false for NaN).
inline std::uint32_t negative_lanes(PlanePair value) {
#if defined(__SSE2__)
    return static_cast<std::uint32_t>(
        _mm_movemask_pd(_mm_cmplt_pd(value, _mm_setzero_pd())));
#else
    return static_cast<std::uint32_t>(value[0] < 0.0) |
           static_cast<std::uint32_t>(value[1] < 0.0) << 1;
#endif
}

/// Per lane, |value| <= limit (false for NaN): std::abs clears the sign bit, as the
/// mask does.
inline BitsPair within(PlanePair value, PlanePair limit) {
    constexpr std::int64_t no_sign = std::numeric_limits<std::int64_t>::max();
    const BitsPair magnitude =
        std::bit_cast<BitsPair>(value) & BitsPair{no_sign, no_sign};
    return std::bit_cast<PlanePair>(magnitude) <= limit;
}

/// N planes a x + b y + c z + d (N even), planes 2k and 2k + 1 side by side in pair k.
template <std::size_t N> struct PlanePairs {
    static_assert(N % 2 == 0);
    // The coefficients, plane 2k's and plane 2k + 1's side by side in pair k.
    std::array<PlanePair, N / 2> a{}; ///< of x
    std::array<PlanePair, N / 2> b{}; ///< of y
    std::array<PlanePair, N / 2> c{}; ///< of z
    std::array<PlanePair, N / 2> d{}; ///< the constant
    /// Pairs up the planes with coefficients pa[i] x + pb[i] y + pc[i] z + pd[i].
    PlanePairs(const std::array<double, N>& pa, const std::array<double, N>& pb,
               const std::array<double, N>& pc, const std::array<double, N>& pd) {
        for (std::size_t k = 0; k < N / 2; ++k) {
            a[k] = PlanePair{pa[2 * k], pa[2 * k + 1]};
            b[k] = PlanePair{pb[2 * k], pb[2 * k + 1]};
            c[k] = PlanePair{pc[2 * k], pc[2 * k + 1]};
            d[k] = PlanePair{pd[2 * k], pd[2 * k + 1]};
        }
    }
    /// Bit i set when plane i's value at p, a x + b y + c z + d summed in that order, is
    /// < 0 (false for NaN).
    std::uint32_t negative_bits(const glm::dvec3& p) const {
        const PlanePair x{p.x, p.x}, y{p.y, p.y}, z{p.z, p.z};
        std::uint32_t bits = 0;
        for (std::size_t k = 0; k < N / 2; ++k) { // planes 2k and 2k + 1
            const PlanePair value = a[k] * x + b[k] * y + c[k] * z + d[k];
            bits |= negative_lanes(value) << (2 * k);
        }
        return bits;
    }
};

/// A stretch of triangles' counts, added to the report when the stretch ends (also when
/// an error ends it).
struct StretchCounts {
    RenderReport& report;    ///< where the counts go
    long long triangles = 0; ///< triangles the stretch met
    long long rejected = 0;  ///< of them, outside one plane
    long long culled = 0;    ///< of them, back faces culled
    /// Counts from zero into `to`.
    explicit StretchCounts(RenderReport& to) : report(to) {}
    StretchCounts(const StretchCounts&) = delete;
    StretchCounts& operator=(const StretchCounts&) = delete;
    ~StretchCounts() {
        report.geometry.triangles += triangles;
        report.rejected.triangles += rejected;
        report.culling.triangles += culled;
    }
};

} // namespace exactpixels
