// fuzz_material: the libFuzzer target for the MTL half of chapter 7's OBJ reader (preset
// `fuzz`). Every input is an MTL file's text: it is written into the folder that holds
// tests/fixtures/models/ and chapter 7's shipped models (src/fuzz/CMakeLists.txt copies
// them there, so a mutated map_Kd can name any of their textures), and a one-triangle
// OBJ file that names it with mtllib, and uses its first material when it defines one,
// is parsed. Bad input must end in exactpixels::Error and nothing else (no crash, no
// leak, no undefined behaviour, no failed assertion, no other exception). fuzz_model
// mutates the OBJ text; this target mutates what it reads through mtllib.
#include "exactpixels/base/error.hpp"
#include "exactpixels/scene/obj_model.hpp"
#include "material_file.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace {

/// The name after the first `newmtl ` at the start of a line, up to the line's end (empty
/// when there is none).
std::string first_material(std::string_view text) {
    const std::string_view key = "newmtl ";
    for (std::size_t at = 0; at < text.size();) {
        const std::size_t end = std::min(text.find('\n', at), text.size());
        const std::string_view line = text.substr(at, end - at);
        if (line.substr(0, key.size()) == key) {
            return std::string(line.substr(key.size()));
        }
        at = end + 1;
    }
    return {};
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    std::string obj = fuzz::write_material_file(text, "fuzz_material");
    const std::string material = first_material(text);
    if (!material.empty() && material.find('\0') == std::string::npos) {
        obj += "usemtl " + material + "\n";
    }
    obj += "f 1/1 2/2 3/3\n";
    try {
        long long texture_bytes = 0;
        const exactpixels::Model model = exactpixels::parse_obj_model(
            obj, "fuzz.obj", EXACTPIXELS_MODEL_FIXTURES, texture_bytes);
        (void)model;
    } catch (const exactpixels::Error&) {
        // bad input, reported as it should be
    }
    return 0;
}
