#include "exactpixels/base/png.hpp"

#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/input_file.hpp"

#include <fmt/format.h>
#include <png.h>
#include <stb_image_write.h>
#include <zlib.h>

#include <algorithm>
#include <array>
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

PendingFile prepare_png(const std::filesystem::path& path, const Framebuffer& frame,
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
    return PendingFile(path, "PNG", bytes, inputs);
}

void write_png(const std::filesystem::path& path, const Framebuffer& frame,
               std::span<const std::filesystem::path> inputs) {
    prepare_png(path, frame, inputs).commit();
}

namespace {

/// The big-endian 32-bit number at `at` in `bytes` (the caller checks the bounds).
std::uint32_t big_endian_u32(std::string_view bytes, std::size_t at) {
    std::uint32_t value = 0;
    for (std::size_t k = 0; k < 4; ++k) {
        value = (value << 8) | static_cast<unsigned char>(bytes[at + k]);
    }
    return value;
}

/// Where the data of the first IHDR chunk starts. libpng skips unknown ancillary chunks
/// before it (a file may begin "mIHD"), so it is found by walking the chunks from the
/// signature, as libpng does, not assumed at byte 16. libpng has already checked that
/// the chunk exists, holds 13 bytes and has a valid colour type; a file that says
/// otherwise is refused here too, never read out of bounds.
std::size_t ihdr_data(std::string_view bytes, const std::string& name) {
    constexpr std::size_t ihdr_length = 13;
    std::size_t at = 8; // after the signature: chunks of length, type, data, CRC
    while (at + 8 <= bytes.size()) {
        const std::size_t length = big_endian_u32(bytes, at);
        if (bytes.compare(at + 4, 4, "IHDR") == 0) {
            if (length != ihdr_length || at + 8 + length > bytes.size()) {
                break;
            }
            return at + 8;
        }
        at += 12 + length;
    }
    throw Error(fmt::format("{}: cannot read image (no IHDR chunk of 13 bytes)", name));
}

/// The bytes an honest zlib stream of this PNG inflates to: for every row (of every
/// Adam7 pass, when interlaced), a filter byte and the row's packed samples. Read from
/// the IHDR chunk whose data starts at `ihdr`.
long long inflated_image_bytes(std::string_view bytes, std::size_t ihdr,
                               const std::string& name) {
    const long long width = big_endian_u32(bytes, ihdr);
    const long long height = big_endian_u32(bytes, ihdr + 4);
    const int bit_depth = static_cast<unsigned char>(bytes[ihdr + 8]);
    const int colour_type = static_cast<unsigned char>(bytes[ihdr + 9]);
    const bool interlaced = bytes[ihdr + 12] != 0;
    // Samples per pixel for colour types 0 (grey), 2 (RGB), 3 (palette), 4 (grey and
    // alpha) and 6 (RGBA).
    const std::array<int, 7> channels{1, 0, 3, 1, 2, 0, 4};
    if (colour_type >= static_cast<int>(channels.size()) || channels[colour_type] == 0) {
        throw Error(
            fmt::format("{}: cannot read image (colour type {})", name, colour_type));
    }
    const long long bits_per_pixel = channels[colour_type] * bit_depth;
    const auto rows_bytes = [&](long long pass_width, long long pass_height) {
        if (pass_width == 0 || pass_height == 0) {
            return 0LL; // an empty pass has no rows at all, not even filter bytes
        }
        return pass_height * (1 + (pass_width * bits_per_pixel + 7) / 8);
    };
    if (!interlaced) {
        return rows_bytes(width, height);
    }
    // Adam7: pass k takes every step_x-th pixel from start_x in every step_y-th row
    // from start_y.
    const std::array<int, 7> start_x{0, 4, 0, 2, 0, 1, 0}, start_y{0, 0, 4, 0, 2, 0, 1};
    const std::array<int, 7> step_x{8, 8, 4, 4, 2, 2, 1}, step_y{8, 8, 8, 4, 4, 2, 2};
    long long total = 0;
    for (std::size_t k = 0; k < 7; ++k) {
        const auto count = [](long long size, int start, int step) {
            return size > start ? (size - start + step - 1) / step : 0LL;
        };
        total += rows_bytes(count(width, start_x[k], step_x[k]),
                            count(height, start_y[k], step_y[k]));
    }
    return total;
}

/// Inflates the IDAT chunks of `bytes` into a small scratch buffer, counting bytes but
/// keeping none, and returns whether the stream ends within `limit` bytes. A stream
/// that is corrupt or cut short also returns true: libpng reports those when it reaches
/// the same byte, and it inflates no further than this did.
bool inflates_within(std::string_view bytes, long long limit) {
    z_stream z{};
    if (inflateInit(&z) != Z_OK) {
        throw Error("cannot start zlib to read a PNG file");
    }
    const std::unique_ptr<z_stream, int (*)(z_streamp)> guard(&z, inflateEnd);
    std::array<unsigned char, 1 << 16> scratch{};
    long long inflated = 0;
    std::size_t at = 8; // after the signature: chunks of length, type, data, CRC
    while (at + 8 <= bytes.size()) {
        const std::size_t length = big_endian_u32(bytes, at);
        // A chunk cut short by the end of the file still counts for what it holds:
        // libpng inflates that much before it finds the end.
        const std::size_t held = std::min<std::size_t>(length, bytes.size() - at - 8);
        if (bytes.compare(at + 4, 4, "IDAT") == 0) {
            z.next_in =
                reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data() + at + 8));
            z.avail_in = static_cast<uInt>(held);
            do { // until the chunk is used up and zlib holds back no output
                z.next_out = scratch.data();
                z.avail_out = static_cast<uInt>(scratch.size());
                const int status = inflate(&z, Z_NO_FLUSH);
                inflated += static_cast<long long>(scratch.size() - z.avail_out);
                if (inflated > limit) {
                    return false;
                }
                if (status == Z_BUF_ERROR) {
                    break; // no progress without the next chunk's bytes
                }
                if (status != Z_OK) {
                    return true; // the stream's end, or an error libpng reports
                }
            } while (z.avail_in > 0 || z.avail_out == 0);
        }
        if (held < length) {
            return true; // the file ends inside this chunk: libpng's error
        }
        at += 12 + length;
    }
    return true;
}

} // namespace

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
    // libpng inflates the whole stream to check its Adler-32, however far it goes on
    // past the image, so a small file could cost minutes: bound it first.
    const long long image_bytes =
        inflated_image_bytes(bytes, ihdr_data(bytes, name), name);
    if (!inflates_within(bytes, image_bytes + max_png_extra_inflated_bytes)) {
        fail(fmt::format("its image data inflates to more than the {} bytes of its {}x{} "
                         "pixels and {} to spare",
                         image_bytes, width, height, max_png_extra_inflated_bytes));
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
