#include "exactpixels/scene/obj_model.hpp"

#include "exactpixels/base/decimal_from_chars.hpp"
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/input_file.hpp"
#include "exactpixels/scene/mesh_transform.hpp"
#include "exactpixels/scene/scene_loader.hpp"

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cassert>
#include <charconv>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

namespace exactpixels {

namespace {

/// Where a message points: a file and a line in it (and the line's text, as read).
struct Place {
    std::string file;
    std::size_t line = 0;
    std::string_view text = {};

    [[noreturn]] void fail(const std::string& message) const {
        throw Error(fmt::format("{}:{}: {}", file, line, message));
    }
};

/// The words of one line (split at spaces and tabs).
std::vector<std::string_view> words_of(std::string_view line) {
    std::vector<std::string_view> words;
    std::size_t i = 0;
    while (i < line.size()) {
        const auto blank = [](char ch) { return ch == ' ' || ch == '\t'; };
        while (i < line.size() && blank(line[i])) {
            ++i;
        }
        const std::size_t start = i;
        while (i < line.size() && !blank(line[i])) {
            ++i;
        }
        if (i > start) {
            words.push_back(line.substr(start, i - start));
        }
    }
    return words;
}

/// `text` without a UTF-8 byte-order mark at its start (some editors write one; it is
/// not part of the first statement). Both readers are given the text without it.
std::string_view without_bom(std::string_view text) {
    const std::string_view bom = "\xEF\xBB\xBF";
    return text.substr(0, bom.size()) == bom ? text.substr(bom.size()) : text;
}

/// Calls `each(place, words)` for every line of `text` that is not blank or a comment.
/// Lines end as tinyobjloader ends them, at "\n", "\r\n" or a lone "\r", so that both
/// see the same statements; a control character (other than a tab) is an Error, since
/// tinyobjloader would take it as the end of the line.
template <class Each>
void for_each_statement(std::string_view text, const std::string& file, Each each) {
    std::size_t line = 0, start = 0;
    while (start < text.size()) {
        ++line;
        std::size_t end = start;
        while (end < text.size() && text[end] != '\n' && text[end] != '\r') {
            const auto ch = static_cast<unsigned char>(text[end]);
            if (ch < 0x20 && ch != '\t') {
                Place{file, line}.fail(fmt::format("control character 0x{:02x}", ch));
            }
            ++end;
        }
        const std::vector<std::string_view> words =
            words_of(text.substr(start, end - start));
        if (!words.empty() && words[0][0] != '#') {
            each(Place{file, line, text.substr(start, end - start)}, words);
        }
        start = end + (text.substr(end, 2) == "\r\n" ? 2 : 1);
    }
}

//> obj-number
/// A decimal number, the whole word and nothing else, finite, within +-limit: an
/// optional sign, digits with an optional point (or a point and digits), an optional
/// exponent. This is the only reading of a number: the model is built from the values
/// it returns, never from tinyobjloader's (see parse_obj_model).
double read_obj_number(const Place& at, std::string_view word, double limit) {
    std::string_view digits = word;
    if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-') {
        digits.remove_prefix(1); // from_chars takes '-' but not '+'
    }
    double value = 0.0;
    const auto [end, error] =
        decimal_from_chars(digits.data(), digits.data() + digits.size(), value);
    const bool whole = end == digits.data() + digits.size();
    if (error == std::errc::result_out_of_range && whole) {
        at.fail(fmt::format("{} is out of range (beyond a double, or so close to 0 that "
                            "it reads as 0)",
                            word));
    }
    if (digits.empty() || error != std::errc{} || !whole) {
        at.fail(fmt::format("'{}' is not a number", word));
    }
    if (!std::isfinite(value) || std::abs(value) > limit) {
        at.fail(
            fmt::format("{} is out of range (allowed: -{} to {})", word, limit, limit));
    }
    return value;
}
//< obj-number

/// The N numbers after a statement's keyword, each read by read_obj_number.
template <int N>
glm::vec<N, double>
read_vector(const Place& at, const std::vector<std::string_view>& words, double limit) {
    glm::vec<N, double> v;
    for (int k = 0; k < N; ++k) {
        v[k] = read_obj_number(at, words[static_cast<std::size_t>(k) + 1], limit);
    }
    return v;
}

/// Checks that a statement has from `lo` to `hi` words after its keyword.
void expect_fields(const Place& at, const std::vector<std::string_view>& words,
                   std::size_t lo, std::size_t hi) {
    const std::size_t n = words.size() - 1;
    if (n < lo || n > hi) {
        at.fail(fmt::format(
            "'{}' takes {} values, this one has {}", words[0],
            lo == hi ? fmt::format("{}", lo) : fmt::format("{} to {}", lo, hi), n));
    }
}

/// One MTL file's materials as the check saw them: name, line, colour, texture.
struct CheckedMaterial {
    Place place;                         ///< where `newmtl` named it
    std::optional<Colour> kd;            ///< its last Kd, as read_obj_number read it
    std::optional<SceneTexture> texture; ///< its map_Kd
};

/// Starts the material a `newmtl` statement names: checked for its one blank, for a
/// name used before and for the limit on materials.
CheckedMaterial& start_material(const Place& at,
                                const std::vector<std::string_view>& words,
                                std::map<std::string, CheckedMaterial>& materials) {
    expect_fields(at, words, 1, 1);
    const std::string name(words[1]);
    if (words[1].data() != words[0].data() + 7) { // tinyobjloader would keep them
        at.fail(
            fmt::format("material '{}': one blank between newmtl and the name", name));
    }
    if (materials.count(name) != 0) {
        at.fail(fmt::format("material '{}' is defined twice (first at {}:{})", name,
                            materials.at(name).place.file,
                            materials.at(name).place.line));
    }
    if (materials.size() >= static_cast<std::size_t>(max_model_materials)) {
        at.fail(fmt::format("material '{}' is more than the {} allowed", name,
                            max_model_materials));
    }
    CheckedMaterial& material = materials[name];
    material.place = at;
    return material;
}

/// The texture a `map_Kd` statement names, read from beside the MTL file, its size
/// checked before its texels are kept and added to the scene's `texture_bytes`.
SceneTexture read_map_kd(const Place& at, const std::vector<std::string_view>& words,
                         const std::filesystem::path& folder, long long& texture_bytes) {
    expect_fields(at, words, 1, 1);
    if (words[1][0] == '-') {
        at.fail(fmt::format("map_Kd option '{}' is not supported", words[1]));
    }
    const std::filesystem::path path = folder / std::string(words[1]);
    try {
        Texture texture = load_texture(path, [&](int width, int height) {
            if (width > max_texture_side || height > max_texture_side) {
                at.fail(
                    fmt::format("{}: {}x{} texels is larger than the {} allowed per side",
                                path.string(), width, height, max_texture_side));
            }
            texture_bytes += 4LL * width * height;
            if (texture_bytes > max_scene_texture_bytes) {
                at.fail(fmt::format("{}: the scene's textures take more than the "
                                    "{} bytes allowed",
                                    path.string(), max_scene_texture_bytes));
            }
        });
        return SceneTexture{"", std::move(texture), path};
    } catch (const Error& error) {
        const std::string message = error.what();
        if (message.rfind(at.file + ":", 0) == 0) {
            throw; // already names this line
        }
        at.fail(message);
    }
}

/// Checks every statement of an MTL file and reads each map_Kd texture.
void check_mtl(std::string_view text, const std::string& file,
               const std::filesystem::path& folder,
               std::map<std::string, CheckedMaterial>& materials,
               long long& texture_bytes) {
    CheckedMaterial* current = nullptr;
    for_each_statement(text, file, [&](const Place& at, const auto& words) {
        const std::string_view key = words[0];
        if (key == "newmtl") {
            current = &start_material(at, words, materials);
            return;
        }
        if (current == nullptr) {
            // A material library starts with newmtl (after comments); a file that does
            // not may be anything, so its text is not quoted.
            at.fail("a statement before any newmtl: not a material library");
        }
        if (key == "Kd") {
            expect_fields(at, words, 3, 3);
            const Colour kd = read_vector<3>(at, words, 1.0);
            for (int k = 0; k < 3; ++k) {
                if (kd[k] < 0.0) {
                    at.fail(fmt::format("Kd {} is out of range (allowed: 0 to 1)",
                                        words[k + 1]));
                }
            }
            current->kd = kd;
        } else if (key == "map_Kd") {
            current->texture = read_map_kd(at, words, folder, texture_bytes);
        } else if (key == "Ka" || key == "Ks" || key == "Ke" || key == "Tf") {
            expect_fields(at, words, 3, 3);
            for (std::size_t k = 1; k <= 3; ++k) {
                (void)read_obj_number(at, words[k], max_model_coordinate);
            }
        } else if (key == "Ns" || key == "Ni" || key == "d" || key == "Tr" ||
                   key == "illum") {
            expect_fields(at, words, 1, 1);
            (void)read_obj_number(at, words[1], max_model_coordinate);
        } else {
            at.fail(
                fmt::format("'{}' is not supported in a material file (supported: "
                            "newmtl, Kd, map_Kd, Ka, Ks, Ke, Tf, Ns, Ni, d, Tr, illum)",
                            key));
        }
    });
}

/// Whether `word` could be the name of an OBJ statement (`v`, `curv`, `usemap`...):
/// a letter, then at most 15 letters, digits or underscores.
bool is_statement_name(std::string_view word) {
    const auto letter = [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
    };
    if (word.empty() || word.size() > 16 || !letter(word[0])) {
        return false;
    }
    for (const char c : word) {
        if (!letter(c) && !(c >= '0' && c <= '9') && c != '_') {
            return false;
        }
    }
    return true;
}

/// What the check of an OBJ file found: the MTL texts for tinyobjloader, each
/// material's colour and texture, every v, vt and vn as read_obj_number read it, and the
/// line of every face in file order.
struct CheckedObj {
    std::map<std::string, std::string> mtl_texts;
    std::map<std::string, CheckedMaterial> materials;
    std::vector<std::filesystem::path> files;
    std::vector<glm::dvec3> positions; ///< as in the file (z not yet flipped)
    std::vector<glm::dvec2> texcoords; ///< u and v (a w is checked and dropped)
    std::vector<glm::dvec3> normals;   ///< as in the file, not normalized
    std::vector<std::size_t> face_lines;
};

/// One face corner's index, checked against the `count` elements read so far.
void check_index(const Place& at, std::string_view corner, std::string_view word,
                 long long count, const char* what) {
    long long index = 0;
    const auto [end, error] =
        std::from_chars(word.data(), word.data() + word.size(), index);
    if (word.empty() || error != std::errc{} || end != word.data() + word.size()) {
        at.fail(fmt::format("'{}' in face corner '{}' is not an index", word, corner));
    }
    if (index == 0) {
        at.fail(fmt::format("index 0 in face corner '{}' (indices start at 1)", corner));
    }
    if (index > count) {
        at.fail(
            fmt::format("index {} in face corner '{}' is beyond the {} {} read so far",
                        index, corner, count, what));
    }
    if (index < -count) {
        at.fail(fmt::format("index {} in face corner '{}' reaches back beyond the {} {} "
                            "read so far",
                            index, corner, count, what));
    }
}

/// How many of each element an OBJ file has declared so far, each within its limit.
struct ObjCounts {
    long long positions = 0, texcoords = 0, normals = 0, triangles = 0;
};

/// Checks an `f` statement: 3 to max_face_corners corners, the triangles of its fan
/// within the limit, and every corner's v/vt/vn indices against the counts so far.
void check_face(const Place& at, const std::vector<std::string_view>& words,
                ObjCounts& counts) {
    const std::size_t corners = words.size() - 1;
    if (corners < 3 || corners > static_cast<std::size_t>(max_face_corners)) {
        at.fail(fmt::format("a face of {} corners (allowed: 3 to {})", corners,
                            max_face_corners));
    }
    counts.triangles += static_cast<long long>(corners) - 2;
    if (counts.triangles > max_model_triangles) {
        at.fail(fmt::format("the faces make more than the {} triangles allowed",
                            max_model_triangles));
    }
    for (std::size_t k = 1; k <= corners; ++k) {
        const std::string_view corner = words[k];
        std::vector<std::string_view> parts;
        std::size_t start = 0;
        for (std::size_t slash;
             (slash = corner.find('/', start)) != std::string_view::npos;
             start = slash + 1) {
            parts.push_back(corner.substr(start, slash - start));
        }
        parts.push_back(corner.substr(start));
        if (parts.size() > 3) {
            at.fail(fmt::format("face corner '{}' has more than 3 parts", corner));
        }
        check_index(at, corner, parts[0], counts.positions, "positions");
        if (parts.size() >= 2 && !(parts.size() == 3 && parts[1].empty())) {
            check_index(at, corner, parts[1], counts.texcoords, "texture coordinates");
        }
        if (parts.size() == 3) {
            check_index(at, corner, parts[2], counts.normals, "normals");
        }
    }
}

/// Reads and checks the material file an `mtllib` statement names, once per name.
void read_mtllib(const Place& at, const std::vector<std::string_view>& words,
                 const std::filesystem::path& folder, CheckedObj& checked,
                 long long& texture_bytes) {
    expect_fields(at, words, 1, 1);
    // tinyobjloader reads the names after "mtllib" split at spaces only, with a
    // backslash escaping the next character: without tabs and backslashes on the
    // line it reads this one name, as the check does.
    if (at.text.find_first_of("\t\\") != std::string_view::npos) {
        at.fail("mtllib: the line holds a tab or a backslash; write the file "
                "name after a space, with neither");
    }
    const std::string name(words[1]);
    const std::filesystem::path path = folder / name;
    std::string mtl;
    try {
        mtl = read_input_file(path, "material", max_material_file_bytes,
                              InputKind::regular_file);
    } catch (const Error& error) {
        at.fail(error.what());
    }
    if (checked.mtl_texts.count(name) != 0) {
        at.fail(fmt::format("mtllib '{}' is named twice", name));
    }
    mtl = std::string(without_bom(mtl));
    check_mtl(mtl, path.string(), path.parent_path(), checked.materials, texture_bytes);
    checked.mtl_texts[name] = std::move(mtl);
    checked.files.push_back(path);
}

//> obj-check
/// Checks every statement of the OBJ text and reads its MTL files, before
/// tinyobjloader sees it: the limits, the numbers, the indices, the materials.
CheckedObj check_obj(std::string_view text, const std::string& file,
                     const std::filesystem::path& folder, long long& texture_bytes) {
    CheckedObj checked;
    ObjCounts counts;
    const auto count = [&](const Place& at, long long& n, const char* what) {
        if (++n > max_model_vertices) {
            at.fail(fmt::format("more than the {} {} allowed", max_model_vertices, what));
        }
    };
    for_each_statement(text, file, [&](const Place& at, const auto& words) {
        const std::string_view key = words[0];
        if (key == "v") {
            expect_fields(at, words, 3, 3);
            count(at, counts.positions, "positions");
            checked.positions.push_back(read_vector<3>(at, words, max_model_coordinate));
        } else if (key == "vt") {
            expect_fields(at, words, 2, 3);
            count(at, counts.texcoords, "texture coordinates");
            checked.texcoords.push_back(read_vector<2>(at, words, max_model_texcoord));
            if (words.size() == 4) {
                (void)read_obj_number(at, words[3], max_model_texcoord);
            }
        } else if (key == "vn") {
            expect_fields(at, words, 3, 3);
            count(at, counts.normals, "normals");
            const glm::dvec3 n = read_vector<3>(at, words, max_model_coordinate);
            if (n == glm::dvec3{0.0}) {
                at.fail("a normal of length 0 has no direction");
            }
            checked.normals.push_back(n);
        } else if (key == "f") {
            check_face(at, words, counts);
            checked.face_lines.push_back(at.line);
        } else if (key == "mtllib") {
            read_mtllib(at, words, folder, checked, texture_bytes);
        } else if (key == "usemtl") {
            expect_fields(at, words, 1, 1);
            if (checked.materials.count(std::string(words[1])) == 0) {
                at.fail(fmt::format("material '{}' is not defined by any mtllib above",
                                    words[1]));
            }
        } else if (key == "o" || key == "g") {
            // names: any words
        } else if (key == "s") {
            expect_fields(at, words, 1, 1);
        } else if (is_statement_name(key)) {
            at.fail(fmt::format("'{}' is not supported (supported: v, vt, vn, f, usemtl, "
                                "mtllib, o, g, s)",
                                key));
        } else {
            // Not even a statement's name: the file may be anything (a scene can name
            // any file), so its text is not quoted.
            at.fail("the line does not start with a statement name: not an OBJ model");
        }
    });
    return checked;
}
//< obj-check

/// Hands tinyobjloader the MTL texts the check has read.
class CheckedMaterials : public tinyobj::MaterialReader {
  public:
    CheckedMaterials(const std::map<std::string, std::string>& texts, std::string model)
        : texts_(texts), model_(std::move(model)) {}
    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* ids, std::string* warning,
                    std::string* error) override {
        const auto found = texts_.find(name);
        if (found == texts_.end()) { // the check read every mtllib it accepted
            throw Error(
                fmt::format("{}: mtllib '{}' was not read by the check", model_, name));
        }
        std::istringstream in(found->second);
        tinyobj::LoadMtl(ids, materials, &in, warning, error);
        return true;
    }

