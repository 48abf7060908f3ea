#include "exactpixels/scene/scene_loader.hpp"

#include "exactpixels/base/decimal_from_chars.hpp"
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/input_file.hpp"
#include "exactpixels/base/test_pattern.hpp"
#include "exactpixels/scene/mesh_transform.hpp"
#include "exactpixels/scene/obj_model.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sys/stat.h>

#ifndef EXACTPIXELS_SCENES_DIR
#define EXACTPIXELS_SCENES_DIR "chapters/07-scenes/scenes"
#endif

namespace exactpixels {

static_assert(max_scene_model_bytes == static_cast<long long>(max_model_file_bytes),
              "a scene's models together may be as large as one model file");

namespace {

const char* type_name(const toml::node& node) {
    switch (node.type()) {
    case toml::node_type::table:
        return "a table";
    case toml::node_type::array:
        return "an array";
    case toml::node_type::string:
        return "a string";
    case toml::node_type::integer:
        return "an integer";
    case toml::node_type::floating_point:
        return "a float";
    case toml::node_type::boolean:
        return "a boolean";
    case toml::node_type::date:
    case toml::node_type::time:
    case toml::node_type::date_time:
        return "a date or time";
    default:
        return "nothing";
    }
}

/// A place in a scene's text as toml++ counts it: line, and column in code points (both
/// from 1, the first line starting after a UTF-8 byte-order mark).
using TextPlace = std::pair<toml::source_index, toml::source_index>;

/// Where a message points: the file, and the line and column in it; and the numbers of
/// the scene that the loader read itself (parse_toml), by where they are.
struct Context {
    std::string file;
    std::filesystem::path folder;
    std::string_view text;
    std::map<TextPlace, double> own_numbers;

