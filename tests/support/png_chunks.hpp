// png_chunks.hpp: editing the chunks of a PNG file's bytes, for tests that corrupt one
// thing (a CRC, the zlib checksum, the size in the header) and nothing else, and making
// PNG files chunk by chunk, for tests that need what no encoder here writes (16-bit
// samples, a chosen gAMA or sRGB chunk, compressed data longer than the image).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <zlib.h>

namespace exactpixels::testing {

/// The CRC-32 of `bytes` as PNG computes it (ISO 3309, polynomial 0xEDB88320).
inline std::uint32_t png_crc(const std::string& bytes) {
    std::uint32_t crc = 0xFFFFFFFFu;
    for (const char byte : bytes) {
        crc ^= static_cast<unsigned char>(byte);
        for (int bit = 0; bit < 8; ++bit) {
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
        }
    }
    return crc ^ 0xFFFFFFFFu;
}

/// The big-endian 32-bit number at `offset`.
inline std::uint32_t read_u32(const std::string& bytes, std::size_t offset) {
    std::uint32_t value = 0;
    for (std::size_t k = 0; k < 4; ++k) {
        value = (value << 8) | static_cast<unsigned char>(bytes.at(offset + k));
    }
    return value;
}

/// Writes `value` big-endian at `offset`.
inline void write_u32(std::string& bytes, std::size_t offset, std::uint32_t value) {
    for (std::size_t k = 0; k < 4; ++k) {
        bytes.at(offset + k) = static_cast<char>((value >> (24 - 8 * k)) & 0xFF);
    }
}

/// Where one chunk sits: its data's offset and length (the CRC follows the data).
struct PngChunk {
    std::size_t data = 0;
    std::size_t length = 0;
};

/// The first chunk of type `type` ("IHDR", "IDAT") in the PNG `bytes`.
inline PngChunk find_chunk(const std::string& bytes, const std::string& type) {
    std::size_t at = 8; // after the signature
    while (at + 12 <= bytes.size()) {
        const std::size_t length = read_u32(bytes, at);
        if (bytes.compare(at + 4, 4, type) == 0) {
            return {at + 8, length};
        }
        at += 12 + length;
    }
    throw std::runtime_error("no " + type + " chunk");
}

/// Recomputes the CRC of the chunk whose data is at `chunk` (after its data changed).
inline void fix_crc(std::string& bytes, const PngChunk& chunk) {
    write_u32(bytes, chunk.data + chunk.length,
              png_crc(bytes.substr(chunk.data - 4, chunk.length + 4)));
}

/// One chunk: its length, its type, `data` and its CRC.
inline std::string png_chunk(const std::string& type, const std::string& data) {
    std::string chunk(4, '\0');
    write_u32(chunk, 0, static_cast<std::uint32_t>(data.size()));
    chunk += type + data + std::string(4, '\0');
    write_u32(chunk, chunk.size() - 4, png_crc(type + data));
    return chunk;
}

/// A PNG file: the signature, IHDR, the chunks `before_idat` (whole chunks, from
/// png_chunk), one IDAT holding the zlib stream `idat`, and IEND.
inline std::string png_file(std::uint32_t width, std::uint32_t height, int bit_depth,
                            int colour_type, const std::string& before_idat,
                            const std::string& idat, bool interlaced = false) {
    std::string ihdr(13, '\0');
    write_u32(ihdr, 0, width);
    write_u32(ihdr, 4, height);
    ihdr[8] = static_cast<char>(bit_depth);
    ihdr[9] = static_cast<char>(colour_type);
    ihdr[12] = interlaced ? 1 : 0; // Adam7
    return std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", ihdr) + before_idat +
           png_chunk("IDAT", idat) + png_chunk("IEND", "");
}

/// The zlib stream of `raw` followed by `zeros` zero bytes, compressed in pieces so that
/// a stream that inflates to gigabytes never exists uncompressed.
inline std::string zlib_stream(const std::string& raw, std::size_t zeros = 0) {
    z_stream z{};
    if (deflateInit2(&z, 9, Z_DEFLATED, 15, 9, Z_RLE) != Z_OK) {
        throw std::runtime_error("deflateInit2 failed");
    }
    std::string out;
    std::array<unsigned char, 1 << 16> buffer{};
    const std::string zero_piece(std::size_t{1} << 20, '\0');
    const auto feed = [&](const char* data, std::size_t size, int flush) {
        z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data));
        z.avail_in = static_cast<uInt>(size);
        do {
            z.next_out = buffer.data();
            z.avail_out = static_cast<uInt>(buffer.size());
            deflate(&z, flush);
            out.append(reinterpret_cast<const char*>(buffer.data()),
                       buffer.size() - z.avail_out);
        } while (z.avail_out == 0 || z.avail_in > 0);
    };
    feed(raw.data(), raw.size(), Z_NO_FLUSH);
    for (std::size_t left = zeros; left > 0;) {
        const std::size_t size = std::min(left, zero_piece.size());
        feed(zero_piece.data(), size, Z_NO_FLUSH);
        left -= size;
    }
    feed(nullptr, 0, Z_FINISH);
    deflateEnd(&z);
    return out;
}

} // namespace exactpixels::testing