  private:
    const std::map<std::string, std::string>& texts_;
    std::string model_; ///< the OBJ file, for the message
};

/// The element `i` (0-based, as tinyobjloader gives it) of what the check read. The
/// check has bounded every index, so an `i` outside is tinyobjloader reading the
/// file otherwise than the check: an Error, never a read out of bounds.
template <class T> const T& element(const Place& at, const std::vector<T>& read, int i) {
    if (i < 0 || static_cast<std::size_t>(i) >= read.size()) {
        at.fail(fmt::format("tinyobjloader gave index {} of {} read by the check", i,
                            read.size()));
    }
    return read[static_cast<std::size_t>(i)];
}

/// OBJ's right-handed coordinates in the scene's left-handed world: z negated.
glm::dvec3 flip_z(const glm::dvec3& p) {
    return {p.x, p.y, -p.z};
}

//> fan
/// Checks that a face is a strictly convex polygon (every corner turns the same way as
/// the face's Newell normal, and the turns add up to one full turn), so that the fan
/// from its first corner covers it exactly once.
void check_convex(const Place& at, const std::vector<glm::dvec3>& p) {
    const std::size_t n = p.size();
    glm::dvec3 normal{0.0};
    for (std::size_t k = 0; k < n; ++k) {
        normal += glm::cross(p[k], p[(k + 1) % n]);
    }
    double turning = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        const glm::dvec3 in = p[k] - p[(k + n - 1) % n];
        const glm::dvec3 out = p[(k + 1) % n] - p[k];
        const double scale = glm::length(in) * glm::length(out) * glm::length(normal);
        if (!(glm::dot(glm::cross(in, out), normal) > 1e-9 * scale)) {
            at.fail(n == 3 ? std::string("the face is degenerate (its corners are "
                                         "collinear or coincide)")
                           : fmt::format("the face is not strictly convex (corner {} of "
                                         "{} turns the other way or not at all)",
                                         k + 1, n));
        }
        turning += std::acos(std::clamp(
            glm::dot(in, out) / (glm::length(in) * glm::length(out)), -1.0, 1.0));
    }
    if (std::abs(turning - 2.0 * std::numbers::pi) > 1e-6) {
        at.fail(fmt::format("the face is not a simple polygon (its edges turn {:.4g} "
                            "times round)",
                            turning / (2.0 * std::numbers::pi)));
    }
}
//< fan

