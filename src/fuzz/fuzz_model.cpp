// fuzz_model: the libFuzzer target for chapter 7's OBJ reader (preset `fuzz`). Every
// input is parsed as an OBJ file whose mtllib and map_Kd names are looked up in a folder
// holding tests/fixtures/models/ and chapter 7's shipped models (src/fuzz/CMakeLists.txt
// copies them there, so every seed's materials and textures can be reached); bad
// input must end in exactpixels::Error and nothing else (no crash, no leak, no
// undefined behaviour, no failed assertion, no other exception).
#include "exactpixels/base/error.hpp"
#include "exactpixels/scene/obj_model.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        long long texture_bytes = 0;
        const exactpixels::Model model = exactpixels::parse_obj_model(
            text, "fuzz.obj", EXACTPIXELS_MODEL_FIXTURES, texture_bytes);
        (void)model;
    } catch (const exactpixels::Error&) {
        // bad input, reported as it should be
    }
    return 0;
}
