// Chapter 0 tests: reading PNG files strictly. A PNG whose chunk CRC or zlib checksum is
// wrong, that is not a PNG at all, or that is truncated is an Error, never an image with
// wrong pixels; the size in the header is checked before any pixel memory is allocated.
// Each corrupt file is made here from the fixture tests/fixtures/png/f.png by changing
// one thing (support/png_chunks.hpp), so the fixture loading proves the rest is sound.
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/base/test_pattern.hpp"
#include "support/png_chunks.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

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