    [[noreturn]] void fail(const toml::source_region& where, const std::string& path,
                           const std::string& message) const {
        throw Error(fmt::format("{}:{}:{}: {}: {}", file, where.begin.line,
                                where.begin.column, path, message));
    }
};

bool is_bare_char(char ch) { // of a bare key, a number, a date, true or false, inf, nan
    return (ch >= '0' && ch <= '9') || (ch >= 'a' && ch <= 'z') ||
           (ch >= 'A' && ch <= 'Z') || ch == '_' || ch == '-' || ch == '+' || ch == '.' ||
           ch == ':';
}

/// The run of characters of a bare key, number or date that starts at text[i].
std::string_view bare_run(std::string_view text, std::size_t i) {
    std::size_t end = i;
    while (end < text.size() && is_bare_char(text[end])) {
        ++end;
    }
    return text.substr(i, end - i);
}

/// Whether `token` is a TOML decimal float with a finite value (an optional sign; an
/// integer part with no leading zero; a fraction, an exponent or both; '_' only between
/// digits).
bool is_decimal_float(std::string_view token) {
    std::size_t i = !token.empty() && (token[0] == '+' || token[0] == '-') ? 1 : 0;
    const auto digits = [&] { // one or more digits, '_' between two of them
        const std::size_t first = i;
        while (i < token.size() &&
               ((token[i] >= '0' && token[i] <= '9') ||
                (token[i] == '_' && i > first && i + 1 < token.size() &&
                 token[i + 1] >= '0' && token[i + 1] <= '9'))) {
            ++i;
        }
        return i > first;
    };
    const std::size_t integer = i;
    if (!digits() || (token[integer] == '0' && i > integer + 1)) {
        return false;
    }
    const std::size_t whole = i;
    if (i < token.size() && token[i] == '.' && !(++i, digits())) {
        return false;
    }
    if (i < token.size() && (token[i] == 'e' || token[i] == 'E')) {
        ++i;
        i += i < token.size() && (token[i] == '+' || token[i] == '-') ? 1 : 0;
        if (!digits()) {
            return false;
        }
    }
    return i == token.size() && i > whole;
}

/// The value of a TOML decimal float (is_decimal_float), rounded to the nearest double by
/// the project's own reader (decimal_from_chars), the same on every standard library. A
/// number beyond the doubles is std::nullopt; a nonzero number nearer 0 than the smallest
/// double reads as 0 with its sign, as toml++ reads it through GCC's library.
std::optional<double> read_decimal_float(std::string_view token) {
    const bool negative = token[0] == '-';
    std::string number; // without the sign and the underscores
    for (const char ch : token.substr(token[0] == '-' || token[0] == '+' ? 1 : 0)) {
        if (ch != '_') {
            number += ch;
        }
    }
    double value = 0.0;
    const auto [end, status] =
        decimal_from_chars(number.data(), number.data() + number.size(), value);
    assert(end == number.data() + number.size());
    if (status == std::errc::result_out_of_range) {
        // Beyond the largest double (1.8e308), or nearer 0 than the smallest (4.9e-324):
        // which one the place of the first nonzero digit says.
        const std::size_t e = std::min(number.find_first_of("eE"), number.size());
        const std::size_t point = std::min(number.find('.'), e);
        const std::size_t first = number.find_first_of("123456789");
        const long long place = static_cast<long long>(point) -
                                static_cast<long long>(first) - (first < point ? 1 : 0);
        long long exponent = 0; // saturated: only its sign beside `place` matters
        for (std::size_t k = e + 1; k < number.size(); ++k) {
            if (number[k] >= '0' && number[k] <= '9') {
                exponent = std::min(exponent * 10 + (number[k] - '0'), 1'000'000'000LL);
            }
        }
        exponent = e + 1 < number.size() && number[e + 1] == '-' ? -exponent : exponent;
        if (place + exponent >= 0) {
            return std::nullopt;
        }
        value = 0.0;
    }
    return negative ? -value : value;
}

//> table-reader
/// One TOML table being read: every key read is recorded, and finish() rejects the
/// keys nobody asked for, naming the allowed ones.
class TableReader {
  public:
    TableReader(const Context& context, const toml::table& table, std::string path,
                std::vector<std::string> allowed)
        : context_(context), table_(table), path_(std::move(path)),
          allowed_(std::move(allowed)) {}

    /// The value at `key`, or nullptr when absent.
    const toml::node* find(const std::string& key) const {
        assert(std::find(allowed_.begin(), allowed_.end(), key) != allowed_.end());
        return table_.get(key);
    }
    /// The value at `key`; an Error naming the table when it is absent.
    const toml::node& require(const std::string& key) const {
        const toml::node* node = find(key);
        if (node == nullptr) {
            context_.fail(table_.source(), path_,
                          fmt::format("the required key '{}' is missing", key));
        }
        return *node;
    }
    /// Rejects every key of the table that is not an allowed one.
    void finish() const {
        for (auto&& [key, node] : table_) {
            const std::string name(key.str());
            if (std::find(allowed_.begin(), allowed_.end(), name) == allowed_.end()) {
                context_.fail(key.source(), child(name),
                              fmt::format("unknown key (allowed here: {})",
                                          fmt::join(allowed_, ", ")));
            }
        }
    }
    /// The key path of a child: "image.width", "mesh[2].uv".
    std::string child(const std::string& key) const {
        return path_.empty() ? key : path_ + "." + key;
    }
    const Context& context() const { return context_; }
    const toml::table& table() const { return table_; }
    const std::string& path() const { return path_; }

  private:
    const Context& context_;
    const toml::table& table_;
    std::string path_;
    std::vector<std::string> allowed_;
};
//< table-reader

//> read-number
/// The value of a TOML number, exactly: every number of a scene is read here. An integer
/// a double cannot hold exactly (beyond 2^53) is an Error, never a rounded value.
double exact_number(const Context& c, const toml::node& node, const std::string& path) {
    if (const auto* integer = node.as_integer()) {
        const std::int64_t value = integer->get();
        constexpr std::int64_t exact_limit = std::int64_t{1} << 53;
        if (value > exact_limit || value < -exact_limit) {
            c.fail(node.source(), path,
                   fmt::format("{} is not exactly representable (integers are allowed "
                               "from -2^53 to 2^53)",
                               value));
        }
        return static_cast<double>(value);
    }
    if (const auto* floating = node.as_floating_point()) {
        // A number below 2^-1022 is the loader's own reading (parse_toml), the rest
        // toml++'s: both round to the nearest double.
        const auto own =
            c.own_numbers.find({node.source().begin.line, node.source().begin.column});
        return own != c.own_numbers.end() ? own->second : floating->get();
    }
    c.fail(node.source(), path,
           fmt::format("expected a number, got {}", type_name(node)));
}

/// A finite number in [lo, hi] (integers are accepted where a float is asked for).
double read_number(const Context& c, const toml::node& node, const std::string& path,
                   double lo, double hi) {
    const double value = exact_number(c, node, path); // Error if not a number
    if (!std::isfinite(value)) {
        c.fail(node.source(), path, fmt::format("{} is not a finite number", value));
    }
    if (value < lo || value > hi) {
        c.fail(node.source(), path,
               fmt::format("{} is out of range (allowed: {} to {})", value, lo, hi));
    }
    return value;
}
//< read-number

/// A number that must be strictly above `lo` (a size, a distance, a budget).
double read_positive(const Context& c, const toml::node& node, const std::string& path,
                     double lo, double hi) {
    const double value = read_number(c, node, path, lo, hi);
    if (!(value > lo)) {
        c.fail(node.source(), path, fmt::format("{} must be greater than {}", value, lo));
    }
    return value;
}

int read_integer(const Context& c, const toml::node& node, const std::string& path,
                 int lo, int hi) {
    if (!node.is_integer()) {
        c.fail(node.source(), path,
               fmt::format("expected an integer, got {}", type_name(node)));
    }
    const double value = exact_number(c, node, path);
    if (value < lo || value > hi) {
        c.fail(node.source(), path,
               fmt::format("{} is out of range (allowed: {} to {})", value, lo, hi));
    }
    return static_cast<int>(value);
}

std::string read_string(const Context& c, const toml::node& node,
                        const std::string& path) {
    if (!node.is_string()) {
        c.fail(node.source(), path,
               fmt::format("expected a string, got {}", type_name(node)));
    }
    return node.as_string()->get();
}

bool read_bool(const Context& c, const toml::node& node, const std::string& path) {
    if (!node.is_boolean()) {
        c.fail(node.source(), path,
               fmt::format("expected true or false, got {}", type_name(node)));
    }
    return node.as_boolean()->get();
}

/// One of a list of words.
std::size_t read_choice(const Context& c, const toml::node& node, const std::string& path,
                        const std::vector<std::string>& words) {
    const std::string word = read_string(c, node, path);
    const auto found = std::find(words.begin(), words.end(), word);
    if (found == words.end()) {
        c.fail(node.source(), path,
               fmt::format("'{}' is not one of: {}", word, fmt::join(words, ", ")));
    }
    return static_cast<std::size_t>(found - words.begin());
}

const toml::array& read_array(const Context& c, const toml::node& node,
                              const std::string& path, std::size_t min_size,
                              std::size_t max_size) {
    if (!node.is_array()) {
        c.fail(node.source(), path,
               fmt::format("expected an array, got {}", type_name(node)));
    }
    const toml::array& array = *node.as_array();
    if (array.size() < min_size || array.size() > max_size) {
        c.fail(node.source(), path,
               min_size == max_size
                   ? fmt::format("expected {} elements, got {}", min_size, array.size())
                   : fmt::format("expected {} to {} elements, got {}", min_size, max_size,
                                 array.size()));
    }
    return array;
}

/// N numbers in [lo, hi]: a point, a size, a colour.
template <int N>
glm::vec<N, double> read_vector(const Context& c, const toml::node& node,
                                const std::string& path, double lo, double hi) {
    const toml::array& array = read_array(c, node, path, N, N);
    glm::vec<N, double> result{};
    for (int k = 0; k < N; ++k) {
        result[k] = read_number(c, *array.get(static_cast<std::size_t>(k)),
                                fmt::format("{}[{}]", path, k), lo, hi);
    }
    return result;
}

/// World coordinates are kept within +-1e6 units so that every product stays finite.
constexpr double world_limit = 1e6;
/// Texture coordinates are kept within +-2^20 texels.
constexpr double uv_limit = 1 << 20;

glm::dvec3 read_point(const Context& c, const toml::node& node, const std::string& path) {
    return read_vector<3>(c, node, path, -world_limit, world_limit);
}

Colour read_colour(const Context& c, const toml::node& node, const std::string& path) {
    return read_vector<3>(c, node, path, 0.0, 1.0);
}

/// A list of `count` N-vectors (count = 0: any number >= 1).
template <int N>
std::vector<glm::vec<N, double>> read_vectors(const Context& c, const toml::node& node,
                                              const std::string& path, std::size_t count,
                                              double lo, double hi) {
    const std::size_t max_count = static_cast<std::size_t>(3 * max_scene_triangles);
    const toml::array& array =
        read_array(c, node, path, count == 0 ? 1 : count, count == 0 ? max_count : count);
    std::vector<glm::vec<N, double>> result;
    for (std::size_t k = 0; k < array.size(); ++k) {
        result.push_back(
            read_vector<N>(c, *array.get(k), fmt::format("{}[{}]", path, k), lo, hi));
    }
    return result;
}

void read_image(const TableReader& t, Scene& scene) {
    const Context& c = t.context();
    if (const auto* n = t.find("width")) {
        scene.width = read_integer(c, *n, t.child("width"), 1, max_image_side);
    }
    if (const auto* n = t.find("height")) {
        scene.height = read_integer(c, *n, t.child("height"), 1, max_image_side);
    }
    if (static_cast<long long>(scene.width) * scene.height > max_image_pixels) {
        c.fail(t.table().source(), t.path(),
               fmt::format("{} x {} pixels is more than the {} allowed", scene.width,
                           scene.height, max_image_pixels));
    }
    if (const auto* n = t.find("background")) {
        scene.background = read_colour(c, *n, t.child("background"));
    }
    t.finish();
}

void read_camera(const TableReader& t, SceneCamera& camera) {
    const Context& c = t.context();
    if (const auto* n = t.find("projection")) {
        camera.projection = read_choice(c, *n, t.child("projection"),
                                        {"perspective", "orthographic"}) == 0
                                ? Projection::perspective
                                : Projection::orthographic;
    }
    if (const auto* n = t.find("fov")) {
        camera.fov_degrees = read_positive(c, *n, t.child("fov"), 0.0, 179.0);
    }
    if (const auto* n = t.find("view_height")) {
        camera.view_height =
            read_positive(c, *n, t.child("view_height"), 0.0, world_limit);
    }
    if (const auto* n = t.find("near")) {
        camera.near = read_number(c, *n, t.child("near"), min_camera_near, world_limit);
    }
    if (const auto* n = t.find("far")) { // finite (read_number), and beyond near
        camera.far = read_number(c, *n, t.child("far"), min_camera_near, world_limit);
        if (!(camera.far > camera.near)) {
            c.fail(n->source(), t.child("far"),
                   fmt::format("{} must be greater than near ({})", camera.far,
                               camera.near));
        }
    }
    if (const auto* n = t.find("position")) {
        camera.position = read_point(c, *n, t.child("position"));
    }
    if (const auto* n = t.find("target")) {
        camera.target = read_point(c, *n, t.child("target"));
    }
    if (const auto* n = t.find("up")) {
        camera.up = read_point(c, *n, t.child("up"));
    }
    // The view direction and up must span a plane (chapter 7, @eq:scene-look-at).
    const glm::dvec3 forward = camera.target - camera.position;
    if (glm::length(glm::cross(forward, camera.up)) <=
            1e-12 * glm::length(forward) * glm::length(camera.up) ||
        glm::length(forward) == 0.0) {
        c.fail(t.table().source(), t.path(),
               "the camera looks along its up direction, or at its own position");
    }
    t.finish();
}

MapperChoice read_mapper(const Context& c, const toml::node& node,
                         const std::string& path) {
    const std::string word = read_string(c, node, path);
    if (word == "auto") {
        return {};
    }
    if (const std::optional<Mapper> mapper = parse_mapper(word)) {
        return {false, *mapper};
    }
    for (const char* prefix : {"subdivided:", "quadratic:"}) {
        if (word.rfind(prefix, 0) == 0) {
            c.fail(node.source(), path,
                   fmt::format("'{}': the span after '{}' must be a whole number of "
                               "pixels from {} to {}",
                               word, prefix, min_mapper_span, max_mapper_span));
        }
    }
    c.fail(node.source(), path,
           fmt::format("'{}' is not a mapper (allowed: auto, exact, affine, "
                       "quadratic, subdivided:N, quadratic:N)",
                       word));
}

void read_render(const TableReader& t, RenderOptions& options) {
    const Context& c = t.context();
    if (const auto* n = t.find("precision")) {
        const std::size_t k =
            read_choice(c, *n, t.child("precision"), {"float", "double", "fixed"});
        options.precision =
            std::array{Precision::float32, Precision::float64, Precision::fixed}[k];
    }
    if (const auto* n = t.find("mapper")) {
        options.mapper = read_mapper(c, *n, t.child("mapper"));
    }
    if (const auto* n = t.find("budget")) {
        options.budget = read_positive(c, *n, t.child("budget"), 0.0, 1e6);
    }
    if (const auto* n = t.find("rounding")) {
        options.rounding = read_bool(c, *n, t.child("rounding"));
    }
    if (const auto* n = t.find("colours")) {
        const std::size_t k =
            read_choice(c, *n, t.child("colours"), {"screen", "perspective", "auto"});
        options.colours =
            std::array{ColourInterpolation::screen, ColourInterpolation::perspective,
                       ColourInterpolation::automatic}[k];
    }
    if (const auto* n = t.find("filter")) {
        const std::size_t k =
            read_choice(c, *n, t.child("filter"),
                        {"nearest", "bilinear", "trilinear", "anisotropic", "auto"});
        options.filter = std::array{SceneFilter::nearest, SceneFilter::bilinear,
                                    SceneFilter::trilinear, SceneFilter::anisotropic,
                                    SceneFilter::automatic}[k];
    }
    if (const auto* n = t.find("shading")) {
        options.shading =
            read_choice(c, *n, t.child("shading"), {"gouraud", "phong"}) == 0
                ? Shading::gouraud
                : Shading::phong;
    }
    if (const auto* n = t.find("ambient")) {
        options.ambient = read_colour(c, *n, t.child("ambient"));
    }
    if (const auto* n = t.find("depth")) { // true, false or "auto"
        if (n->is_string()) {
            read_choice(c, *n, t.child("depth"), {"auto"});
            options.depth = DepthMode::automatic;
        } else if (n->is_boolean()) {
            options.depth =
                read_bool(c, *n, t.child("depth")) ? DepthMode::on : DepthMode::off;
        } else {
            c.fail(
                n->source(), t.child("depth"),
                fmt::format("expected true, false or \"auto\", got {}", type_name(*n)));
        }
    }
    t.finish();
}

/// A direction: three numbers, not all zero, returned as a unit vector.
glm::dvec3 read_direction(const Context& c, const toml::node& node,
                          const std::string& path) {
    const glm::dvec3 d = read_point(c, node, path);
    if (!(glm::length(d) > 0.0)) {
        c.fail(node.source(), path, "[0, 0, 0] has no direction");
    }
    return glm::normalize(d);
}

//> read-light
/// One `[[light]]` table: its type decides which keys it may have.
SceneLight read_light(const Context& c, const toml::table& table,
                      const std::string& path) {
    const toml::node* type = table.get("type");
    if (type == nullptr) {
        c.fail(table.source(), path, "the required key 'type' is missing");
    }
    const bool point =
        read_choice(c, *type, path + ".type", {"directional", "point"}) == 1;
    const TableReader t(
        c, table, path,
        {"type", point ? "position" : "direction", "colour", "intensity"});
    SceneLight light;
    light.type = point ? LightType::point : LightType::directional;
    if (point) {
        light.position = read_point(c, t.require("position"), t.child("position"));
    } else {
        light.direction = read_direction(c, t.require("direction"), t.child("direction"));
    }
    if (const auto* n = t.find("colour")) {
        light.colour = read_colour(c, *n, t.child("colour"));
    }
    if (const auto* n = t.find("intensity")) {
        light.intensity =
            read_number(c, *n, t.child("intensity"), 0.0, max_light_intensity);
    }
    t.finish(); // a direction on a point light, or a position on a directional one
    return light;
}
//< read-light

/// Counts a width x height texture against the scene's texel memory `texture_bytes`,
/// before the texture exists. The Error names no place: its caller's does.
void count_texture_bytes(long long& texture_bytes, long long width, long long height) {
    texture_bytes += width * height * 4;
    if (texture_bytes > max_scene_texture_bytes) {
        throw Error(
            fmt::format("a {}x{} texture takes the scene's textures beyond the {} "
                        "bytes allowed",
                        width, height, max_scene_texture_bytes));
    }
}

//> read-texture
Texture read_texture(const TableReader& t, long long& texture_bytes) {
    const Context& c = t.context();
    const auto take = [&](const toml::node& where, const std::string& path,
                          long long width, long long height) {
        try {
            count_texture_bytes(texture_bytes, width, height);
        } catch (const Error& error) {
            c.fail(where.source(), path, error.what());
        }
    };
    const std::size_t kind = read_choice(c, t.require("kind"), t.child("kind"),
                                         {"checkerboard", "grid", "f", "png"});
    const auto size = [&] {
        const toml::node& node = t.require("size");
        const toml::array& array = read_array(c, node, t.child("size"), 2, 2);
        return glm::ivec2{
            read_integer(c, *array.get(0), t.child("size") + "[0]", 1, max_texture_side),
            read_integer(c, *array.get(1), t.child("size") + "[1]", 1, max_texture_side)};
    };
    if (kind == 0 || kind == 1) { // checkerboard, grid
        const glm::ivec2 s = size();
        const char* key = kind == 0 ? "square" : "spacing";
        const int cell =
            read_integer(c, t.require(key), t.child(key), 1, max_texture_side);
        t.finish();
        take(t.require("size"), t.child("size"), s.x, s.y);
        if (kind == 0) {
            return checkerboard_texture(s.x, s.y, cell);
        }
        std::vector<Rgba8> texels; // lines one texel wide every `cell` texels
        for (int j = 0; j < s.y; ++j) {
            for (int i = 0; i < s.x; ++i) {
                const bool line = i % cell == 0 || j % cell == 0;
                texels.push_back(line ? rgba(250, 210, 60) : rgba(30, 40, 70));
            }
        }
        return Texture(s.x, s.y, std::move(texels));
    }
    if (kind == 2) { // the "F"
        const int cell = read_integer(c, t.require("cell"), t.child("cell"), 1, 256);
        t.finish();
        take(t.require("cell"), t.child("cell"), f_glyph_width * cell,
             f_glyph_height * cell);
        return f_texture(cell);
    }
    const toml::node& file = t.require("file");
    const std::filesystem::path path = c.folder / read_string(c, file, t.child("file"));
    t.finish();
    try { // every Error below names the path and the reason, and the catch its place
        return load_texture(path, [&](int width, int height) { // before decoding
            if (width > max_texture_side || height > max_texture_side) {
                throw Error(
                    fmt::format("{}: {}x{} texels is larger than the {} allowed per side",
                                path.string(), width, height, max_texture_side));
            }
            count_texture_bytes(texture_bytes, width, height);
        });
    } catch (const Error& error) {
        c.fail(file.source(), t.child("file"), error.what());
    }
}
//< read-texture

/// The quad a-b-c-d as two triangles sharing the diagonal a-c.
void add_quad(SceneMesh& mesh, const std::array<SceneVertex, 4>& q) {
    mesh.triangles.push_back({q[0], q[1], q[2]});
    mesh.triangles.push_back({q[0], q[2], q[3]});
}

/// A vertex on a plane spanned by two axes, uv = texels_per_unit * plane coordinates.
SceneVertex planar_vertex(glm::dvec3 p, glm::dvec2 plane, double texels_per_unit) {
    return {p, plane * texels_per_unit, {1.0, 1.0, 1.0}};
}

//> read-primitive
/// Fills mesh.triangles from the primitive the mesh table describes.
void read_primitive(const TableReader& t, SceneMesh& mesh, std::size_t primitive) {
    const Context& c = t.context();
    const auto tpu = [&] {
        const toml::node* n = t.find("texels_per_unit");
        return n ? read_positive(c, *n, t.child("texels_per_unit"), 0.0, 1e6) : 16.0;
    };
    const auto optional_vectors = [&](const char* key, std::size_t count, auto tag,
                                      double lo, double hi) {
        constexpr int N = decltype(tag)::value;
        const toml::node* n = t.find(key);
        return n ? read_vectors<N>(c, *n, t.child(key), count, lo, hi)
                 : std::vector<glm::vec<N, double>>{};
    };
    using Two = std::integral_constant<int, 2>;
    using Three = std::integral_constant<int, 3>;
    if (primitive == 0 || primitive == 1) { // triangles, quad
        const char* key = primitive == 0 ? "positions" : "corners";
        const std::vector<glm::dvec3> p =
            read_vectors<3>(c, t.require(key), t.child(key), primitive == 1 ? 4 : 0,
                            -world_limit, world_limit);
        if (primitive == 0 && p.size() % 3 != 0) {
            c.fail(t.require(key).source(), t.child(key),
                   fmt::format("{} points do not make whole triangles (need a "
                               "multiple of 3)",
                               p.size()));
        }
        const auto uv = optional_vectors("uv", p.size(), Two{}, -uv_limit, uv_limit);
        const auto rgb = optional_vectors("colours", p.size(), Three{}, 0.0, 1.0);
        mesh.vertex_colours = !rgb.empty();
        std::vector<SceneVertex> v(p.size());
        for (std::size_t k = 0; k < p.size(); ++k) {
            v[k] = {p[k], uv.empty() ? TexCoord{} : uv[k],
                    rgb.empty() ? Colour{1.0, 1.0, 1.0} : rgb[k]};
        }
        const toml::node* normals = t.find("normals");
        if (normals != nullptr && normals->is_array()) { // one per vertex, any length
            const toml::array& array =
                read_array(c, *normals, t.child("normals"), p.size(), p.size());
            for (std::size_t k = 0; k < p.size(); ++k) {
                v[k].normal = read_direction(
                    c, *array.get(k), fmt::format("{}[{}]", t.child("normals"), k));
            }
            mesh.normals = NormalSource::given;
        }
        if (primitive == 1) {
            add_quad(mesh, {v[0], v[1], v[2], v[3]});
        } else {
            for (std::size_t k = 0; k < v.size(); k += 3) {
                mesh.triangles.push_back({v[k], v[k + 1], v[k + 2]});
            }
        }
    } else if (primitive == 2) { // box: six faces, outward, counter-clockwise outside
        const glm::dvec3 centre = read_point(c, t.require("centre"), t.child("centre"));
        const glm::dvec3 h =
            0.5 * read_vector<3>(c, t.require("size"), t.child("size"), 0.0, world_limit);
        const double s = tpu();
        for (int axis = 0; axis < 3; ++axis) {
            for (const double side : {-1.0, 1.0}) {
                const int a = (axis + 1) % 3, b = (axis + 2) % 3; // the face's axes
                std::array<SceneVertex, 4> q;
                const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
                for (int k = 0; k < 4; ++k) {
                    glm::dvec3 p = centre;
                    p[axis] += side * h[axis];
                    // Walk the face one way on the + side and the other way on the -
                    // side, so that all faces turn the same way seen from outside.
                    const double ca = corners[k][0], cb = corners[k][1] * side;
                    p[a] += ca * h[a];
                    p[b] += cb * h[b];
                    q[static_cast<std::size_t>(k)] = planar_vertex(
                        p, {(ca + 1) * h[a], (1 - corners[k][1]) * h[b]}, s);
                }
                // The walk above turns from axis a to axis b, counter-clockwise about
                // the outward axis in a right-handed frame; world space is left-handed
                // (x right, y up, z forward), where that turn looks clockwise from
                // outside. Reversed, each face is counter-clockwise seen from outside,
                // which is what the renderer's back-face test takes as a front face.
                add_quad(mesh, {q[0], q[3], q[2], q[1]});
            }
        }
    } else if (primitive == 3) { // floor: a horizontal rectangle at height y
        const double y =
            read_number(c, t.require("y"), t.child("y"), -world_limit, world_limit);
        const glm::dvec2 x =
            read_vector<2>(c, t.require("x"), t.child("x"), -world_limit, world_limit);
        const glm::dvec2 z =
            read_vector<2>(c, t.require("z"), t.child("z"), -world_limit, world_limit);
        const double s = tpu();
        add_quad(mesh, {planar_vertex({x[0], y, z[0]}, {x[0], -z[0]}, s),
                        planar_vertex({x[0], y, z[1]}, {x[0], -z[1]}, s),
                        planar_vertex({x[1], y, z[1]}, {x[1], -z[1]}, s),
                        planar_vertex({x[1], y, z[0]}, {x[1], -z[0]}, s)});
    } else { // fan: a disc of `segments` triangles around a centre, facing -z
        const glm::dvec3 centre = read_point(c, t.require("centre"), t.child("centre"));
        const double radius =
            read_positive(c, t.require("radius"), t.child("radius"), 0.0, world_limit);
        const int segments =
            read_integer(c, t.require("segments"), t.child("segments"), 3, 4096);
        const auto rim = optional_vectors("rim_colours", 0, Three{}, 0.0, 1.0);
        const toml::node* hub = t.find("centre_colour");
        mesh.vertex_colours = !rim.empty() || hub != nullptr;
        const Colour hub_colour =
            hub ? read_colour(c, *hub, t.child("centre_colour")) : Colour{1.0, 1.0, 1.0};
        const double s = tpu();
        const auto rim_vertex = [&](int k) {
            const double angle = 2.0 * std::numbers::pi * (k % segments) / segments;
            const glm::dvec2 d{std::cos(angle), std::sin(angle)};
            SceneVertex v = planar_vertex(centre + radius * glm::dvec3{d.x, d.y, 0.0},
                                          radius * glm::dvec2{1.0 + d.x, 1.0 - d.y}, s);
            if (!rim.empty()) {
                v.colour = rim[static_cast<std::size_t>(k % segments) % rim.size()];
            }
            return v;
        };
        SceneVertex middle = planar_vertex(centre, {radius, radius}, s);
        middle.colour = hub_colour;
        for (int k = 0; k < segments; ++k) {
            mesh.triangles.push_back({middle, rim_vertex(k), rim_vertex(k + 1)});
        }
    }
}
//< read-primitive

const std::vector<std::string> primitive_keys[5] = {
    {"positions", "uv", "colours"},
    {"corners", "uv", "colours"},
    {"centre", "size", "texels_per_unit"},
    {"y", "x", "z", "texels_per_unit"},
    {"centre", "radius", "segments", "rim_colours", "centre_colour", "texels_per_unit"},
};

//> read-transform
/// The mesh's `scale`, `rotate` and `translate` (each optional): a number or three
/// factors, each > 0; three angles in degrees; a point.
MeshTransform read_transform(const TableReader& t) {
    const Context& c = t.context();
    MeshTransform transform;
    if (const auto* n = t.find("scale")) {
        if (n->is_array()) {
            const toml::array& array = read_array(c, *n, t.child("scale"), 3, 3);
            for (int k = 0; k < 3; ++k) {
                transform.scale[k] =
                    read_positive(c, *array.get(static_cast<std::size_t>(k)),
                                  fmt::format("{}[{}]", t.child("scale"), k), 0.0, 1e6);
            }
        } else {
            transform.scale =
                glm::dvec3{read_positive(c, *n, t.child("scale"), 0.0, 1e6)};
        }
    }
    if (const auto* n = t.find("rotate")) {
        transform.rotate_degrees = read_vector<3>(c, *n, t.child("rotate"), -3600, 3600);
    }
    if (const auto* n = t.find("translate")) {
        transform.translate = read_point(c, *n, t.child("translate"));
    }
    return transform;
}

/// Places the mesh by the transform, then checks what the scene asks of every mesh:
/// coordinates within the world limit, no triangle of zero area.
void place_and_check(const Context& c, const toml::table& table, const std::string& path,
                     SceneMesh& mesh, const MeshTransform& transform) {
    try {
        transform_mesh(mesh, transform);
    } catch (const Error& error) {
        c.fail(table.source(), path, error.what());
    }
    for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
        const auto& tri = mesh.triangles[k];
        for (const SceneVertex& v : tri) {
            for (int i = 0; i < 3; ++i) {
                if (!(std::abs(v.position[i]) <= world_limit)) {
                    c.fail(table.source(), path,
                           fmt::format("{} reaches {} after the transform, "
                                       "beyond the world's +-{}",
                                       triangle_name(mesh, k), v.position[i],
                                       world_limit));
                }
            }
        }
        // A triangle of zero area in the world has no plane to interpolate on: reject
        // it here rather than draw nothing later.
        const glm::dvec3 e1 = tri[1].position - tri[0].position;
        const glm::dvec3 e2 = tri[2].position - tri[0].position;
        const double area2 = glm::length(glm::cross(e1, e2));
        if (!(area2 > 1e-12 * glm::length(e1) * glm::length(e2))) {
            c.fail(table.source(), path,
                   fmt::format("{} is degenerate (its corners are collinear or "
                               "coincide, so it has no area)",
                               triangle_name(mesh, k)));
        }
    }
    share_positions(mesh); // the geometry stage moves each distinct position once
}
//< read-transform

const std::vector<std::string> transform_keys{"translate", "rotate", "scale"};

SceneMesh read_mesh(const Context& c, const toml::table& table, const std::string& path,
                    const Scene& scene) {
    // Which keys are allowed depends on the primitive: read it first.
    const toml::node* kind_node = table.get("primitive");
    if (kind_node == nullptr) {
        c.fail(table.source(), path,
               "the required key 'primitive' (or 'file', for a model) is missing");
    }
    const std::size_t primitive = read_choice(
        c, *kind_node, path + ".primitive", {"triangles", "quad", "box", "floor", "fan"});
    std::vector<std::string> allowed{"primitive", "name",     "texture", "wrap",
                                     "colour",    "cull",     "normals", "shading",
                                     "specular",  "shininess"};
    allowed.insert(allowed.end(), primitive_keys[primitive].begin(),
                   primitive_keys[primitive].end());
    allowed.insert(allowed.end(), transform_keys.begin(), transform_keys.end());
    const TableReader t(c, table, path, allowed);
    SceneMesh mesh;
    mesh.name = path;
    mesh.origin = fmt::format("{}:{}:{}: {}", c.file, table.source().begin.line,
                              table.source().begin.column, path);
    if (const auto* n = t.find("name")) {
        mesh.name = read_string(c, *n, t.child("name"));
    }
    if (const auto* n = t.find("texture")) {
        const std::string name = read_string(c, *n, t.child("texture"));
        const auto found =
            std::find_if(scene.textures.begin(), scene.textures.end(),
                         [&](const SceneTexture& s) { return s.name == name; });
        if (found == scene.textures.end()) {
            c.fail(n->source(), t.child("texture"),
                   fmt::format("no texture named '{}' under [textures]", name));
        }
        mesh.texture = static_cast<std::size_t>(found - scene.textures.begin());
    }
    if (const auto* n = t.find("wrap")) {
        mesh.wrap = read_choice(c, *n, t.child("wrap"), {"repeat", "clamp"}) == 0
                        ? Wrap::repeat
                        : Wrap::clamp;
    }
    if (const auto* n = t.find("colour")) {
        mesh.colour = read_colour(c, *n, t.child("colour"));
    }
    if (const auto* n = t.find("cull")) {
        mesh.cull_back = read_choice(c, *n, t.child("cull"), {"none", "back"}) == 1;
    }
    if (const auto* n = t.find("normals"); n != nullptr && !n->is_array()) {
        mesh.normals = read_choice(c, *n, t.child("normals"), {"face", "smooth"}) == 0
                           ? NormalSource::face
                           : NormalSource::smooth;
    } else if (n != nullptr && primitive != 0 && primitive != 1) {
        c.fail(n->source(), t.child("normals"),
               "one normal per vertex is possible only for \"triangles\" and \"quad\" "
               "(here: \"face\" or \"smooth\")");
    }
    if (const auto* n = t.find("shading")) {
        mesh.shading = read_choice(c, *n, t.child("shading"), {"gouraud", "phong"}) == 0
                           ? Shading::gouraud
                           : Shading::phong;
    }
    if (const auto* n = t.find("specular")) {
        mesh.specular = read_colour(c, *n, t.child("specular"));
    }
    if (const auto* n = t.find("shininess")) {
        mesh.shininess = read_number(c, *n, t.child("shininess"), 1.0, max_shininess);
    }
    read_primitive(t, mesh, primitive);
    const MeshTransform transform = read_transform(t);
    t.finish();
    place_and_check(c, table, path, mesh, transform);
    return mesh;
}

//> read-model
/// A model file as a scene holds it once: the model (its triangles in model space), the
/// scene texture each part's map_Kd became, and its triangle count.
struct LoadedModel {
    Model model;
    std::vector<std::optional<std::size_t>> textures; ///< per part, into scene.textures
    long long triangles = 0;
};

/// The model files a scene has read, by identity (device and inode), so that every
/// reference to one file, however its path is spelled, reads and checks it once and
/// shares its textures.
struct ModelCache {
    std::map<std::pair<dev_t, ino_t>, LoadedModel> models;
    long long bytes = 0; ///< the sizes of the model files read so far
};

/// Reads the model `model_path` names, or finds it in `cache`. A new model's files are
/// added to scene.models and its textures to scene.textures. Errors name `file`'s place.
const LoadedModel& load_model(const Context& c, const toml::node& file,
                              const std::string& path,
                              const std::filesystem::path& model_path, Scene& scene,
                              ModelCache& cache, long long& texture_bytes) {
    const auto read = [&] {
        try {
            return read_obj_model(model_path, texture_bytes);
        } catch (const Error& error) { // names the model's file and line, and the value
            c.fail(file.source(), path, error.what());
        }
    };
    struct stat info {};
    if (::stat(model_path.c_str(), &info) != 0) {
        // Missing or unreadable: read_obj_model says why, as for any input. A file that
        // appears in between is refused, not read without its size counted.
        read();
        c.fail(file.source(), path,
               fmt::format("{}: the model file changed while it was read",
                           model_path.string()));
    }
    const std::pair key{info.st_dev, info.st_ino};
    if (const auto found = cache.models.find(key); found != cache.models.end()) {
        return found->second;
    }
    // Checked from the file's size before it is read (read_obj_model refuses anything
    // but a regular file, whose size this is).
    if (cache.bytes + info.st_size > max_scene_model_bytes) {
        c.fail(file.source(), path,
               fmt::format("{}: {} bytes take the scene's model files beyond the {} "
                           "bytes allowed together",
                           model_path.string(), info.st_size, max_scene_model_bytes));
    }
    LoadedModel loaded{read(), {}, 0};
    cache.bytes += info.st_size;
    scene.models.insert(scene.models.end(), loaded.model.files.begin(),
                        loaded.model.files.end());
    for (ModelPart& part : loaded.model.parts) {
        loaded.triangles += static_cast<long long>(part.triangles.size());
        loaded.textures.emplace_back();
        if (part.texture) {
            if (scene.textures.size() >= static_cast<std::size_t>(max_scene_textures)) {
                c.fail(file.source(), path,
                       fmt::format("the model's textures take the scene beyond the {} "
                                   "textures allowed",
                                   max_scene_textures));
            }
            loaded.textures.back() = scene.textures.size();
            scene.textures.push_back(std::move(*part.texture));
            part.texture.reset(); // the scene holds it now; references use the index
        }
    }
    return cache.models.emplace(key, std::move(loaded)).first->second;
}

/// A `[[mesh]]` with `file = "model.obj"`: one SceneMesh per material the model's faces
/// use, each with that material's texture. `triangles` is the scene's count so far: the
/// model's copies are checked against max_scene_triangles and max_scene_meshes before
/// they are made.
void read_model(const Context& c, const toml::table& table, const std::string& path,
                Scene& scene, ModelCache& cache, long long& texture_bytes,
                long long triangles) {
    const TableReader t(c, table, path,
                        {"file", "name", "wrap", "cull", "normals", "shading", "specular",
                         "shininess", "translate", "rotate", "scale"});
    const toml::node& file = t.require("file");
    const std::filesystem::path model_path =
        c.folder / read_string(c, file, t.child("file"));
    std::string name = path;
    if (const auto* n = t.find("name")) {
        name = read_string(c, *n, t.child("name"));
    }
    Wrap wrap = Wrap::repeat;
    if (const auto* n = t.find("wrap")) {
        wrap = read_choice(c, *n, t.child("wrap"), {"repeat", "clamp"}) == 0
                   ? Wrap::repeat
                   : Wrap::clamp;
    }
    bool cull_back = false;
    if (const auto* n = t.find("cull")) {
        cull_back = read_choice(c, *n, t.child("cull"), {"none", "back"}) == 1;
    }
    // The lighting keys, as an inline mesh reads them (normals "given": the OBJ's vn).
    SceneMesh lit;
    const toml::node* normals = t.find("normals");
    if (normals != nullptr) {
        const std::size_t kind =
            read_choice(c, *normals, t.child("normals"), {"face", "smooth", "given"});
        lit.normals = kind == 0   ? NormalSource::face
                      : kind == 1 ? NormalSource::smooth
                                  : NormalSource::given;
    }
    if (const auto* n = t.find("shading")) {
        lit.shading = read_choice(c, *n, t.child("shading"), {"gouraud", "phong"}) == 0
                          ? Shading::gouraud
                          : Shading::phong;
    }
    if (const auto* n = t.find("specular")) {
        lit.specular = read_colour(c, *n, t.child("specular"));
    }
    if (const auto* n = t.find("shininess")) {
        lit.shininess = read_number(c, *n, t.child("shininess"), 1.0, max_shininess);
    }
    const MeshTransform transform = read_transform(t);
    t.finish();
    const LoadedModel& loaded =
        load_model(c, file, t.child("file"), model_path, scene, cache, texture_bytes);
    if (lit.normals == NormalSource::given && loaded.model.line_without_normal != 0) {
        c.fail(normals->source(), t.child("normals"),
               fmt::format("\"given\" needs a normal at every corner, and the face at "
                           "{}:{} has a corner without one (no vn index)",
                           model_path.string(), loaded.model.line_without_normal));
    }
    if (triangles + loaded.triangles > max_scene_triangles) {
        c.fail(file.source(), t.child("file"),
               fmt::format("the model's {} triangles take the scene beyond the {} "
                           "triangles allowed",
                           loaded.triangles, max_scene_triangles));
    }
    if (scene.meshes.size() + loaded.model.parts.size() >
        static_cast<std::size_t>(max_scene_meshes)) {
        c.fail(file.source(), t.child("file"),
               fmt::format("the model's {} materials take the scene beyond the {} "
                           "meshes allowed",
                           loaded.model.parts.size(), max_scene_meshes));
    }
    for (std::size_t k = 0; k < loaded.model.parts.size(); ++k) {
        const ModelPart& part = loaded.model.parts[k];
        SceneMesh mesh;
        mesh.name = part.material.empty() ? name : name + "/" + part.material;
        mesh.origin = fmt::format("{}:{}:{}: {}", c.file, table.source().begin.line,
                                  table.source().begin.column, path);
        mesh.triangles = part.triangles; // copies: each reference is placed on its own
        mesh.model = model_path.string();
        mesh.model_lines = part.lines;
        mesh.colour = part.colour;
        mesh.texture = loaded.textures[k];
        mesh.wrap = wrap;
        mesh.cull_back = cull_back;
        mesh.normals = lit.normals;
        mesh.shading = lit.shading;
        mesh.specular = lit.specular;
        mesh.shininess = lit.shininess;
        place_and_check(c, table, path, mesh, transform);
        scene.meshes.push_back(std::move(mesh));
    }
}
//< read-model

} // namespace

/// The index just past the TOML string that opens at text[i] (a '"' or a '\''), one line
/// or three-quoted; for a string never closed, the line break or the end that cuts it.
std::size_t past_string(std::string_view text, std::size_t i) {
    const char quote = text[i];
    const bool triple = text.substr(i, 3) == std::string(3, quote);
    const std::string close = triple ? std::string(3, quote) : std::string(1, quote);
    std::size_t j = i + close.size();
    while (j < text.size() && text.compare(j, close.size(), close) != 0 &&
           (triple || text[j] != '\n')) {
        j += quote == '"' && text[j] == '\\' ? 2 : 1; // an escape in a basic string
    }
    return j < text.size() && text.compare(j, close.size(), close) == 0
               ? j + close.size()
               : std::min(j, text.size());
}

/// Rejects a dotted key of more than max_key_parts parts anywhere in `text`, before the
/// parser (which recurses once per part) sees it. Outside strings and comments, a dot
/// joins two parts of one key or the two halves of a float; a run of dots is broken only
/// by punctuation ('=', ',', brackets, braces) or a line break.
void check_key_depth(const Context& c, std::string_view text) {
    int line = 1, dots = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char ch = text[i];
        if (ch == '"' || ch == '\'') { // skip a string, one line or three-quoted
            const std::size_t end = past_string(text, i);
            line +=
                static_cast<int>(std::count(text.begin() + i, text.begin() + end, '\n'));
            i = end - 1;
        } else if (ch == '#') {
            while (i + 1 < text.size() && text[i + 1] != '\n') {
                ++i;
            }
        } else if (ch == '.') {
            if (++dots >= max_key_parts) {
                throw Error(fmt::format("{}:{}: a dotted key has more than {} parts",
                                        c.file, line, max_key_parts));
            }
        } else if (ch == '\n' || ch == '=' || ch == ',' || ch == '[' || ch == ']' ||
                   ch == '{' || ch == '}') {
            line += ch == '\n';
            dots = 0;
        }
    }
}

