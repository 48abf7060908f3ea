#include "exactpixels/base/png.hpp"

#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/base/error.hpp"

#include <fmt/format.h>
#include <stb_image.h>
#include <stb_image_write.h>

namespace exactpixels {

void write_png(const std::filesystem::path& path, const Framebuffer& frame) {
    if (frame.width() <= 0 || frame.height() <= 0) {
        throw Error(fmt::format("{}: cannot write an empty {}x{} image", path.string(),
                                frame.width(), frame.height()));
    }
    write_atomically(path, "PNG", [&](const std::filesystem::path& temporary) {
        return stbi_write_png(temporary.c_str(), frame.width(), frame.height(), 4,
                              frame.pixels().data(), frame.width() * 4) != 0;
    });
}

Framebuffer read_png(const std::filesystem::path& path) {
    int width = 0, height = 0, channels = 0;
    unsigned char* data = stbi_load(path.c_str(), &width, &height, &channels, 4);
    if (data == nullptr) {
        throw Error(
            fmt::format("{}: cannot read image ({})", path.string(),
                        stbi_failure_reason() ? stbi_failure_reason() : "unknown"));
    }
    if (width <= 0 || height <= 0) {
        stbi_image_free(data);
        throw Error(fmt::format("{}: image has zero size", path.string()));
    }
    Framebuffer frame(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const unsigned char* p = data + (static_cast<std::size_t>(y) * width + x) * 4;
            frame.at(x, y) = rgba(p[0], p[1], p[2], p[3]);
        }
    }
    stbi_image_free(data);
    return frame;
}

} // namespace exactpixels
