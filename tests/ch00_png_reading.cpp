// Chapter 0 tests: reading PNG files strictly. A PNG whose chunk CRC or zlib checksum is
// wrong, that is not a PNG at all, or that is truncated is an Error, never an image with
// wrong pixels; the size in the header is checked before any pixel memory is allocated.
// Each corrupt file is made here from the fixture tests/fixtures/png/f.png by changing
// one thing (support/png_chunks.hpp), so the fixture loading proves the rest is sound.
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/base/test_pattern.hpp"
#include "support/printing.hpp"
#include "support/png_chunks.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <utility>
#include <vector>

using namespace exactpixels;
using namespace exactpixels::testing;
namespace fs = std::filesystem;

namespace {

const fs::path fixture = fs::path(EXACTPIXELS_SOURCE_DIR) / "tests/fixtures/png/f.png";

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/// Writes `bytes` to a scratch file and reads it back as a PNG.
Framebuffer read_bytes(const std::string& bytes) {
    const fs::path path = fs::temp_directory_path() /
                          ("exactpixels-png-" + std::to_string(::getpid()) + ".png");
    std::ofstream(path, std::ios::binary) << bytes;
    struct Remove {
        fs::path path;
        ~Remove() { fs::remove(path); }
    } remove{path};
    return read_png(path);
}

} // namespace

TEST_CASE("the PNG fixture reads back as the F it was written from") {
    CHECK(read_png(fixture) == draw_f_pattern(2));
    CHECK(read_bytes(slurp(fixture)) == draw_f_pattern(2));
}

TEST_CASE("a PNG with a bad chunk CRC is rejected") {
    for (const char* type : {"IHDR", "IDAT"}) {
        CAPTURE(type);
        std::string bytes = slurp(fixture);
        const PngChunk chunk = find_chunk(bytes, type);
        bytes[chunk.data + chunk.length] ^= 0x01; // one bit of the stored CRC
        CHECK_THROWS_WITH_AS(read_bytes(bytes), doctest::Contains("CRC"), Error);
    }
}

TEST_CASE("a PNG with a bad zlib checksum is rejected") {
    std::string bytes = slurp(fixture);
    const PngChunk idat = find_chunk(bytes, "IDAT");
    bytes[idat.data + idat.length - 1] ^= 0x01; // the Adler-32 ends the zlib stream
    fix_crc(bytes, idat);                       // so only the zlib checksum is wrong
    CHECK_THROWS_WITH_AS(read_bytes(bytes), doctest::Contains("incorrect data check"),
                         Error);

    // A changed pixel byte with both checksums recomputed is no longer corruption, so
    // the Adler-32 is what the line above caught.
    std::string fixed = slurp(fixture);
    CHECK_NOTHROW(fix_crc(fixed, idat));
    CHECK(read_bytes(fixed) == draw_f_pattern(2));
}

TEST_CASE("data that is not a PNG is rejected by its signature, whatever its name") {
    const std::string gif =
        std::string("GIF89a\x01\x00\x01\x00\x80\x00\x00", 13) + std::string(32, '\0');
    CHECK_THROWS_WITH_AS(read_bytes(gif), doctest::Contains("PNG signature"), Error);
    CHECK_THROWS_WITH_AS(read_bytes(""), doctest::Contains("PNG signature"), Error);
    const std::string truncated = slurp(fixture).substr(0, 60);
    CHECK_THROWS_AS(read_bytes(truncated), Error);
}

TEST_CASE("a PNG's size is checked from its header before its pixels are decoded") {
    // The header claims 16384 x 16383 pixels (1 GiB of RGBA8) for a 99-byte file.
    std::string bytes = slurp(fixture);
    const PngChunk ihdr = find_chunk(bytes, "IHDR");
    write_u32(bytes, ihdr.data, 16384);
    write_u32(bytes, ihdr.data + 4, 16383);
    fix_crc(bytes, ihdr);
    CHECK_THROWS_WITH_AS(read_bytes(bytes),
                         doctest::Contains(std::to_string(max_png_pixels).c_str()),
                         Error);

    // The caller's check sees the header's size and may refuse it.
    int seen_width = 0, seen_height = 0;
    CHECK_THROWS_WITH_AS(read_png(fixture,
                                  [&](int width, int height) {
                                      seen_width = width;
                                      seen_height = height;
                                      throw Error("too big for this caller");
                                  }),
                         "too big for this caller", Error);
    CHECK(seen_width == 10);
    CHECK(seen_height == 14);
}

