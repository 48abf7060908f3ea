// section_textures.cpp: a scene's [textures]: procedural ones and PNG files, each
// counted against the scene's texel memory before it is made or decoded.
#include "exactpixels/base/test_pattern.hpp"
#include "exactpixels/scene/scene_sections.hpp"

namespace exactpixels::scene_format {

namespace {

/// Counts a width x height texture against the scene's texel memory `texture_bytes`,
/// before the texture exists. The Error names no place: its caller's does.
void count_texture_bytes(long long& texture_bytes, long long width, long long height) {
    texture_bytes += width * height * 4;
    if (texture_bytes > max_scene_texture_bytes) {
        throw Error(
            fmt::format("a {}x{} texture takes the scene's textures beyond the {} "
                        "bytes allowed",
                        width, height, max_scene_texture_bytes));
    }
}

/// One texture of [textures], made (or read) once its texels are counted.
Texture read_texture(const TableReader& t, long long& texture_bytes) {
    const Context& c = t.context();
    const auto take = [&](const toml::node& where, const std::string& path,
                          long long width, long long height) {
        try {
            count_texture_bytes(texture_bytes, width, height);
        } catch (const Error& error) {
            c.fail(where.source(), path, error.what());
        }
    };
    const std::size_t kind = read_choice(c, t.require("kind"), t.child("kind"),
                                         {"checkerboard", "grid", "f", "png"});
    const auto size = [&] {
        const toml::node& node = t.require("size");
        const toml::array& array = read_array(c, node, t.child("size"), 2, 2);
        return glm::ivec2{
            read_integer(c, *array.get(0), t.child("size") + "[0]", 1, max_texture_side),
            read_integer(c, *array.get(1), t.child("size") + "[1]", 1, max_texture_side)};
    };
    if (kind == 0 || kind == 1) { // checkerboard, grid
        const glm::ivec2 s = size();
        const char* key = kind == 0 ? "square" : "spacing";
        const int cell =
            read_integer(c, t.require(key), t.child(key), 1, max_texture_side);
        t.finish();
        take(t.require("size"), t.child("size"), s.x, s.y);
        if (kind == 0) {
            return checkerboard_texture(s.x, s.y, cell);
        }
        std::vector<Rgba8> texels; // lines one texel wide every `cell` texels
        for (int j = 0; j < s.y; ++j) {
            for (int i = 0; i < s.x; ++i) {
                const bool line = i % cell == 0 || j % cell == 0;
                texels.push_back(line ? rgba(250, 210, 60) : rgba(30, 40, 70));
            }
        }
        return Texture(s.x, s.y, std::move(texels));
    }
    if (kind == 2) { // the "F"
        const int cell = read_integer(c, t.require("cell"), t.child("cell"), 1, 256);
        t.finish();
        take(t.require("cell"), t.child("cell"), f_glyph_width * cell,
             f_glyph_height * cell);
        return f_texture(cell);
    }
    const toml::node& file = t.require("file");
    const std::filesystem::path path = c.folder / read_string(c, file, t.child("file"));
    t.finish();
    try { // every Error below names the path and the reason, and the catch its place
        return load_texture(path, [&](int width, int height) { // before decoding
            if (width > max_texture_side || height > max_texture_side) {
                throw Error(
                    fmt::format("{}: {}x{} texels is larger than the {} allowed per side",
                                path.string(), width, height, max_texture_side));
            }
            count_texture_bytes(texture_bytes, width, height);
        });
    } catch (const Error& error) {
        c.fail(file.source(), t.child("file"), error.what());
    }
}

} // namespace

void read_textures(const Context& c, const toml::table& table, Scene& scene,
                   long long& texture_bytes) {
    if (table.size() > static_cast<std::size_t>(max_scene_textures)) {
        c.fail(table.source(), "textures",
               fmt::format("{} textures are more than the {} allowed", table.size(),
                           max_scene_textures));
    }
    for (auto&& [key, node] : table) {
        const std::string path = "textures." + std::string(key.str());
        const TableReader reader(c, read_table(c, node, path), path,
                                 {"kind", "size", "square", "spacing", "cell", "file"});
        SceneTexture texture{
            std::string(key.str()), read_texture(reader, texture_bytes), {}};
        const toml::node* file = node.as_table()->get("file");
        if (file != nullptr && file->is_string()) { // read_texture has checked it
            texture.file = c.folder / file->as_string()->get();
        }
        scene.textures.push_back(std::move(texture));
    }
}

} // namespace exactpixels::scene_format