/// The part of `model` that faces of material `id` go into, made on its first face
/// with the colour and texture the check read for that material.
ModelPart& part_for(int id, Model& model, std::map<int, std::size_t>& part_of,
                    const std::vector<tinyobj::material_t>& materials,
                    const CheckedObj& checked, const std::string& name) {
    if (part_of.count(id) == 0) {
        part_of[id] = model.parts.size();
        ModelPart part;
        if (id >= 0) {
            const tinyobj::material_t& m = materials[static_cast<std::size_t>(id)];
            part.material = m.name;
            const CheckedMaterial& checked_material = checked.materials.at(m.name);
            // Without a Kd, tinyobjloader's default (0, or 0.6 for a material with a
            // map_Kd before any Kd): a constant, not a number it read.
            part.colour = checked_material.kd.value_or(
                Colour{m.diffuse[0], m.diffuse[1], m.diffuse[2]});
            part.texture = checked_material.texture;
            if (part.texture) {
                part.texture->name = name + ":" + m.name;
            }
        }
        model.parts.push_back(std::move(part));
    }
    return model.parts[part_of[id]];
}

/// Adds the face whose `n` corners tinyobjloader gives at `indices` to `part`: each
/// corner's numbers as the check read them, z flipped, the face checked convex and
/// cut into its fan. Clears `model.normals` at the first corner without a normal.
void add_face(const Place& at, const tinyobj::index_t* indices, std::size_t n,
              const CheckedObj& checked, ModelPart& part, Model& model) {
    const glm::dvec2 texels = part.texture ? glm::dvec2{part.texture->texture.width(),
                                                        part.texture->texture.height()}
                                           : glm::dvec2{0.0};
    std::vector<SceneVertex> corners(n);
    std::vector<glm::dvec3> positions(n);
    for (std::size_t k = 0; k < n; ++k) {
        // tinyobjloader gives the structure (which v, vt and vn each corner names);
        // the numbers are the check's own.
        const tinyobj::index_t index = indices[k];
        SceneVertex& v = corners[k];
        v.position = positions[k] =
            flip_z(element(at, checked.positions, index.vertex_index));
        if (index.texcoord_index >= 0) {
            const glm::dvec2 uv = element(at, checked.texcoords, index.texcoord_index);
            v.uv = {uv.x * texels.x, (1.0 - uv.y) * texels.y};
        }
        if (index.normal_index >= 0) {
            v.normal =
                unit_normal(flip_z(element(at, checked.normals, index.normal_index)));
        } else if (model.normals) {
            model.normals = false;
            model.line_without_normal = at.line;
        }
    }
    check_convex(at, positions);
    for (std::size_t k = 1; k + 1 < n; ++k) { // the fan from corner 0
        part.triangles.push_back({corners[0], corners[k], corners[k + 1]});
        part.lines.push_back(at.line);
    }
}

} // namespace

