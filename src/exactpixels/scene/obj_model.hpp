// obj_model.hpp: reading a Wavefront OBJ model and its MTL materials (chapter 7,
// @sec:scene-models), every line checked before tinyobjloader reads the structure (which
// elements each face corner names, which material each face uses). Every number in the
// model is the check's reading of it, never tinyobjloader's, which differs (it reads
// 0.3 as 3 * 0.1). A UTF-8 byte-order mark at the start of a file is skipped.
//
// Usage:
//   long long texture_bytes = 0; // the scene's texel memory so far
//   Model torus = read_obj_model("models/torus.obj", texture_bytes); // throws Error
//   for (const ModelPart& part : torus.parts) { /* one material's triangles */ }
//
// The subset read (anything else is an Error): in the OBJ file `v x y z`, `vt u v [w]`,
// `vn x y z`, `f` with 3 to max_face_corners corners written `v`, `v/vt`, `v//vn` or
// `v/vt/vn` (1-based indices, or negative ones counting back from the last element
// read so far), `usemtl`, `mtllib` (one file per line), `o`, `g`, `s` and comments; in
// the MTL file `newmtl`, `Kd r g b` (each in [0, 1]), `map_Kd file.png` (no options),
// and the numeric statements Ka, Ks, Ke, Ns, Ni, d, Tr and illum, which are checked and
// ignored. Paths are relative to the file that names them.
//
// Units and conventions: OBJ is right-handed (x right, y up, z towards the viewer); the
// scene's world is left-handed (z forward). A model is read with z negated, which keeps
// its shape (no mirror image), turns its front (+z) towards the default camera, and
// keeps its faces counter-clockwise seen from outside, as the renderer's back-face test
// wants. Texture coordinates (u, v), with v up from the bottom of the image, become
// texels (u * width, (1 - v) * height). Polygons are cut into a fan of triangles from
// their first corner; a fan covers a polygon exactly only when it is convex, so a face
// that is not strictly convex (or is degenerate) is an Error naming its line.
//
// Errors: every message starts with `FILE:LINE: ` (the OBJ or MTL file and the line of
// the offending statement), then names the value and what is allowed. Every limit below
// is checked before the memory it bounds is allocated.
#pragma once

#include "exactpixels/scene/scene.hpp"

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace exactpixels {

/// The largest OBJ file, bytes (64 MiB: about a million triangles).
inline constexpr std::size_t max_model_file_bytes = std::size_t{64} << 20;
/// The largest MTL file, bytes.
inline constexpr std::size_t max_material_file_bytes = std::size_t{1} << 20;
/// The most positions (and, separately, texture coordinates and normals) of one model.
inline constexpr long long max_model_vertices = 1 << 21;
/// The most triangles one model's faces may make (a face of n corners makes n - 2).
inline constexpr long long max_model_triangles = 1 << 20;
/// The most corners of one face.
inline constexpr int max_face_corners = 64;
/// The most materials of one model.
inline constexpr int max_model_materials = 64;
/// Model coordinates lie within +-this (the scene's world limit).
inline constexpr double max_model_coordinate = 1e6;
/// Texture coordinates lie within +-this (in texture widths: 256 widths of the largest
/// texture are 2^20 texels, the scene's limit).
inline constexpr double max_model_texcoord = 256.0;

/// One material's triangles in model space (after the z flip, before any transform).
struct ModelPart {
    std::string material;                              ///< its name, or "" for none
    Colour colour = {1.0, 1.0, 1.0};                   ///< Kd, sRGB code / 255
    std::optional<SceneTexture> texture;               ///< map_Kd, read from its PNG
    std::vector<std::array<SceneVertex, 3>> triangles; ///< uv in texels of `texture`
    std::vector<std::size_t> lines; ///< for each triangle, the line of its face
};

/// A model: its parts, one per material its faces use, in order of first use.
struct Model {
    std::vector<ModelPart> parts;             ///< none empty
    std::vector<std::filesystem::path> files; ///< the OBJ and MTL files read
    bool normals = false; ///< every face gave a normal for every corner
    /// The line of the first face with a corner without a normal (`vn`), or 0 when every
    /// corner has one: what `normals = "given"` cannot light.
    std::size_t line_without_normal = 0;
};

/// Parses and checks the OBJ text of `file`; mtllib and map_Kd paths are resolved
/// against `folder`. Texture memory is counted into `texture_bytes` and checked against
/// max_scene_texture_bytes before decoding. Throws Error (see above) on any bad input.
Model parse_obj_model(std::string_view text, const std::filesystem::path& file,
                      const std::filesystem::path& folder, long long& texture_bytes);

/// Reads the OBJ file at `path` (a regular file of at most max_model_file_bytes) and
/// parses it as parse_obj_model does. Throws Error naming the path when it cannot be
/// read.
Model read_obj_model(const std::filesystem::path& path, long long& texture_bytes);

} // namespace exactpixels
