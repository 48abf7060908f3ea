// scene.hpp: a scene as the renderer sees it, after loading and checking (chapter 7).
//
// Usage:
//   Scene scene = load_scene("chapters/07-scenes/scenes/corridor.toml"); // scene_loader
//   RenderResult result = render_scene(scene);                        // scene_renderer
//
// World space: x right, y up, z forward (away from a camera at the default pose), the
// same handedness as view space. The camera looks from `position` at `target`; view
// space has the eye at the origin, x right, y up and z the depth along the view
// direction (z > 0 in front), as chapter 3's pinhole (perspective.hpp); the depth z is
// the w of chapter 3. Colours are RGB in [0, 1], sRGB codes / 255 (chapter 8); texture
// coordinates are in texels (texel (i, j) covers [i, i+1) x [j, j+1)). Everything in a
// Scene has been checked by the loader: sizes in range, numbers finite, no degenerate
// triangle.
#pragma once

#include "exactpixels/base/types.hpp"
#include "exactpixels/texture/texture.hpp"
#include "exactpixels/texture/texture_mapper.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace exactpixels {

/// How the camera maps view space to the screen.
enum class Projection {
    perspective, ///< a pinhole: screen position x / z, depth w = z varies
    orthographic ///< parallel rays: screen position x, depth w = 1 everywhere
};

/// The camera of a scene.
struct SceneCamera {
    Projection projection = Projection::perspective; ///< pinhole or parallel
    double fov_degrees = 60.0; ///< perspective: vertical field of view, (0, 180)
    double view_height = 2.0;  ///< orthographic: world units from top to bottom
    glm::dvec3 position = {0.0, 0.0, -4.0}; ///< the eye, world units
    glm::dvec3 target = {0.0, 0.0, 0.0};    ///< the point seen at the image centre
    glm::dvec3 up = {0.0, 1.0, 0.0};        ///< which way is up on screen
    double near = 0.1; ///< perspective: the near plane's depth, world units, > 0
    /// perspective: the far plane's depth, world units, > near; infinity (the default,
    /// `far` absent) is no far plane
    double far = std::numeric_limits<double>::infinity();
};

/// One corner of a mesh triangle in world space.
struct SceneVertex {
    glm::dvec3 position;             ///< world units
    TexCoord uv = {0.0, 0.0};        ///< texels (used only when the mesh has a texture)
    Colour colour = {1.0, 1.0, 1.0}; ///< sRGB code / 255 (used only with vertex colours)
    /// The unit normal the scene or a model gives this corner, world space; zero when
    /// none is given.
    glm::dvec3 normal = {0.0, 0.0, 0.0};
};

/// The mapper a scene asks for: one of chapter 3's, or `auto` (choose per triangle or
/// per span).
struct MapperChoice {
    bool automatic = true; ///< choose per triangle or span within the error budget
    Mapper mapper = {};    ///< the mapper when not automatic
    /// auto: affine on the whole triangle where its bound fits the budget
    /// (@eq:scene-triangle-bound), per span elsewhere; false: per span everywhere (the
    /// choice before the triangle test, for the chapter's comparison)
    bool per_triangle = true;
};

/// Whether the renderer runs a depth stage (@sec:scene-depth).
enum class DepthMode {
    off,      ///< no depth stage: meshes drawn in file order, later on top
    on,       ///< a depth buffer: the nearest surface wins, ties go to the later one
    automatic ///< on only when meshes can overlap on screen (the default)
};

/// How vertex colours are interpolated (@sec:scene-colours).
enum class ColourInterpolation {
    screen,      ///< linearly on screen (Gouraud; wrong under perspective)
    perspective, ///< c/w over 1/w, as chapter 3 interpolates u: one divide per pixel
    automatic    ///< per mesh: perspective when screen's error bound exceeds the budget
};

/// How the scene renderer turns texture coordinates into colours (chapter 8).
enum class SceneFilter {
    nearest,     ///< one texel per pixel, chapter 3's sampling (the default)
    bilinear,    ///< chapter 8's bilinear on level 0
    trilinear,   ///< chapter 8's trilinear across the mip chain
    anisotropic, ///< chapter 8's trilinear probes along the footprint's longer side
    automatic    ///< per triangle: bilinear where no corner is minified, else trilinear
};

/// Where lighting is computed (@sec:scene-lighting).
enum class Shading {
    gouraud, ///< per vertex: the lit colour interpolated by the colour stage
    phong    ///< per pixel: the normal interpolated, renormalised, lit at each pixel
};

/// The render options of a scene.
struct RenderOptions {
    Precision precision = Precision::float64; ///< the mappers' inner-loop arithmetic
    MapperChoice mapper = {};                 ///< which mapper, or auto
    double budget = 0.5;  ///< auto: the largest texel error allowed, texels, > 0
    bool rounding = true; ///< chapter 4's rounding modifier (false: rule 1 everywhere)
    DepthMode depth = DepthMode::automatic; ///< `depth = true | false | "auto"`
    /// `colours = "screen" | "perspective" | "auto"` (auto: `budget` in 8-bit levels)
    ColourInterpolation colours = ColourInterpolation::screen;
    /// `filter = "nearest" | "bilinear" | "trilinear" | "anisotropic" | "auto"`
    SceneFilter filter = SceneFilter::nearest;
    /// `shading = "gouraud" | "phong"`: the default of meshes without their own
    Shading shading = Shading::phong;
    Colour ambient = {0.0, 0.0, 0.0}; ///< light reaching every surface, sRGB / 255
};