Model parse_obj_model(std::string_view text, const std::filesystem::path& file,
                      const std::filesystem::path& folder, long long& texture_bytes) {
    const std::string name = file.string();
    text = without_bom(text);
    CheckedObj checked = check_obj(text, name, folder, texture_bytes);
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warning, error;
    CheckedMaterials reader(checked.mtl_texts, name);
    std::istringstream in{std::string(text)};
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &in, &reader,
                          /*triangulate=*/false)) {
        throw Error(fmt::format("{}: tinyobjloader: {}", name, error));
    }
    Model model;
    model.files.push_back(file);
    model.files.insert(model.files.end(), checked.files.begin(), checked.files.end());
    model.normals = true;
    std::map<int, std::size_t> part_of; // material id -> index into model.parts
    std::size_t face = 0;               // faces in file order
    for (const tinyobj::shape_t& shape : shapes) {
        std::size_t offset = 0;
        for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
            assert(face < checked.face_lines.size());
            const Place at{name, checked.face_lines[face++]};
            ModelPart& part = part_for(shape.mesh.material_ids[f], model, part_of,
                                       materials, checked, name);
            const std::size_t n = shape.mesh.num_face_vertices[f];
            add_face(at, &shape.mesh.indices[offset], n, checked, part, model);
            offset += n;
        }
    }
    assert(face == checked.face_lines.size()); // tinyobjloader kept every face
    if (model.parts.empty()) {
        Place{name, 1}.fail("the model has no faces (no 'f' statement): nothing to draw");
    }
    return model;
}

Model read_obj_model(const std::filesystem::path& path, long long& texture_bytes) {
    const std::string text =
        read_input_file(path, "model", max_model_file_bytes, InputKind::regular_file);
    return parse_obj_model(text, path, path.parent_path(), texture_bytes);
}

} // namespace exactpixels