namespace {

/// Where in `text` the numbers are that toml++ may not read but the project does: the
/// TOML decimal floats in a value's place whose magnitude is nonzero and below the
/// smallest normal double, 2^-1022. toml++ reads a float through the standard library's
/// streams, and LLVM's libc++ refuses such a number there (its strtod reports ERANGE).
/// A value's place: after '=', or after '[' or ',' inside an array or inline table, and
/// not before '=' (a key); headers and comments and strings are skipped.
std::vector<std::size_t> tiny_numbers(std::string_view text) {
    std::vector<std::size_t> found;
    int depth = 0;       // of the arrays and inline tables open in a value
    bool header = false; // between a table header's brackets
    char last = '\n';    // the last character that counts (not blank, not in a comment)
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char ch = text[i];
        if (ch == '"' || ch == '\'') {
            i = past_string(text, i) - 1;
            last = '"';
        } else if (ch == '#') {
            i = std::min(text.find('\n', i), text.size()) - 1;
        } else if (ch == '\n') {
            header = depth == 0 ? false : header;
            last = depth == 0 ? '\n' : last;
        } else if (ch == '[' && depth == 0 && (last == '\n' || header)) {
            header = true;
            last = ch;
        } else if (ch == '[' || ch == '{') {
            depth += header ? 0 : 1;
            last = ch;
        } else if (ch == ']' || ch == '}') {
            depth -= depth > 0 && !header ? 1 : 0;
            last = ch;
        } else if (is_bare_char(ch)) {
            const std::string_view token = bare_run(text, i);
            const std::size_t next = text.find_first_not_of(" \t", i + token.size());
            const bool value =
                !header && (last == '=' || (depth > 0 && (last == '[' || last == ','))) &&
                (next == std::string_view::npos || text[next] != '=');
            if (value && is_decimal_float(token)) {
                const std::optional<double> number = read_decimal_float(token);
                const bool nonzero = // a digit 1 to 9 before the exponent
                    token.find_first_of("123456789") < token.find_first_of("eE");
                if (number && std::abs(*number) < std::numeric_limits<double>::min() &&
                    nonzero) {
                    found.push_back(i);
                }
            }
            i += token.size() - 1;
            last = 'a';
        } else if (ch != ' ' && ch != '\t' && ch != '\r') {
            last = ch;
        }
    }
    return found;
}