/// How a light falls off.
enum class LightType {
    directional, ///< from far away: one direction and one strength everywhere
    point        ///< from a point: strength over the squared distance
};

/// A light of a scene (`[[light]]`).
struct SceneLight {
    LightType type = LightType::directional; ///< `type`
    glm::dvec3 direction = {0.0, 0.0, 1.0};  ///< directional: the way it travels, unit
    glm::dvec3 position = {0.0, 0.0, 0.0};   ///< point: world units
    Colour colour = {1.0, 1.0, 1.0};         ///< sRGB code / 255, each in [0, 1]
    double intensity = 1.0; ///< scales colour; a point light's, at distance 1
};

/// Where a mesh's normals come from (@sec:scene-normals).
enum class NormalSource {
    face,   ///< each triangle's own plane (flat facets)
    smooth, ///< area-weighted average of the faces at each shared position
    given   ///< the mesh's `normals` key, one per vertex
};

/// A named texture of a scene.
struct SceneTexture {
    std::string name;           ///< the key under [textures]
    Texture texture;            ///< the texels
    std::filesystem::path file; ///< the PNG it was read from (empty: procedural)
};

/// A mesh: triangles and the effects they call for.
struct SceneMesh {
    std::string name;                                  ///< for messages and reports
    std::vector<std::array<SceneVertex, 3>> triangles; ///< world space, none degenerate
    /// The distinct corner positions of `triangles`, each once (share_positions), and
    /// for each triangle the index of each corner's position: the geometry stage moves
    /// a position shared by several corners once. With them, each triangle's texture
    /// coordinates packed, 48 bytes a triangle: the lean geometry stage reads them, not
    /// the 264 bytes of `triangles` (on the big torus, a frame 8 % faster). All three
    /// empty, or all true of `triangles` (call share_positions again after changing a
    /// corner's position or uv); the geometry stage indexes a mesh made in code without
    /// them itself.
    std::vector<glm::dvec3> positions;
    std::vector<std::array<std::uint32_t, 3>> corner_positions; ///< into `positions`
    std::vector<std::array<TexCoord, 3>> corner_uvs; ///< per triangle, its corners' uv
    std::optional<std::size_t> texture;              ///< index into Scene::textures
    Wrap wrap = Wrap::repeat;                        ///< how its texture repeats
    bool vertex_colours = false;                     ///< interpolate SceneVertex::colour
    Colour colour = {1.0, 1.0, 1.0}; ///< the flat colour (texels are multiplied by it)
    bool cull_back = false;          ///< skip triangles whose back faces the camera
    NormalSource normals = NormalSource::face; ///< where lighting's normals come from
    std::optional<Shading> shading;            ///< the mesh's own, else the scene's
    Colour specular = {0.0, 0.0, 0.0};         ///< Blinn-Phong highlight colour
    double shininess = 32.0;                   ///< Blinn-Phong exponent
    std::string origin; ///< "FILE:LINE:COLUMN: mesh[k]", where the mesh was defined
    /// For a mesh read from an OBJ file: the file, and for each triangle the line of
    /// the face it was cut from, so that a message about a triangle can name it.
    std::string model;
    std::vector<std::size_t> model_lines; ///< the OBJ line of each triangle's face
};

/// How a message names triangle `k` of `mesh`: "triangle k", and for a model's
/// triangle also the OBJ file and line of its face.
inline std::string triangle_name(const SceneMesh& mesh, std::size_t k) {
    std::string name = "triangle " + std::to_string(k);
    if (k < mesh.model_lines.size()) {
        name += " (the face at " + mesh.model + ":" +
                std::to_string(mesh.model_lines[k]) + ")";
    }
    return name;
}

/// A loaded, checked scene.
struct Scene {
    std::filesystem::path file;          ///< where it was read from (for messages)
    int width = 320;                     ///< image width, pixels, [1, 8192]
    int height = 240;                    ///< image height, pixels, [1, 8192]
    Colour background = {0.0, 0.0, 0.0}; ///< RGB (sRGB code / 255) of uncovered pixels
    SceneCamera camera = {};             ///< how the scene is seen
    RenderOptions options = {};          ///< the [render] table's options
    std::vector<SceneTexture> textures;  ///< named textures
    std::vector<SceneMesh> meshes;       ///< drawn in order (later meshes on top)
    std::vector<SceneLight> lights;      ///< none: no lighting stage
    /// The OBJ and MTL files its `[[mesh]] file = ...` entries read.
    std::vector<std::filesystem::path> models;
};

} // namespace exactpixels