TEST_CASE("a PNG with an unknown chunk before its IHDR is read by its own IHDR") {
    // libpng skips an unknown ancillary chunk (lower-case first letter) before IHDR, so
    // such a file is a sound image. The fuzzer found one whose first chunk was "mIHD":
    // the decompression-bomb guard read the header at byte 16 and took the stray
    // chunk's tenth byte, 0x89, for the colour type (std::out_of_range, not Error).
    std::string stray(13, '\0');
    stray[9] = '\x89';
    const std::string fixture_bytes = slurp(fixture);
    const std::string bytes =
        fixture_bytes.substr(0, 8) + png_chunk("mIHD", stray) + fixture_bytes.substr(8);
    CHECK(read_bytes(bytes) == draw_f_pattern(2));

    // The guard still counts this image's rows: the bomb below is refused, with or
    // without the stray chunk in front.
    std::string rows;
    for (int y = 0; y < 8; ++y) {
        rows += '\0' + std::string(32, '\x40');
    }
    const std::string bomb =
        png_file(8, 8, 8, 6, "", zlib_stream(rows, std::size_t{64} << 20));
    CHECK_THROWS_WITH_AS(read_bytes(bomb.substr(0, 8) + png_chunk("mIHD", stray) +
                                    bomb.substr(8)),
                         doctest::Contains("inflates to more than"), Error);
}

TEST_CASE("a PNG path that is a FIFO or a directory is refused without blocking") {
    const fs::path fifo = fs::temp_directory_path() /
                          ("exactpixels-png-fifo-" + std::to_string(::getpid()));
    fs::remove(fifo);
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    CHECK_THROWS_WITH_AS(read_png(fifo), doctest::Contains("not a regular file"), Error);
    fs::remove(fifo);
    CHECK_THROWS_WITH_AS(read_png(fs::temp_directory_path()),
                         doctest::Contains("directory"), Error);
}

namespace {

/// A 256 x 256 16-bit grey PNG holding every sample value once, 0 to 65535 row by row
/// (pixel (x, y) holds 256 y + x), with the chunks `before_idat`.
std::string every_16bit_sample(const std::string& before_idat) {
    std::string rows;
    for (int y = 0; y < 256; ++y) {
        rows += '\0'; // filter type 0: the samples as they are
        for (int x = 0; x < 256; ++x) {
            rows += static_cast<char>(y); // big-endian: the high byte first
            rows += static_cast<char>(x);
        }
    }
    return png_file(256, 256, 16, 0, before_idat, zlib_stream(rows));
}

/// The 8-bit code nearest to the 16-bit sample v, code c standing for 257 c: round(v /
/// 257), never a tie since v / 257 is never a half.
int nearest_code(int v) {
    return (v + 128) / 257;
}

/// The sample values whose pixel in `image` (from every_16bit_sample) is not the grey
/// code `expected(v)`, opaque.
std::vector<int> wrong_samples(const Framebuffer& image, int (*expected)(int)) {
    std::vector<int> wrong;
    for (int v = 0; v < 65536; ++v) {
        const auto c = static_cast<std::uint8_t>(expected(v));
        if (image.at(v % 256, v / 256) != rgba(c, c, c, 255)) {
            wrong.push_back(v);
        }
    }
    return wrong;
}

const std::string srgb_chunk = png_chunk("sRGB", std::string(1, '\0'));

/// A gAMA chunk: the file's gamma times 100000 (45455: sRGB's 1/2.2; 100000: linear).
std::string gama_chunk(std::uint32_t gamma) {
    std::string data(4, '\0');
    write_u32(data, 0, gamma);
    return png_chunk("gAMA", data);
}

} // namespace

TEST_CASE("a 16-bit PNG's samples are sRGB codes, each read as the nearest 8-bit code") {
    // Without a gAMA or sRGB chunk a 16-bit file is sRGB like an 8-bit one, and says the
    // same as with an sRGB chunk or a gAMA of 1/2.2.
    for (const std::string& chunks :
         {std::string(), srgb_chunk, gama_chunk(45455), srgb_chunk + gama_chunk(45455)}) {
        CAPTURE(chunks.size());
        const Framebuffer image = read_bytes(every_16bit_sample(chunks));
        CHECK(image.at(0x80, 0x80) == rgba(0x80, 0x80, 0x80, 255)); // sample 0x8080
        CHECK(wrong_samples(image, nearest_code).empty());
    }
}

