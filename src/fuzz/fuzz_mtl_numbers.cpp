// fuzz_mtl_numbers: the differential libFuzzer target for the numbers of chapter 7's MTL
// reader (preset `fuzz`). Every input is an MTL file's text, written into the fixtures
// folder as fuzz_material writes it, behind an OBJ file that names it with mtllib and
// draws one triangle with each material it defines (each `newmtl NAME` line). When the
// loader accepts the model, the MTL text is read a second way (reference_reading.hpp):
// each material's colour is the three numbers of its last Kd statement read by strtod,
// or, without a Kd, tinyobjloader's default for it. Every part the loader made must
// have that colour bit for bit, and name a material the reference read. Any difference
// aborts. (The other numeric statements are checked and not drawn: no value to compare.)
#include "material_file.hpp"
#include "reference_reading.hpp"

#include <tiny_obj_loader.h>

#include <bit>
#include <cstddef>
#include <cstdint>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace {

/// Each material's last Kd statement (its words), or none for a material without one.
/// The numbers are read only once the loader has accepted the file.
std::map<std::string, std::vector<std::string>> kd_statements(std::string_view text) {
    std::map<std::string, std::vector<std::string>> statements;
    std::string current;
    for (const auto& words : fuzz::lines_of_words(text)) {
        if (words.size() == 2 && words[0] == "newmtl") {
            current = words[1];
            statements[current];
        } else if (!words.empty() && words[0] == "Kd") {
            statements[current] = words;
        }
    }
    return statements;
}

bool same(double a, double b) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const auto statements = kd_statements(fuzz::skip_bom(text));
    std::string obj = fuzz::write_material_file(text, "fuzz_mtl_numbers");
    for (const auto& [material, kd] : statements) {
        if (material.find('\0') == std::string::npos) {
            obj += "usemtl " + material + "\nf 1/1 2/2 3/3\n";
        }
    }
    const std::optional<exactpixels::Model> read = fuzz::accepted(obj);
    if (!read) {
        return 0;
    }
    const exactpixels::Model& model = *read;
    // tinyobjloader's defaults for materials without a Kd (0, or 0.6 after a map_Kd).
    std::map<std::string, int> ids;
    std::vector<tinyobj::material_t> materials;
    std::string warning, error;
    std::istringstream in{std::string(fuzz::skip_bom(text))};
    tinyobj::LoadMtl(&ids, &materials, &in, &warning, &error);
    for (const exactpixels::ModelPart& part : model.parts) {
        const auto found = statements.find(part.material);
        if (found == statements.end() || ids.count(part.material) == 0) {
            fuzz::differ("the loader drew material '" + part.material +
                         "', which the reference did not read");
        }
        const tinyobj::material_t& m =
            materials[static_cast<std::size_t>(ids[part.material])];
        const std::vector<std::string>& kd = found->second;
        if (!kd.empty() && kd.size() != 4) {
            fuzz::differ("the loader accepted a Kd of " + std::to_string(kd.size() - 1) +
                         " words");
        }
        const glm::dvec3 want = kd.empty()
                                    ? glm::dvec3{m.diffuse[0], m.diffuse[1], m.diffuse[2]}
                                    : glm::dvec3{fuzz::number(kd[1]), fuzz::number(kd[2]),
                                                 fuzz::number(kd[3])};
        for (int k = 0; k < 3; ++k) {
            if (!same(part.colour[k], want[k])) {
                fuzz::differ("the colour of material '" + part.material + "'");
            }
        }
    }
    return 0;
}
