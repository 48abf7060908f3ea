// scene_toml.cpp: the value readers of scene_toml.hpp. Each checks one TOML value's type,
// exactness and range, and names its place and key path when it refuses it.
#include "exactpixels/scene/scene_toml.hpp"

#include <cmath>

namespace exactpixels::scene_format {

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

glm::dvec3 read_point(const Context& c, const toml::node& node, const std::string& path) {
    return read_vector<3>(c, node, path, -world_limit, world_limit);
}

Colour read_colour(const Context& c, const toml::node& node, const std::string& path) {
    return read_vector<3>(c, node, path, 0.0, 1.0);
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

const toml::table& read_table(const Context& c, const toml::node& node,
                              const std::string& path) {
    if (!node.is_table()) {
        c.fail(node.source(), path,
               fmt::format("expected a table, got {}", type_name(node)));
    }
    return *node.as_table();
}

} // namespace exactpixels::scene_format