TEST_CASE("a PNG whose gAMA says linear is converted to sRGB codes at 8 and 16 bits") {
    // The file says that its values are light, not codes, so libpng encodes them as
    // codes with its approximation of sRGB, a power of 1/2.2: the light 0x80 / 255 is
    // code 0xBA (186.4), at 8 bits as at 16, where an sRGB file keeps 0x80.
    const Framebuffer wide = read_bytes(every_16bit_sample(gama_chunk(100000)));
    CHECK(wide.at(0x80, 0x80) == rgba(0xBA, 0xBA, 0xBA, 255)); // sample 0x8080
    const std::string row = std::string(1, '\0') + static_cast<char>(0x80);
    const Framebuffer narrow =
        read_bytes(png_file(1, 1, 8, 0, gama_chunk(100000), zlib_stream(row)));
    CHECK(narrow.at(0, 0) == rgba(0xBA, 0xBA, 0xBA, 255));
    CHECK(read_bytes(png_file(1, 1, 8, 0, srgb_chunk, zlib_stream(row))).at(0, 0) ==
          rgba(0x80, 0x80, 0x80, 255));
}

TEST_CASE("a PNG whose data inflates far beyond its image is refused before inflating") {
    // An 8 x 8 RGBA image (8 rows of a filter byte and 32 bytes) followed in the same
    // zlib stream by 256 MiB of zeros, in a file of about 256 KiB: zlib packs up to 258
    // zeros into about a bit, so a file of the 80 MiB allowed could inflate to 80 GiB.
    // Made here, not a fixture: tests/fixtures/png/ seeds the fuzzer and is kept small.
    std::string rows;
    for (int y = 0; y < 8; ++y) {
        rows += '\0' + std::string(32, static_cast<char>(0x40 + y));
    }
    const std::size_t zeros = std::size_t{256} << 20;
    const std::string bomb = png_file(8, 8, 8, 6, "", zlib_stream(rows, zeros));
    CAPTURE(bomb.size());
    CHECK(bomb.size() < (std::size_t{1} << 20));

    const auto start = std::chrono::steady_clock::now();
    CHECK_THROWS_WITH_AS(read_bytes(bomb), doctest::Contains("inflates to more than"),
                         Error);
    const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
    CHECK(took.count() < 0.1); // inflating the zeros took half a second

    // Cut short inside its IDAT chunk, the file is still refused for what it holds
    // (libpng inflates all of it before it finds the end).
    const std::string cut = bomb.substr(0, bomb.size() - 1000);
    CHECK_THROWS_WITH_AS(read_bytes(cut), doctest::Contains("inflates to more than"),
                         Error);

    // The same image without the zeros reads, so the zeros are what was refused.
    const Framebuffer image = read_bytes(png_file(8, 8, 8, 6, "", zlib_stream(rows)));
    CHECK(image.at(5, 7) == rgba(0x47, 0x47, 0x47, 0x47));
}

TEST_CASE(
    "a PNG's data may inflate to its rows and the stated extra bytes, and no more") {
    // An 8 x 8 RGBA image is 8 rows of a filter byte and 32 bytes, 264 bytes; interlaced,
    // its seven passes have rows of 1, 1, 2, 2, 4, 4 and 8 pixels, in 1, 1, 1, 2, 2, 4
    // and 4 rows: 5 + 5 + 9 + 18 + 34 + 68 + 132 = 271 bytes. All zeros is a black,
    // transparent image.
    for (const std::pair<bool, int>& image :
         {std::pair{false, 264}, std::pair{true, 271}}) {
        const bool interlaced = image.first;
        const int row_bytes = image.second;
        CAPTURE(interlaced);
        const auto png = [&](long long extra) {
            return png_file(
                8, 8, 8, 6, "",
                zlib_stream(std::string(static_cast<std::size_t>(row_bytes), '\0'),
                            static_cast<std::size_t>(extra)),
                interlaced);
        };
        CHECK(read_bytes(png(0)).at(7, 7) == rgba(0, 0, 0, 0));
        CHECK(read_bytes(png(max_png_extra_inflated_bytes)).at(7, 7) == rgba(0, 0, 0, 0));
        CHECK_THROWS_WITH_AS(
            read_bytes(png(max_png_extra_inflated_bytes + 1)),
            doctest::Contains(
                fmt::format("more than the {} bytes of its 8x8 pixels", row_bytes)
                    .c_str()),
            Error);
    }
}
