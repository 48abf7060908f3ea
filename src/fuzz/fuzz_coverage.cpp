// fuzz_coverage: the libFuzzer target for the input of `exactpixels coverage` (chapter 2,
// coverage_reader.hpp), seeded from tests/fixtures/coverage/. Every input is read and
// drawn by each rasterizer in both precisions; bad input must end in exactpixels::Error
// and nothing else. Frames are capped at 64 x 64 pixels so each run stays fast.
#include "exactpixels/base/error.hpp"
#include "exactpixels/raster/coverage_reader.hpp"

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    using exactpixels::CoveragePrecision;
    using exactpixels::RasterizerKind;
    for (const RasterizerKind kind :
         {RasterizerKind::scanline, RasterizerKind::edge, RasterizerKind::edge8x8}) {
        for (const CoveragePrecision precision :
             {CoveragePrecision::fixed, CoveragePrecision::floating}) {
            std::istringstream in(text);
            exactpixels::Viewport viewport{0, 0};
            try {
                (void)exactpixels::count_coverage(in, kind, precision, viewport, 64 * 64);
            } catch (const exactpixels::Error&) {
                // bad input, reported as it should be
            }
        }
    }
    return 0;
}
