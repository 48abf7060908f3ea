#include "exactpixels/base/png.hpp"

#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/input_file.hpp"

#include <fmt/format.h>
#include <png.h>
#include <stb_image_write.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace exactpixels {

std::string encode_png(const Framebuffer& frame) {
    std::string bytes;
    const auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                                   static_cast<std::size_t>(size));
    };
    if (frame.width() <= 0 || frame.height() <= 0 ||
        stbi_write_png_to_func(append, &bytes, frame.width(), frame.height(), 4,
                               frame.pixels().data(), frame.width() * 4) == 0) {
        throw Error(fmt::format("cannot encode the {}x{} image as PNG", frame.width(),
                                frame.height()));
    }
    return bytes;
}

void write_png(const std::filesystem::path& path, const Framebuffer& frame,
               std::span<const std::filesystem::path> inputs) {
    if (frame.width() <= 0 || frame.height() <= 0) {
        throw Error(fmt::format("{}: cannot write an empty {}x{} image", path.string(),
                                frame.width(), frame.height()));
    }
    check_output(path, "PNG", inputs); // before the work of encoding
    std::string bytes;
    try {
        bytes = encode_png(frame);
    } catch (const Error& error) {
        throw Error(fmt::format("{}: {}", path.string(), error.what()));
    }
    write_file_atomically(path, "PNG", bytes, inputs);
}

Framebuffer read_png(const std::filesystem::path& path,
                     const std::function<void(int width, int height)>& check_size) {
    const std::string bytes =
        read_input_file(path, "PNG", max_png_file_bytes, InputKind::regular_file);
    return decode_png(bytes, path.string(), check_size);
}

Framebuffer decode_png(std::string_view bytes, const std::string& name,
                       const std::function<void(int width, int height)>& check_size) {
    const auto fail = [&](const std::string& reason) -> void {
        throw Error(fmt::format("{}: cannot read image ({})", name, reason));
    };
    constexpr std::size_t signature_bytes = 8;
    if (bytes.size() < signature_bytes ||
        png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0,
                    signature_bytes) != 0) {
        fail("not a PNG file: it does not start with the PNG signature");
    }
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    // png_image_free releases libpng's state however this function ends.
    const std::unique_ptr<png_image, void (*)(png_imagep)> guard(&image, png_image_free);
    if (png_image_begin_read_from_memory(&image, bytes.data(), bytes.size()) == 0) {
        fail(image.message);
    }
    const int width = static_cast<int>(image.width);
    const int height = static_cast<int>(image.height);
    if (image.width < 1 || image.height < 1 ||
        static_cast<long long>(image.width) * image.height > max_png_pixels) {
        fail(fmt::format("{}x{} pixels is more than the {} allowed", image.width,
                         image.height, max_png_pixels));
    }
    if (check_size) {
        check_size(width, height);
    }
    // A 16-bit file without a gAMA or sRGB chunk holds sRGB codes like an 8-bit one
    // (libpng would take it as linear light); each sample is read as the nearest 8-bit
    // code, round(v / 257).
    image.flags |= PNG_IMAGE_FLAG_16BIT_sRGB;
    image.format = PNG_FORMAT_RGBA; // 8 bits per channel, sRGB values as stored
    std::vector<std::uint8_t> data(PNG_IMAGE_SIZE(image));
    if (png_image_finish_read(&image, nullptr, data.data(), 0, nullptr) == 0) {
        fail(image.message);
    }
    Framebuffer frame(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::uint8_t* p =
                data.data() + (static_cast<std::size_t>(y) * image.width + x) * 4;
            frame.at(x, y) = rgba(p[0], p[1], p[2], p[3]);
        }
    }
    return frame;
}

} // namespace exactpixels
