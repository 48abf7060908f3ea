// scene_loader.hpp: reading a scene from a TOML file, checking every value on the way.
//
// Usage:
//   Scene scene = load_scene("scenes/floor.toml");   // throws Error on any bad input
//   Scene same = parse_scene(text, "floor.toml", "scenes"); // from a string
//
// The format is documented in chapter 7 (@sec:scene-format). Every message of a thrown
// Error starts with `FILE:LINE:COLUMN: KEY.PATH:` (the place of the offending value, or
// of the table that lacks a required key), then says what is wrong and what is
// allowed. Rejected: TOML syntax errors, unknown keys, values of the wrong type,
// values out of range (sizes, field of view, budget...), NaN and infinities, missing or
// unreadable texture files, and degenerate meshes (a triangle of zero area). Texture
// file paths are relative to the scene file's folder. Every limit below is checked
// before the memory it bounds is allocated.
#pragma once

#include "exactpixels/scene/scene.hpp"

#include <cstddef>
#include <filesystem>
#include <string_view>

namespace exactpixels {

/// The largest image side, pixels.
inline constexpr int max_image_side = 8192;
/// The largest image, pixels (2^24: 64 MiB of RGBA8).
inline constexpr long long max_image_pixels = 1LL << 24;
/// The largest texture side, texels (procedural or read from a PNG file).
inline constexpr int max_texture_side = 4096;
/// The most textures a scene may define.
inline constexpr int max_scene_textures = 64;
/// The most texel memory a scene's textures may take together, bytes (RGBA8: two
/// textures of the largest size, 128 MiB).
inline constexpr long long max_scene_texture_bytes =
    2LL * max_texture_side * max_texture_side * 4;
/// The smallest camera near plane, world units. With every vertex drawn at a depth of at
/// least this much, 1/w stays below 10^6 and u/w below 2^40, finite even in float.
inline constexpr double min_camera_near = 1e-6;
/// The most parts of one dotted key ("a.b.c" has 3). The TOML parser recurses once per
/// part, so the raw text is checked for this before it is parsed.
inline constexpr int max_key_parts = 64;
/// The largest scene file, bytes (4 MiB). It is read in pieces, so a larger file, or
/// an endless one such as /dev/zero, is refused after at most this much.
inline constexpr std::size_t max_scene_file_bytes = std::size_t{4} << 20;
/// The most triangles a scene may hold, counting a model's triangles once for every
/// `[[mesh]]` that names it.
inline constexpr long long max_scene_triangles = 1 << 20;
/// The most meshes a scene may hold, each material of a model counting as one (and so
/// the most `[[mesh]]` entries). The depth plan compares meshes in pairs.
inline constexpr int max_scene_meshes = 4096;
/// The most bytes of model (OBJ) files a scene may read, all its distinct models
/// together: as much as one model file may hold (max_model_file_bytes). Each file is
/// read once however many `[[mesh]]` entries name it.
inline constexpr long long max_scene_model_bytes = 64LL << 20;
/// The most lights (`[[light]]`) a scene may hold: each costs every lit pixel or vertex
/// a dot product, a square root and a power.
inline constexpr int max_scene_lights = 8;
/// The largest light intensity (a point light's at distance 1).
inline constexpr double max_light_intensity = 1e6;
/// The largest Blinn-Phong exponent: at 10^4 the highlight falls to half within 0.7
/// degrees of its peak, narrower than a pixel in any shipped scene.
inline constexpr double max_shininess = 1e4;

/// Parses and checks a scene given as TOML text. `file` names it in messages; texture
/// paths are resolved against `folder`. Throws Error (see above) on any bad input.
Scene parse_scene(std::string_view text, const std::filesystem::path& file,
                  const std::filesystem::path& folder);

/// Reads, parses and checks the scene file at `path`. Throws Error naming the path when
/// it cannot be read, and as parse_scene does for bad content.
Scene load_scene(const std::filesystem::path& path);

/// The files `scene` was read from: the scene file, then each texture's PNG. An output
/// must not be any of them (write_png's `inputs`).
std::vector<std::filesystem::path> scene_inputs(const Scene& scene);

/// The folder of the scenes that ship with chapter 7 (chapters/07-scenes/scenes in the
/// source tree this library was built from).
std::filesystem::path shipped_scene_folder();

/// The shipped scenes, in the order the chapter presents them (the first is the one
/// `exactpixels render` draws when given no scene).
std::vector<std::filesystem::path> shipped_scenes();

} // namespace exactpixels
