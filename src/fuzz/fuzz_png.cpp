// fuzz_png: the libFuzzer target for the PNG reader (png.hpp, libpng), seeded from
// tests/fixtures/png/. Every input is decoded; anything that is not a sound PNG must end
// in exactpixels::Error and nothing else. Images above 256 x 256 pixels are refused by
// the size check before decoding, so each run stays fast.
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        (void)exactpixels::decode_png(bytes, "fuzz.png", [](int width, int height) {
            if (static_cast<long long>(width) * height > 256 * 256) {
                throw exactpixels::Error("fuzz.png: larger than the fuzz target decodes");
            }
        });
    } catch (const exactpixels::Error&) {
        // bad input, reported as it should be
    }
    return 0;
}
