// lighting.hpp: Lambert diffuse and Blinn-Phong specular light, and the normals they need
// (chapter 7, @sec:scene-lighting).
//
// Usage:
//   const std::vector<CornerNormals> n = mesh_normals(mesh);  // one per triangle
//   const std::vector<ViewLight> lights = lights_in_view(scene.lights, to_view);
//   Colour c = light_colour(lights, ambient, diffuse, material, point, normal, to_eye);
//
// Colours in and out are chapter 8's: each channel an sRGB code / 255. Inside, lighting
// works in linear light (a sum of lights may exceed 1; the framebuffer clamps it): the
// diffuse, specular, ambient and light colours are decoded, and the lit colour encoded
// once, at the end (srgb.hpp's curves). Lighting is computed in view space
// (the eye at the origin, x right, y up, z forward, as scene.hpp): positions in world
// units, normals and directions unit vectors. A normal points out of the front of a
// surface, the side from which its corners run counter-clockwise on screen. A light
// lights only the side its normal faces: behind a surface only the ambient term is left.
#pragma once

#include "exactpixels/base/types.hpp"
#include "exactpixels/scene/scene.hpp"

#include <array>
#include <functional>
#include <vector>

namespace exactpixels {

/// The shortest distance a point light is taken to be from a lit point, world units: a
/// light on a surface would otherwise bring it infinite irradiance (@eq:scene-falloff).
inline constexpr double min_light_distance = 1e-6;

/// The unit normals at the three corners of one triangle.
using CornerNormals = std::array<glm::dvec3, 3>;

/// The normal of a triangle's plane, pointing out of its front (unit length). The
/// corners must not be collinear.
glm::dvec3 face_normal(const std::array<SceneVertex, 3>& triangle);

/// The normals at every corner of every triangle of `mesh`, as the mesh asks
/// (@sec:scene-normals): `given`, the vertices' own; `face`, each triangle's face normal
/// at its three corners; `smooth`, at each corner the sum of the face normals of all the
/// triangles that share its position exactly, each weighted by its area, normalised.
std::vector<CornerNormals> mesh_normals(const SceneMesh& mesh);

/// mesh_normals, bit for bit, with `smooth`'s sums kept per shared position (`corners`
/// indexes the corners of mesh.triangles in `positions`, as SceneMesh's index does)
/// instead of looked up per corner in an ordered map. Exact where every position is
/// finite and no component is -0 (the map merges 0 and -0, the index does not);
/// elsewhere it is mesh_normals.
std::vector<CornerNormals>
mesh_normals_shared(const SceneMesh& mesh, const std::vector<glm::dvec3>& positions,
                    const std::vector<std::array<std::uint32_t, 3>>& corners);

/// A light as the shading code sees it: in view space, with its colour and intensity
/// folded into one radiance.
struct ViewLight {
    LightType type = LightType::directional; ///< how it falls off
    glm::dvec3 towards = {0.0, 0.0, -1.0};   ///< directional: unit vector to the light
    glm::dvec3 position = {0.0, 0.0, 0.0};   ///< point: view space, world units
    Colour radiance = {1.0, 1.0, 1.0};       ///< linear light: colour times intensity
};

/// The scene's lights moved to view space by `to_view`, a rotation (directions) plus a
/// translation (points): `to_view(p, true)` moves a point, `to_view(d, false)` a
/// direction.
std::vector<ViewLight>
lights_in_view(const std::vector<SceneLight>& lights,
               const std::function<glm::dvec3(glm::dvec3, bool)>& to_view);

/// What the surface does with light: its specular colour and exponent (the diffuse
/// colour comes from the pixel or the vertex, as the shading mode says).
struct Material {
    Colour specular = {0.0, 0.0, 0.0}; ///< sRGB code / 255, each in [0, 1]
    double shininess = 32.0;           ///< Blinn-Phong exponent, [1, max_shininess]
};

/// The light reaching a point from one light: its unit direction l towards the light
/// and the irradiance E it brings (radiance, over the squared distance for a point
/// light, @eq:scene-falloff).
struct Incident {
    glm::dvec3 towards; ///< unit vector from the point to the light
    Colour irradiance;  ///< linear light
};

/// The light `light` brings to the view-space point `p` (a point light at distance d
/// below min_light_distance counts as min_light_distance away).
Incident incident(const ViewLight& light, glm::dvec3 p);

/// The lit colour of a point (@eq:scene-lighting), in linear light: diffuse times
/// (ambient plus the sum of E max(0, n.l)) plus specular times the sum of E
/// max(0, n.h)^shininess over the lights with n.l > 0, where h is the unit half vector
/// of l and the unit vector to the eye. `ambient`, `diffuse` and the specular colour are
/// sRGB code / 255 and decoded first; the result is encoded back (unrounded, each
/// channel >= 0: @eq:scene-colour-rule). `normal` and `to_eye` are unit vectors; `p` is
/// the point in view space.
Colour light_colour(const std::vector<ViewLight>& lights, const Colour& ambient,
                    const Colour& diffuse, const Material& material, glm::dvec3 p,
                    glm::dvec3 normal, glm::dvec3 to_eye);

/// The shading a mesh gets: its own `shading` key, else the scene's.
Shading mesh_shading(const Scene& scene, const SceneMesh& mesh);

} // namespace exactpixels
