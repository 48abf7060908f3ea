#include "exactpixels/scene/mesh_transform.hpp"

#include "exactpixels/base/error.hpp"

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <unordered_map>

namespace exactpixels {

namespace {

/// cos and sin of an angle in degrees, exact at whole quarter turns (where the library's
/// cos(pi / 2) would be 6e-17, not 0).
glm::dvec2 cos_sin_degrees(double degrees) {
    const double turns = degrees / 90.0;
    if (turns == std::floor(turns) && std::abs(turns) < 1e9) {
        const auto quarter = static_cast<long long>(turns) % 4;
        constexpr double table[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
        const auto k = static_cast<std::size_t>((quarter + 4) % 4);
        return {table[k][0], table[k][1]};
    }
    const double radians = degrees * std::numbers::pi / 180.0;
    return {std::cos(radians), std::sin(radians)};
}

} // namespace

//> transform
glm::dmat3 rotation_matrix(const glm::dvec3& degrees) {
    const glm::dvec2 x = cos_sin_degrees(degrees.x), y = cos_sin_degrees(degrees.y),
                     z = cos_sin_degrees(degrees.z);
    // glm matrices are built column by column: each line below is one column.
    const glm::dmat3 rx{{1, 0, 0}, {0, x[0], x[1]}, {0, -x[1], x[0]}}; // +y towards +z
    const glm::dmat3 ry{{y[0], 0, -y[1]}, {0, 1, 0}, {y[1], 0, y[0]}}; // +z towards +x
    const glm::dmat3 rz{{z[0], z[1], 0}, {-z[1], z[0], 0}, {0, 0, 1}}; // +x towards +y
    return rz * ry * rx;
}

glm::dvec3 transform_point(const MeshTransform& t, const glm::dvec3& p) {
    return t.translate + rotation_matrix(t.rotate_degrees) * (t.scale * p);
}

glm::dvec3 unit_normal(const glm::dvec3& n) {
    return glm::normalize(n / std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)}));
}

void transform_mesh(SceneMesh& mesh, const MeshTransform& t) {
    const glm::dmat3 rotation = rotation_matrix(t.rotate_degrees);
    for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
        for (SceneVertex& v : mesh.triangles[k]) {
            v.position = t.translate + rotation * (t.scale * v.position);
            if (v.normal != glm::dvec3{0.0}) { // inverse transpose of rotation * scale
                const glm::dvec3 n = rotation * (v.normal / t.scale);
                // Only a factor near the smallest normal double (2.2e-308) can take a
                // component of a unit normal beyond the doubles.
                if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) {
                    throw Error(fmt::format("the scale takes the normal of {} beyond "
                                            "the doubles",
                                            triangle_name(mesh, k)));
                }
                v.normal = unit_normal(n);
            }
        }
    }
}
//< transform

namespace {

/// A position's three doubles as bits: the key under which share_positions finds it.
using PositionBits = std::array<std::uint64_t, 3>;

PositionBits bits_of(const glm::dvec3& p) {
    return {std::bit_cast<std::uint64_t>(p.x), std::bit_cast<std::uint64_t>(p.y),
            std::bit_cast<std::uint64_t>(p.z)};
}

struct PositionBitsHash {
    std::size_t operator()(const PositionBits& b) const {
        std::uint64_t h = b[0];
        for (const std::uint64_t word : {b[1], b[2]}) {
            h = (h ^ (h >> 29)) * 0x9e3779b97f4a7c15u + word; // mixes, nothing exact
        }
        return static_cast<std::size_t>(h ^ (h >> 32));
    }
};

} // namespace

SharedPositions
shared_positions(const std::vector<std::array<SceneVertex, 3>>& triangles) {
    if (triangles.size() > std::numeric_limits<std::uint32_t>::max() / 3) {
        throw Error(
            fmt::format("a mesh of {} triangles is beyond 32-bit position indices",
                        triangles.size()));
    }
    SharedPositions shared;
    shared.corners.assign(triangles.size(), {});
    shared.uvs.assign(triangles.size(), {});
    std::unordered_map<PositionBits, std::uint32_t, PositionBitsHash> index;
    index.reserve(triangles.size()); // a closed mesh has about half as many
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        for (std::size_t k = 0; k < 3; ++k) {
            const glm::dvec3& p = triangles[t][k].position;
            const auto next = static_cast<std::uint32_t>(shared.positions.size());
            const auto [at, added] = index.try_emplace(bits_of(p), next);
            if (added) {
                shared.positions.push_back(p);
            }
            shared.corners[t][k] = at->second;
            shared.uvs[t][k] = triangles[t][k].uv;
        }
    }
    return shared;
}

bool index_matches(const std::vector<std::array<SceneVertex, 3>>& triangles,
                   const SharedPositions& index) {
    if (index.corners.size() != triangles.size() ||
        index.uvs.size() != triangles.size()) {
        return false;
    }
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        for (std::size_t k = 0; k < 3; ++k) {
            const SceneVertex& v = triangles[t][k];
            const std::uint32_t at = index.corners[t][k];
            if (at >= index.positions.size() ||
                std::memcmp(&index.positions[at], &v.position, sizeof v.position) != 0 ||
                std::memcmp(&index.uvs[t][k], &v.uv, sizeof v.uv) != 0) {
                return false;
            }
        }
    }
    return true;
}

void share_positions(SceneMesh& mesh) {
    SharedPositions shared = shared_positions(mesh.triangles);
    mesh.positions = std::move(shared.positions);
    mesh.corner_positions = std::move(shared.corners);
    mesh.corner_uvs = std::move(shared.uvs);
}

} // namespace exactpixels