/// Where in the scene's text toml++ read a float.
void float_places(const toml::node& node, std::set<TextPlace>& out) {
    if (const toml::table* table = node.as_table()) {
        for (auto&& [key, child] : *table) {
            float_places(child, out);
        }
    } else if (const toml::array* array = node.as_array()) {
        for (const toml::node& child : *array) {
            float_places(child, out);
        }
    } else if (node.is_floating_point()) {
        out.insert({node.source().begin.line, node.source().begin.column});
    }
}

} // namespace

/// The key as written on `line` (one line of a scene) that a toml++ error at `column`
/// (from 1) is about: the last key before the column that ends at an unquoted '=' (a
/// key-value pair) or ']' (a table header), or the first one when the error points
/// before it (at a header's '['). Empty when the line has none.
std::string key_written_on(std::string_view line, std::size_t column) {
    std::string key;
    std::size_t start = 0; // where the key being scanned begins
    for (std::size_t i = 0; i < line.size() && line[i] != '#'; ++i) {
        const char ch = line[i];
        if (ch == '"' || ch == '\'') {
            i = past_string(line, i) - 1;
        } else if (ch == '[' || ch == '{' || ch == ',') {
            start = i + 1;
        } else if (ch == '=' || ch == ']') {
            const std::size_t first = line.find_first_not_of(" \t", start);
            const std::size_t last = line.find_last_not_of(" \t", i - 1);
            const bool before = i + 1 < column;
            if (first < i && (before || key.empty())) {
                key = line.substr(first, last + 1 - first);
            }
            if (!before && !key.empty()) {
                break;
            }
            start = i + 1;
        }
    }
    return key;
}

