// fuzz_obj_numbers: the differential libFuzzer target for the numbers of chapter 7's OBJ
// reader (preset `fuzz`). Every input is parsed as an OBJ file, as fuzz_model does; when
// the loader accepts it, the input is read a second way: tinyobjloader for its structure
// (which v, vt and vn each face corner names, and each face's material) and strtod for
// every number of every v, vt and vn statement (reference_reading.hpp). Every corner of
// every triangle the loader made must hold those numbers bit for bit: its position (z
// negated), its texture coordinates (in texels of its material's texture) and its
// normal (made of length 1 as the loader does it). Any difference aborts.
#include "reference_reading.hpp"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string_view>

namespace {

using exactpixels::SceneVertex;

/// The MTL files of the fixtures folder, without a byte-order mark, for tinyobjloader.
class FolderMaterials : public tinyobj::MaterialReader {
  public:
    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* ids, std::string* warning,
                    std::string* error) override {
        std::ifstream file(std::filesystem::path(EXACTPIXELS_MODEL_FIXTURES) / name,
                           std::ios::binary);
        std::stringstream text;
        text << file.rdbuf();
        std::istringstream in{std::string(fuzz::skip_bom(text.str()))};
        tinyobj::LoadMtl(ids, materials, &in, warning, error);
        return true;
    }
};

bool same(double a, double b) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

bool same(const glm::dvec3& a, const glm::dvec3& b) {
    return same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z);
}

/// The numbers of every v, vt and vn statement, in file order, read by strtod.
struct ReferenceNumbers {
    std::vector<glm::dvec3> positions, normals;
    std::vector<glm::dvec2> texcoords;
};

ReferenceNumbers read_numbers(std::string_view text) {
    ReferenceNumbers numbers;
    for (const auto& words : fuzz::lines_of_words(text)) {
        if (words.empty()) {
            continue;
        }
        const auto vector3 = [&] {
            return glm::dvec3{fuzz::number(words.at(1)), fuzz::number(words.at(2)),
                              fuzz::number(words.at(3))};
        };
        if (words[0] == "v") {
            numbers.positions.push_back(vector3());
        } else if (words[0] == "vn") {
            numbers.normals.push_back(vector3());
        } else if (words[0] == "vt") {
            numbers.texcoords.push_back(
                {fuzz::number(words.at(1)), fuzz::number(words.at(2))});
        }
    }
    return numbers;
}

/// The corner tinyobjloader's index names, from the reference numbers, as the loader
/// makes it: z negated, uv in `texels`, the normal of length 1.
SceneVertex expected_corner(const ReferenceNumbers& numbers,
                            const tinyobj::index_t& index, const glm::dvec2& texels) {
    const auto at = [](const auto& read, int i) {
        if (i < 0 || static_cast<std::size_t>(i) >= read.size()) {
            fuzz::differ("tinyobjloader names an element the reference did not read");
        }
        return read[static_cast<std::size_t>(i)];
    };
    SceneVertex v;
    const glm::dvec3 p = at(numbers.positions, index.vertex_index);
    v.position = {p.x, p.y, -p.z};
    if (index.texcoord_index >= 0) {
        const glm::dvec2 uv = at(numbers.texcoords, index.texcoord_index);
        v.uv = {uv.x * texels.x, (1.0 - uv.y) * texels.y};
    }
    if (index.normal_index >= 0) {
        const glm::dvec3 n = at(numbers.normals, index.normal_index);
        const glm::dvec3 m = glm::dvec3{n.x, n.y, -n.z} /
                             std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)});
        v.normal = glm::normalize(m);
    }
    return v;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const std::optional<exactpixels::Model> read = fuzz::accepted(text);
    if (!read) {
        return 0;
    }
    const exactpixels::Model& model = *read;
    const std::string_view body = fuzz::skip_bom(text);
    const ReferenceNumbers numbers = read_numbers(body);
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warning, error;
    FolderMaterials reader;
    std::istringstream in{std::string(body)};
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &in, &reader,
                          /*triangulate=*/false)) {
        fuzz::differ("tinyobjloader refused a model the loader accepted: " + error);
    }
    // Each part's triangles in the loader's order: materials in order of first use,
    // faces in file order, each a fan from its first corner.
    std::map<int, std::size_t> part_of;
    std::vector<std::size_t> made(model.parts.size(), 0);
    for (const tinyobj::shape_t& shape : shapes) {
        std::size_t offset = 0;
        for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
            const int id = shape.mesh.material_ids[f];
            if (part_of.count(id) == 0) {
                const std::size_t next = part_of.size();
                part_of[id] = next;
            }
            const std::size_t p = part_of[id];
            if (p >= model.parts.size()) {
                fuzz::differ("more materials used than the loader's parts");
            }
            const exactpixels::ModelPart& part = model.parts[p];
            const glm::dvec2 texels = part.texture
                                          ? glm::dvec2{part.texture->texture.width(),
                                                       part.texture->texture.height()}
                                          : glm::dvec2{0.0};
            const std::size_t n = shape.mesh.num_face_vertices[f];
            for (std::size_t k = 1; k + 1 < n; ++k) {
                if (made[p] >= part.triangles.size()) {
                    fuzz::differ("more triangles than the loader made");
                }
                const auto& drawn = part.triangles[made[p]++];
                const std::size_t corner[3] = {0, k, k + 1};
                for (int c = 0; c < 3; ++c) {
                    const SceneVertex want = expected_corner(
                        numbers, shape.mesh.indices[offset + corner[c]], texels);
                    const SceneVertex& got = drawn[static_cast<std::size_t>(c)];
                    if (!same(got.position, want.position) ||
                        !same(got.uv.x, want.uv.x) || !same(got.uv.y, want.uv.y) ||
                        !same(got.normal, want.normal)) {
                        fuzz::differ("a corner of the face at line " +
                                     std::to_string(part.lines[made[p] - 1]));
                    }
                }
            }
            offset += n;
        }
    }
    for (std::size_t p = 0; p < model.parts.size(); ++p) {
        if (made[p] != model.parts[p].triangles.size()) {
            fuzz::differ("fewer triangles than the loader made");
        }
    }
    return 0;
}
