// png_chunks.hpp: editing the chunks of a PNG file's bytes, for tests that corrupt one
// thing (a CRC, the zlib checksum, the size in the header) and nothing else.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

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

} // namespace exactpixels::testing