/// toml++'s description of a parse error, with the key of a redefinition named as the
/// scene wrote it. toml++ 3.3 quotes that key ("cannot redefine existing array '...' as
/// table", "cannot insert '...' into existing inline table") from a record of the text
/// that holds a quoted key's first characters twice: ["mesh"] after [[mesh]] is named
/// '"memesh"'. The key between its first and last quote is replaced by the key read
/// from the line the error points at.
std::string toml_message(const toml::parse_error& error, std::string_view text) {
    std::string message(error.description());
    const std::size_t open = message.find('\'');
    const std::size_t close = message.rfind('\'');
    if (message.find("cannot redefine existing") == std::string::npos &&
        message.find("cannot insert") == std::string::npos) {
        return message;
    }
    if (open == std::string::npos || open == close) {
        return message;
    }
    std::size_t begin = 0; // of the error's line in text
    for (auto n = error.source().begin.line; n > 1 && begin != std::string_view::npos;
         --n) {
        begin = text.find('\n', begin);
        begin = begin == std::string_view::npos ? begin : begin + 1;
    }
    if (begin == std::string_view::npos) {
        return message;
    }
    const std::string_view line = text.substr(begin, text.find('\n', begin) - begin);
    const std::string key = key_written_on(line, error.source().begin.column);
    return key.empty() ? message : message.replace(open + 1, close - open - 1, key);
}

