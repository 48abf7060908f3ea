// section_lights.cpp: a scene's [[light]] tables, directional or point lights.
#include "exactpixels/scene/scene_sections.hpp"

namespace exactpixels::scene_format {

namespace {

/// One `[[light]]` table: its type decides which keys it may have.
SceneLight read_light(const Context& c, const toml::table& table,
                      const std::string& path) {
    const toml::node* type = table.get("type");
    if (type == nullptr) {
        c.fail(table.source(), path, "the required key 'type' is missing");
    }
    const bool point =
        read_choice(c, *type, path + ".type", {"directional", "point"}) == 1;
    const TableReader t(
        c, table, path,
        {"type", point ? "position" : "direction", "colour", "intensity"});
    SceneLight light;
    light.type = point ? LightType::point : LightType::directional;
    if (point) {
        light.position = read_point(c, t.require("position"), t.child("position"));
    } else {
        light.direction = read_direction(c, t.require("direction"), t.child("direction"));
    }
    if (const auto* n = t.find("colour")) {
        light.colour = read_colour(c, *n, t.child("colour"));
    }
    if (const auto* n = t.find("intensity")) {
        light.intensity =
            read_number(c, *n, t.child("intensity"), 0.0, max_light_intensity);
    }
    t.finish(); // a direction on a point light, or a position on a directional one
    return light;
}

} // namespace

void read_lights(const Context& c, const toml::node& node, Scene& scene) {
    const toml::array& list =
        read_array(c, node, "light", 1, static_cast<std::size_t>(max_scene_lights));
    for (std::size_t k = 0; k < list.size(); ++k) {
        const std::string path = fmt::format("light[{}]", k);
        scene.lights.push_back(read_light(c, read_table(c, *list.get(k), path), path));
    }
}

} // namespace exactpixels::scene_format
