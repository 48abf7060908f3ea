// scene_sections.hpp: the readers of a scene file's sections, one file each
// (section_*.cpp), called in the file's order by parse_scene (scene_loader.cpp). Each
// checks every key and value of its section and throws Error at the first bad one
// (scene_toml.hpp). Not for use outside the loader.
#pragma once

#include "exactpixels/scene/mesh_transform.hpp"
#include "exactpixels/scene/obj_model.hpp"
#include "exactpixels/scene/scene_toml.hpp"

#include <map>
#include <optional>
#include <string>
#include <sys/types.h>
#include <utility>

namespace exactpixels::scene_format {

/// [image]: width, height and background into `scene`. Error at the first bad key.
void read_image(const Context& c, const toml::table& table, Scene& scene);
/// [camera]: projection, field of view or view height, near and far, and the look-at.
/// Error at the first bad key, or a far not beyond near.
void read_camera(const Context& c, const toml::table& table, SceneCamera& camera);
/// [render]: precision, mapper, budget and the other options that apply to every mesh.
/// Error at the first bad key.
void read_render(const Context& c, const toml::table& table, RenderOptions& options);
/// [textures]: each named texture into scene.textures, its texels counted into
/// `texture_bytes` (against max_scene_texture_bytes) before they are made. Error at
/// the first bad key, an unreadable PNG, or texels beyond the limit.
void read_textures(const Context& c, const toml::table& table, Scene& scene,
                   long long& texture_bytes);
/// [[light]]: the array of lights into scene.lights. Error at the first bad key.
void read_lights(const Context& c, const toml::node& node, Scene& scene);
/// [[mesh]]: the array of meshes, each a primitive or a model file, into scene.meshes
/// (a model's textures into scene.textures), within the scene's triangle and mesh limits.
/// Error at the first bad key or value, or beyond a limit.
void read_meshes(const Context& c, const toml::node& node, Scene& scene,
                 long long& texture_bytes);

// Shared by the two kinds of [[mesh]] (section_meshes.cpp, section_models.cpp).

/// Which of the keys every mesh may have a mesh of this kind may have: a model has no
/// `texture` or `colour` (its materials say them) and may take its normals from the
/// file ("given"); a mesh of triangles or a quad may list a normal per vertex.
enum class MeshKind { primitive, primitive_with_normals, model };

/// The keys every mesh may have, in the order the messages list them.
const std::vector<std::string>& mesh_option_keys(MeshKind kind);
/// Reads the keys every mesh may have (name, texture, wrap, colour, cull, normals,
/// shading, specular, shininess) into `mesh`, and sets its name and origin. Error at
/// the first bad one.
void read_mesh_options(const TableReader& t, const Scene& scene, MeshKind kind,
                       SceneMesh& mesh);
/// The mesh's `scale`, `rotate` and `translate` (each optional; identity when none).
/// Error at the first bad one.
MeshTransform read_transform(const TableReader& t);
/// The keys of read_transform, in the order the messages list them.
const std::vector<std::string>& transform_keys();
/// Places the mesh by the transform, then checks what the scene asks of every mesh:
/// coordinates within the world limit, no triangle of zero area. Error naming the
/// first vertex or triangle that fails.
void place_and_check(const Context& c, const toml::table& table, const std::string& path,
                     SceneMesh& mesh, const MeshTransform& transform);

/// A model file as a scene holds it once: the model (its triangles in model space), the
/// scene texture each part's map_Kd became, and its triangle count.
struct LoadedModel {
    Model model; ///< its parts' triangles in model space
    std::vector<std::optional<std::size_t>> textures; ///< per part, into scene.textures
    long long triangles = 0;                          ///< of all its parts
};

/// The model files a scene has read, by identity (device and inode), so that every
/// reference to one file, however its path is spelled, reads and checks it once and
/// shares its textures.
struct ModelCache {
    std::map<std::pair<dev_t, ino_t>, LoadedModel> models; ///< by device and inode
    long long bytes = 0; ///< the sizes of the model files read so far
};

/// A `[[mesh]]` with `file = "model.obj"`: one SceneMesh per material its faces use, each
/// with that material's texture, appended to scene.meshes. `triangles` is the scene's
/// count so far: the copies are checked against max_scene_triangles and
/// max_scene_meshes before they are made. Error at the first bad key, a bad model
/// file (read_obj_model's), or beyond a limit.
void read_model(const Context& c, const toml::table& table, const std::string& path,
                Scene& scene, ModelCache& cache, long long& texture_bytes,
                long long triangles);

} // namespace exactpixels::scene_format
