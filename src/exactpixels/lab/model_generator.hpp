// model_generator.hpp: the OBJ models the project makes itself (chapter 7,
// @sec:scene-models): a textured torus, a room with furniture boxes, a terrain.
//
// Usage:
//   GeneratedModel torus = torus_model(36, 18);    // 36 x 18 quads, 1296 triangles
//   write_generated_model(torus, "models");         // models/torus.obj, .mtl, .png
//
// The files are what a modelling tool would write: right-handed coordinates (y up, the
// front towards +z), faces counter-clockwise seen from outside, texture coordinates
// with v up from the bottom of the image, numbers to 6 significant digits. Everything
// is a function of the arguments (no clock, no randomness but a fixed seed), so the
// committed models in chapters/07-scenes/models/ can be made again byte for byte.
#pragma once

#include "exactpixels/base/framebuffer.hpp"

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace exactpixels {

/// A model as files: NAME.obj, NAME.mtl and its textures, all in one folder.
struct GeneratedModel {
    std::string name; ///< the file stem
    std::string obj;  ///< the OBJ text (names NAME.mtl)
    std::string mtl;  ///< the MTL text (names the textures)
    std::vector<std::pair<std::string, Framebuffer>> textures; ///< file name, image
};

/// A torus around the y axis (radii 1 and 0.4) of `rings` x `sides` quads, with vertex
/// normals and a striped texture: 2 * rings * sides triangles. Both at least 3.
GeneratedModel torus_model(int rings, int sides, const std::string& name = "torus");

/// A 6 x 3 x 5 room (its faces turned inwards) with a wooden floor, a table, a bed and
/// a cabinet (boxes, faces outwards).
GeneratedModel room_model();

/// A `cells` x `cells` grid of triangle pairs over 8 x 8 units, heights a sum of two
/// waves, with vertex normals and a grass texture. At least 1.
GeneratedModel terrain_model(int cells);

/// The models committed in chapters/07-scenes/models/: torus_model(36, 18),
/// room_model(), terrain_model(24).
std::vector<GeneratedModel> shipped_models();

/// The speed test's model: torus_model(400, 128, "big_torus"), 102,400 triangles.
GeneratedModel big_torus_model();

/// A scene (TOML text) that draws big_torus.obj, from the same folder, whole at
/// 1280 x 720 with depth, back faces culled and mapper auto.
std::string big_torus_scene();

/// Writes the model's files into `folder` (each written atomically). Throws Error.
void write_generated_model(const GeneratedModel& model,
                           const std::filesystem::path& folder);

} // namespace exactpixels
