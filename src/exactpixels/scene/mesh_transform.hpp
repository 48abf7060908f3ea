// mesh_transform.hpp: placing a mesh in the world by scale, rotation and translation
// (chapter 7, @sec:scene-models).
//
// Usage:
//   MeshTransform t;                  // the identity
//   t.scale = {2.0, 2.0, 2.0};        // factors along x, y, z, each > 0
//   t.rotate_degrees = {0.0, 90.0, 0.0};
//   t.translate = {0.0, 0.0, 5.0};    // world units
//   transform_mesh(mesh, t);          // positions and normals, in place
//   share_positions(mesh);            // each distinct position listed once
//
// The order is fixed: scale, then rotate about x, then about y, then about z, then
// translate: p' = translate + Rz Ry Rx (scale * p) (@eq:scene-transform). Angles are in
// degrees; a positive angle about x turns +y towards +z, about y turns +z towards +x,
// about z turns +x towards +y. Normals are carried by the inverse transpose of the
// linear part, Rz Ry Rx / scale, and normalised again.
#pragma once

#include "exactpixels/scene/scene.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace exactpixels {

/// Where a mesh goes: scale, rotation and translation, applied in that order.
struct MeshTransform {
    glm::dvec3 scale = {1.0, 1.0, 1.0};          ///< factors along x, y, z, each > 0
    glm::dvec3 rotate_degrees = {0.0, 0.0, 0.0}; ///< about x, then y, then z, degrees
    glm::dvec3 translate = {0.0, 0.0, 0.0};      ///< world units, applied last
};

/// The rotation Rz Ry Rx of `degrees` (about x first), as a 3x3 matrix.
glm::dmat3 rotation_matrix(const glm::dvec3& degrees);

/// The point `p` placed by `t`: translate + Rz Ry Rx (scale * p).
glm::dvec3 transform_point(const MeshTransform& t, const glm::dvec3& p);

/// The vector of length 1 in the direction of `n` (finite, not zero). It is divided by
/// its largest component first, so that the sum of squares can neither overflow nor
/// underflow to 0, whatever finite numbers `n` holds.
glm::dvec3 unit_normal(const glm::dvec3& n);

/// Moves every vertex of `mesh` by `t`; normals by the inverse transpose, made of
/// length 1 by unit_normal (a zero normal stays zero). Throws Error, naming the
/// triangle, when a scale factor below the smallest normal double takes a normal
/// beyond the doubles.
void transform_mesh(SceneMesh& mesh, const MeshTransform& t);

/// A mesh's corner positions as an indexed mesh: each distinct position once (equal
/// bit for bit: 0 and -0 differ), in the order they first appear, and each triangle's
/// corners as indices into that list; with each triangle's texture coordinates packed
/// beside them, the rest of what the geometry stage reads of a corner.
struct SharedPositions {
    std::vector<glm::dvec3> positions;                 ///< distinct, in first-seen order
    std::vector<std::array<std::uint32_t, 3>> corners; ///< per triangle, into positions
    std::vector<std::array<TexCoord, 3>> uvs;          ///< per triangle, its corners' uv
};

/// The indexed positions of `triangles`. Throws Error beyond 32-bit indices (over
/// 2^32 / 3 triangles; the loader stops at 2^20).
SharedPositions
shared_positions(const std::vector<std::array<SceneVertex, 3>>& triangles);

/// Whether `index` is true of `triangles`: each corner's position at its index, and its
/// texture coordinate packed, bit for bit.
bool index_matches(const std::vector<std::array<SceneVertex, 3>>& triangles,
                   const SharedPositions& index);

/// Fills mesh.positions, mesh.corner_positions and mesh.corner_uvs with
/// shared_positions(mesh.triangles). The loader calls it once a mesh is placed; code
/// that moves a corner or changes its texture coordinate afterwards calls it again (or
/// clears them) before rendering.
void share_positions(SceneMesh& mesh);

} // namespace exactpixels
