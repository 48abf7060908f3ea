// section_image.cpp: a scene's [image]: its size in pixels and its background.
#include "exactpixels/scene/scene_sections.hpp"

namespace exactpixels::scene_format {

void read_image(const Context& c, const toml::table& table, Scene& scene) {
    const TableReader t(c, table, "image", {"width", "height", "background"});
    if (const auto* n = t.find("width")) {
        scene.width = read_integer(c, *n, t.child("width"), 1, max_image_side);
    }
    if (const auto* n = t.find("height")) {
        scene.height = read_integer(c, *n, t.child("height"), 1, max_image_side);
    }
    if (static_cast<long long>(scene.width) * scene.height > max_image_pixels) {
        c.fail(t.table().source(), t.path(),
               fmt::format("{} x {} pixels is more than the {} allowed", scene.width,
                           scene.height, max_image_pixels));
    }
    if (const auto* n = t.find("background")) {
        scene.background = read_colour(c, *n, t.child("background"));
    }
    t.finish();
}

} // namespace exactpixels::scene_format
