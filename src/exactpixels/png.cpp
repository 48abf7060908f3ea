#include "exactpixels/png.hpp"

#include "exactpixels/atomic_file.hpp"
#include "exactpixels/error.hpp"

#include <fmt/format.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include <string>

namespace exactpixels {

void write_png(const std::filesystem::path& path, const Framebuffer& frame,
               std::span<const std::filesystem::path> inputs) {
    if (frame.width() <= 0 || frame.height() <= 0) {
        throw Error(fmt::format("{}: cannot write an empty {}x{} image", path.string(),
                                frame.width(), frame.height()));
    }
    check_output(path, "PNG", inputs); // before the work of encoding
    std::string bytes;
    const auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                                   static_cast<std::size_t>(size));
    };
    if (stbi_write_png_to_func(append, &bytes, frame.width(), frame.height(), 4,
                               frame.pixels().data(), frame.width() * 4) == 0) {
        throw Error(fmt::format("{}: cannot encode the {}x{} image as PNG", path.string(),
                                frame.width(), frame.height()));
    }
    write_file_atomically(path, "PNG", bytes, inputs);
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