/// The scene's TOML document, as toml++ reads it with a 0 of the same length in place of
/// each number below 2^-1022 (tiny_numbers), whose value the loader reads itself into
/// c.own_numbers: every column stays where it was, and toml++ reads the same on every
/// standard library. Where a 0 stood anywhere but in a float's place, the text is read as
/// written, and so is a text with an error (the error is the text's as written, unless
/// that is toml++ refusing a tiny number).
toml::table parse_toml(Context& c) {
    const std::vector<std::size_t> tiny = tiny_numbers(c.text);
    std::string zeroed(c.text);
    std::set<TextPlace> tiny_ends; // where toml++ reports refusing one
    // The place of each, counted from the one before.
    std::size_t i = c.text.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;
    TextPlace place{1, 1};
    for (const std::size_t at : tiny) {
        for (; i < at; ++i) {
            const bool continuation =
                (static_cast<unsigned char>(c.text[i]) & 0xC0) == 0x80;
            place = c.text[i] == '\n'
                        ? TextPlace{place.first + 1, 1}
                        : TextPlace{place.first, place.second + !continuation};
        }
        const std::string_view token = bare_run(c.text, at);
        c.own_numbers[place] = *read_decimal_float(token);
        tiny_ends.insert({place.first, place.second + token.size()});
        const std::size_t digits = token[0] == '-' || token[0] == '+' ? 1 : 0;
        zeroed.replace(at + digits, token.size() - digits,
                       "0." + std::string(token.size() - digits - 2, '0'));
    }
    std::optional<toml::parse_error> zeroed_error;
    try {
        toml::table root = toml::parse(zeroed, c.file);
        std::set<TextPlace> floats;
        float_places(root, floats);
        if (std::all_of(c.own_numbers.begin(), c.own_numbers.end(),
                        [&](const auto& own) { return floats.count(own.first) != 0; })) {
            return root;
        }
    } catch (const toml::parse_error& error) {
        zeroed_error = error;
    }
    c.own_numbers.clear();
    try {
        return toml::parse(c.text, c.file);
    } catch (const toml::parse_error& error) {
        const bool refused = tiny_ends.count({error.source().begin.line,
                                              error.source().begin.column}) != 0;
        const toml::parse_error& shown = refused && zeroed_error ? *zeroed_error : error;
        c.fail(shown.source(), "(syntax)", toml_message(shown, c.text));
    }
}

