// section_models.cpp: a [[mesh]] that names a model file (`file = "model.obj"`): each
// file read once however many meshes name it, its textures held once, and one mesh per
// material its faces use, each placed by the [[mesh]]'s own transform.
#include "exactpixels/scene/scene_sections.hpp"

#include <sys/stat.h>

namespace exactpixels::scene_format {

namespace {

/// Reads the model `model_path` names, or finds it in `cache`. A new model's files are
/// added to scene.models and its textures to scene.textures. Errors name `file`'s place.
const LoadedModel& load_model(const Context& c, const toml::node& file,
                              const std::string& path,
                              const std::filesystem::path& model_path, Scene& scene,
                              ModelCache& cache, long long& texture_bytes) {
    const auto read = [&] {
        try {
            return read_obj_model(model_path, texture_bytes);
        } catch (const Error& error) { // names the model's file and line, and the value
            c.fail(file.source(), path, error.what());
        }
    };
    struct stat info {};
    if (::stat(model_path.c_str(), &info) != 0) {
        // Missing or unreadable: read_obj_model says why, as for any input. A file that
        // appears in between is refused, not read without its size counted.
        read();
        c.fail(file.source(), path,
               fmt::format("{}: the model file changed while it was read",
                           model_path.string()));
    }
    const std::pair key{info.st_dev, info.st_ino};
    if (const auto found = cache.models.find(key); found != cache.models.end()) {
        return found->second;
    }
    // Checked from the file's size before it is read (read_obj_model refuses anything
    // but a regular file, whose size this is).
    if (cache.bytes + info.st_size > max_scene_model_bytes) {
        c.fail(file.source(), path,
               fmt::format("{}: {} bytes take the scene's model files beyond the {} "
                           "bytes allowed together",
                           model_path.string(), info.st_size, max_scene_model_bytes));
    }
    LoadedModel loaded{read(), {}, 0};
    cache.bytes += info.st_size;
    scene.models.insert(scene.models.end(), loaded.model.files.begin(),
                        loaded.model.files.end());
    for (ModelPart& part : loaded.model.parts) {
        loaded.triangles += static_cast<long long>(part.triangles.size());
        loaded.textures.emplace_back();
        if (part.texture) {
            if (scene.textures.size() >= static_cast<std::size_t>(max_scene_textures)) {
                c.fail(file.source(), path,
                       fmt::format("the model's textures take the scene beyond the {} "
                                   "textures allowed",
                                   max_scene_textures));
            }
            loaded.textures.back() = scene.textures.size();
            scene.textures.push_back(std::move(*part.texture));
            part.texture.reset(); // the scene holds it now; references use the index
        }
    }
    return cache.models.emplace(key, std::move(loaded)).first->second;
}

} // namespace

void read_model(const Context& c, const toml::table& table, const std::string& path,
                Scene& scene, ModelCache& cache, long long& texture_bytes,
                long long triangles) {
    std::vector<std::string> allowed = mesh_option_keys(MeshKind::model);
    allowed.insert(allowed.end(), transform_keys().begin(), transform_keys().end());
    const TableReader t(c, table, path, allowed);
    const toml::node& file = t.require("file");
    const std::filesystem::path model_path =
        c.folder / read_string(c, file, t.child("file"));
    SceneMesh options; // name, wrap, cull and lighting, for every part
    read_mesh_options(t, scene, MeshKind::model, options);
    const MeshTransform transform = read_transform(t);
    t.finish();
    const LoadedModel& loaded =
        load_model(c, file, t.child("file"), model_path, scene, cache, texture_bytes);
    if (options.normals == NormalSource::given && loaded.model.line_without_normal != 0) {
        c.fail(t.find("normals")->source(), t.child("normals"),
               fmt::format("\"given\" needs a normal at every corner, and the face at "
                           "{}:{} has a corner without one (no vn index)",
                           model_path.string(), loaded.model.line_without_normal));
    }
    if (triangles + loaded.triangles > max_scene_triangles) {
        c.fail(file.source(), t.child("file"),
               fmt::format("the model's {} triangles take the scene beyond the {} "
                           "triangles allowed",
                           loaded.triangles, max_scene_triangles));
    }
    if (scene.meshes.size() + loaded.model.parts.size() >
        static_cast<std::size_t>(max_scene_meshes)) {
        c.fail(file.source(), t.child("file"),
               fmt::format("the model's {} materials take the scene beyond the {} "
                           "meshes allowed",
                           loaded.model.parts.size(), max_scene_meshes));
    }
    for (std::size_t k = 0; k < loaded.model.parts.size(); ++k) {
        const ModelPart& part = loaded.model.parts[k];
        SceneMesh mesh = options;
        mesh.name =
            part.material.empty() ? options.name : options.name + "/" + part.material;
        mesh.triangles = part.triangles; // copies: each reference is placed on its own
        mesh.model = model_path.string();
        mesh.model_lines = part.lines;
        mesh.colour = part.colour;
        mesh.texture = loaded.textures[k];
        place_and_check(c, table, path, mesh, transform);
        scene.meshes.push_back(std::move(mesh));
    }
}

} // namespace exactpixels::scene_format
