#include "exactpixels/scene/supersampled_reference.hpp"

#include "exactpixels/base/error.hpp"
#include "exactpixels/scene/scene_renderer.hpp"

#include <fmt/format.h>

namespace exactpixels {

std::vector<LinearTexel> linear_pixels(const Framebuffer& frame) {
    std::vector<LinearTexel> out;
    out.reserve(frame.pixels().size());
    for (const Rgba8 p : frame.pixels()) {
        out.push_back(decode_texel(p));
    }
    return out;
}

std::vector<LinearTexel> supersampled_reference(const Scene& scene, int s) {
    if (s < 1 || s > supersample_max_factor) {
        throw Error(fmt::format("{}: {} samples per side is outside [1, {}]",
                                scene.file.string(), s, supersample_max_factor));
    }
    if (static_cast<long long>(scene.width) * s > max_image_side ||
        static_cast<long long>(scene.height) * s > max_image_side) {
        throw Error(fmt::format("{}: {} x {} pixels at {} samples per side exceed the {} "
                                "allowed per side",
                                scene.file.string(), scene.width, scene.height, s,
                                max_image_side));
    }
    Scene big = scene;
    big.width = scene.width * s;
    big.height = scene.height * s;
    big.options.filter = SceneFilter::nearest;
    const std::vector<LinearTexel> samples = linear_pixels(render_scene(big).image);
    const auto w = static_cast<std::size_t>(scene.width);
    const auto big_w = static_cast<std::size_t>(big.width);
    const double weight = 1.0 / (double(s) * double(s));
    std::vector<LinearTexel> out(w * static_cast<std::size_t>(scene.height),
                                 LinearTexel{0.0});
    for (int y = 0; y < big.height; ++y) {
        for (int x = 0; x < big.width; ++x) {
            out[static_cast<std::size_t>(y / s) * w + static_cast<std::size_t>(x / s)] +=
                weight * samples[static_cast<std::size_t>(y) * big_w +
                                 static_cast<std::size_t>(x)];
        }
    }
    return out;
}

} // namespace exactpixels