Scene parse_scene(std::string_view text, const std::filesystem::path& file,
                  const std::filesystem::path& folder) {
    Context context{file.string(), folder, text, {}};
    check_key_depth(context, text);
    const toml::table root = parse_toml(context);
    const Context& c = context;
    Scene scene;
    scene.file = file;
    const TableReader top(c, root, "",
                          {"image", "camera", "render", "textures", "mesh", "light"});
    const auto section = [&](const char* key) -> const toml::table* {
        const toml::node* n = top.find(key);
        if (n != nullptr && !n->is_table()) {
            c.fail(n->source(), key,
                   fmt::format("expected a table, got {}", type_name(*n)));
        }
        return n ? n->as_table() : nullptr;
    };
    if (const toml::table* t = section("image")) {
        read_image(TableReader(c, *t, "image", {"width", "height", "background"}), scene);
    }
    if (const toml::table* t = section("camera")) {
        read_camera(TableReader(c, *t, "camera",
                                {"projection", "fov", "view_height", "near", "far",
                                 "position", "target", "up"}),
                    scene.camera);
    }
    if (const toml::table* t = section("render")) {
        read_render(TableReader(c, *t, "render",
                                {"precision", "mapper", "budget", "rounding", "depth",
                                 "colours", "filter", "shading", "ambient"}),
                    scene.options);
    }
    long long texture_bytes = 0; // the texel memory of the textures so far
    if (const toml::table* t = section("textures")) {
        if (t->size() > static_cast<std::size_t>(max_scene_textures)) {
            c.fail(t->source(), "textures",
                   fmt::format("{} textures are more than the {} allowed", t->size(),
                               max_scene_textures));
        }
        for (auto&& [key, node] : *t) {
            const std::string path = "textures." + std::string(key.str());
            if (!node.is_table()) {
                c.fail(node.source(), path,
                       fmt::format("expected a table, got {}", type_name(node)));
            }
            const TableReader reader(
                c, *node.as_table(), path,
                {"kind", "size", "square", "spacing", "cell", "file"});
            SceneTexture texture{
                std::string(key.str()), read_texture(reader, texture_bytes), {}};
            const toml::node* file = node.as_table()->get("file");
            if (file != nullptr && file->is_string()) { // read_texture has checked it
                texture.file = c.folder / file->as_string()->get();
            }
            scene.textures.push_back(std::move(texture));
        }
    }
    if (const toml::node* lights = top.find("light")) {
        const toml::array& list = read_array(c, *lights, "light", 1,
                                             static_cast<std::size_t>(max_scene_lights));
        for (std::size_t k = 0; k < list.size(); ++k) {
            const std::string path = fmt::format("light[{}]", k);
            const toml::node& node = *list.get(k);
            if (!node.is_table()) {
                c.fail(node.source(), path,
                       fmt::format("expected a table, got {}", type_name(node)));
            }
            scene.lights.push_back(read_light(c, *node.as_table(), path));
        }
    }
    const toml::node* meshes = top.find("mesh");
    if (meshes == nullptr) {
        c.fail(root.source(), "mesh", "the scene has no [[mesh]]: nothing to draw");
    }
    const toml::array& list =
        read_array(c, *meshes, "mesh", 1, static_cast<std::size_t>(max_scene_meshes));
    ModelCache models;
    long long triangles = 0;
    for (std::size_t k = 0; k < list.size(); ++k) {
        const std::string path = fmt::format("mesh[{}]", k);
        const toml::node& node = *list.get(k);
        if (!node.is_table()) {
            c.fail(node.source(), path,
                   fmt::format("expected a table, got {}", type_name(node)));
        }
        const std::size_t before = scene.meshes.size();
        if (node.as_table()->contains("file")) {
            read_model(c, *node.as_table(), path, scene, models, texture_bytes,
                       triangles);
        } else {
            scene.meshes.push_back(read_mesh(c, *node.as_table(), path, scene));
        }
        for (std::size_t m = before; m < scene.meshes.size(); ++m) {
            triangles += static_cast<long long>(scene.meshes[m].triangles.size());
        }
        if (triangles > max_scene_triangles) {
            c.fail(
                node.source(), path,
                fmt::format("the scene has more than {} triangles", max_scene_triangles));
        }
        if (scene.meshes.size() > static_cast<std::size_t>(max_scene_meshes)) {
            c.fail(node.source(), path,
                   fmt::format("the scene has more than {} meshes (each material of a "
                               "model is one)",
                               max_scene_meshes));
        }
    }
    top.finish();
    return scene;
}

Scene load_scene(const std::filesystem::path& path) {
    const std::string text =
        read_input_file(path, "scene", max_scene_file_bytes, InputKind::any);
    return parse_scene(text, path, path.parent_path());
}

std::vector<std::filesystem::path> scene_inputs(const Scene& scene) {
    std::vector<std::filesystem::path> files{scene.file};
    files.insert(files.end(), scene.models.begin(), scene.models.end());
    for (const SceneTexture& texture : scene.textures) {
        if (!texture.file.empty()) {
            files.push_back(texture.file);
        }
    }
    return files;
}

std::filesystem::path shipped_scene_folder() {
    return EXACTPIXELS_SCENES_DIR;
}

std::vector<std::filesystem::path> shipped_scenes() {
    const std::filesystem::path folder = shipped_scene_folder();
    return {folder / "corridor.toml", folder / "horizon.toml",    folder / "gouraud.toml",
            folder / "sprites.toml",  folder / "near_plane.toml", folder / "boxes.toml",
            folder / "lit.toml"};
}

} // namespace exactpixels
