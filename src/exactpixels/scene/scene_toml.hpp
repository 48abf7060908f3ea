// scene_toml.hpp: the scene loader's TOML reading helpers, shared by the readers of the
// scene file's sections (scene_sections.hpp). Not for use outside the loader: it
// includes toml++, which only the scene layer links.
//
// Usage (inside a section reader):
//   const TableReader t(c, table, "camera", {"fov", "near"});
//   if (const auto* n = t.find("fov")) {
//       fov = read_positive(c, *n, t.child("fov"), 0, 179);
//   }
//   t.finish(); // an Error for any other key
//
// Every reader throws Error through Context::fail: "FILE:LINE:COLUMN: KEY.PATH: what".
#pragma once

#include "exactpixels/base/error.hpp"
#include "exactpixels/scene/scene.hpp"
#include "exactpixels/scene/scene_loader.hpp"

#include <fmt/format.h>
#include <glm/glm.hpp>
#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace exactpixels::scene_format {

/// World coordinates are kept within +-1e6 units so that every product stays finite.
inline constexpr double world_limit = 1e6;
/// Texture coordinates are kept within +-2^20 texels.
inline constexpr double uv_limit = 1 << 20;

/// A place in a scene's text as toml++ counts it: line, and column in code points (both
/// from 1, the first line starting after a UTF-8 byte-order mark).
using TextPlace = std::pair<toml::source_index, toml::source_index>;

/// Where a message points: the file, and the line and column in it; and the numbers of
/// the scene that the loader read itself (parse_toml), by where they are.
struct Context {
    std::string file;                        ///< the scene's name in messages
    std::filesystem::path folder;            ///< where its textures and models are
    std::string_view text;                   ///< the scene's text
    std::map<TextPlace, double> own_numbers; ///< the loader's readings of tiny numbers

    /// Throws Error "FILE:LINE:COLUMN: PATH: MESSAGE" at the start of `where`.
    [[noreturn]] void fail(const toml::source_region& where, const std::string& path,
                           const std::string& message) const {
        throw Error(fmt::format("{}:{}:{}: {}: {}", file, where.begin.line,
                                where.begin.column, path, message));
    }
};

/// "a table", "an integer", ...: what a TOML value is, for messages.
const char* type_name(const toml::node& node);

//> table-reader
/// One TOML table being read: every key read is recorded, and finish() rejects the
/// keys nobody asked for, naming the allowed ones.
class TableReader {
  public:
    /// Reads `table`, at key path `path`, which may hold only the keys `allowed`.
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
    const Context& context() const { return context_; } ///< where messages point
    const toml::table& table() const { return table_; } ///< the table being read
    const std::string& path() const { return path_; }   ///< its key path

  private:
    const Context& context_;
    const toml::table& table_;
    std::string path_;
    std::vector<std::string> allowed_;
};
//< table-reader

/// The value of a TOML number, exactly; an Error for an integer beyond +-2^53 or a value
/// that is not a number.
double exact_number(const Context& c, const toml::node& node, const std::string& path);
/// A finite number in [lo, hi] (integers are accepted where a float is asked for).
double read_number(const Context& c, const toml::node& node, const std::string& path,
                   double lo, double hi);
/// A number in (lo, hi]: a size, a distance, a budget.
double read_positive(const Context& c, const toml::node& node, const std::string& path,
                     double lo, double hi);
/// A TOML integer in [lo, hi].
int read_integer(const Context& c, const toml::node& node, const std::string& path,
                 int lo, int hi);
/// A TOML string.
std::string read_string(const Context& c, const toml::node& node,
                        const std::string& path);
/// true or false.
bool read_bool(const Context& c, const toml::node& node, const std::string& path);
/// The index in `words` of the string at `node`; an Error listing them for any other.
std::size_t read_choice(const Context& c, const toml::node& node, const std::string& path,
                        const std::vector<std::string>& words);
/// The value named by a string of `words`, whose values are `values` in the same order.
template <class T, std::size_t N>
T read_enum(const Context& c, const toml::node& node, const std::string& path,
            const std::vector<std::string>& words, const std::array<T, N>& values) {
    assert(words.size() == N);
    return values[read_choice(c, node, path, words)];
}
/// A TOML array of min_size to max_size elements.
const toml::array& read_array(const Context& c, const toml::node& node,
                              const std::string& path, std::size_t min_size,
                              std::size_t max_size);
/// A TOML table (a section, a texture, a light, a mesh).
const toml::table& read_table(const Context& c, const toml::node& node,
                              const std::string& path);

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

/// A point of the world: three numbers within +-world_limit.
glm::dvec3 read_point(const Context& c, const toml::node& node, const std::string& path);
/// A colour: three numbers in [0, 1].
Colour read_colour(const Context& c, const toml::node& node, const std::string& path);
/// A direction: three numbers, not all zero, returned as a unit vector.
glm::dvec3 read_direction(const Context& c, const toml::node& node,
                          const std::string& path);

/// Rejects a dotted key of more than max_key_parts parts anywhere in `text`, before the
/// parser (which recurses once per part) sees it.
void check_key_depth(const Context& c, std::string_view text);
/// The scene's TOML document, its tiny numbers read by the loader into c.own_numbers
/// (scene_toml_text.cpp); a syntax error is an Error at its place, key "(syntax)".
toml::table parse_toml(Context& c);

} // namespace exactpixels::scene_format
