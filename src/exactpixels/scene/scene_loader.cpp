// scene_loader.cpp: a scene file read section by section, in the order of the format
// (chapter 7, @sec:scene-format): the text checked and parsed (scene_toml_text.cpp), then
// [image], [camera], [render], [textures], [[light]] and [[mesh]] (section_*.cpp).
#include "exactpixels/scene/scene_loader.hpp"

#include "exactpixels/base/input_file.hpp"
#include "exactpixels/scene/scene_sections.hpp"

#ifndef EXACTPIXELS_SCENES_DIR
#define EXACTPIXELS_SCENES_DIR "chapters/07-scenes/scenes"
#endif

namespace exactpixels {

static_assert(max_scene_model_bytes == static_cast<long long>(max_model_file_bytes),
              "a scene's models together may be as large as one model file");

Scene parse_scene(std::string_view text, const std::filesystem::path& file,
                  const std::filesystem::path& folder) {
    using namespace scene_format;
    Context context{file.string(), folder, text, {}};
    check_key_depth(context, text);
    const toml::table root = parse_toml(context);
    const Context& c = context;
    Scene scene;
    scene.file = file;
    const TableReader top(c, root, "",
                          {"image", "camera", "render", "textures", "mesh", "light"});
    const auto section = [&](const char* key) -> const toml::table* {
        const toml::node* n = top.find(key);
        return n ? &read_table(c, *n, key) : nullptr;
    };
    if (const toml::table* t = section("image")) {
        read_image(c, *t, scene);
    }
    if (const toml::table* t = section("camera")) {
        read_camera(c, *t, scene.camera);
    }
    if (const toml::table* t = section("render")) {
        read_render(c, *t, scene.options);
    }
    long long texture_bytes = 0; // the texel memory of the textures so far
    if (const toml::table* t = section("textures")) {
        read_textures(c, *t, scene, texture_bytes);
    }
    if (const toml::node* lights = top.find("light")) {
        read_lights(c, *lights, scene);
    }
    const toml::node* meshes = top.find("mesh");
    if (meshes == nullptr) {
        c.fail(root.source(), "mesh", "the scene has no [[mesh]]: nothing to draw");
    }
    read_meshes(c, *meshes, scene, texture_bytes);
    top.finish();
    return scene;
}

Scene load_scene(const std::filesystem::path& path) {
    const std::string text =
        read_input_file(path, "scene", max_scene_file_bytes, InputKind::any);
    return parse_scene(text, path, path.parent_path());
}

std::vector<std::filesystem::path> scene_inputs(const Scene& scene) {
    std::vector<std::filesystem::path> files{scene.file};
    files.insert(files.end(), scene.models.begin(), scene.models.end());
    for (const SceneTexture& texture : scene.textures) {
        if (!texture.file.empty()) {
            files.push_back(texture.file);
        }
    }
    return files;
}

std::filesystem::path shipped_scene_folder() {
    return EXACTPIXELS_SCENES_DIR;
}

std::vector<std::filesystem::path> shipped_scenes() {
    const std::filesystem::path folder = shipped_scene_folder();
    return {folder / "corridor.toml", folder / "horizon.toml",    folder / "gouraud.toml",
            folder / "sprites.toml",  folder / "near_plane.toml", folder / "boxes.toml",
            folder / "lit.toml"};
}

} // namespace exactpixels
