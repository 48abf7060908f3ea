// mapper.hpp: which of chapter 3's mappers turns a pixel into a texture coordinate, and
// how its name is spelled (in scene files, reports, tables and benchmark names).
//
// Usage:
//   Mapper m{MapperKind::quadratic_subdivided, 16};
//   mapper_name(m);                                   // "quadratic:16"
//   std::optional<Mapper> p = parse_mapper("subdivided:8");   // {subdivided, 8}
//   mapper_kind_name(MapperKind::quadratic_subdivided);        // "quadratic:N"
//
// The spellings, one for each kind: exact, affine, subdivided:N, quadratic, quadratic:N,
// where N (2 to 4096) is the piece length in pixels; "subdivided" alone means
// subdivided:16. A Mapper's `piece` matters only for the two subdivided kinds.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace exactpixels {

/// Which mapper turns a pixel into a texture coordinate.
enum class MapperKind {
    exact,               ///< u = (u/w) / (1/w) at every pixel
    affine,              ///< u interpolated linearly in screen space
    subdivided,          ///< exact every `piece` pixels, affine in between
    quadratic,           ///< Pursey's parabola over each whole row span
    quadratic_subdivided ///< Pursey's parabola over pieces of `piece` pixels
};

/// The arithmetic of a mapper's inner loop.
enum class Precision {
    float32, ///< float
    float64, ///< double
    fixed    ///< 16.16 texel coordinates in integers, indexed with TexelRounding
};

/// One of chapter 3's mappers: its kind and, for the subdivided kinds, its piece length.
struct Mapper {
    MapperKind kind = MapperKind::exact; ///< which mapper
    int piece = 16; ///< pixels per piece (subdivided kinds), in [2, 4096]
    /// Mappers are equal when kind and piece length are.
    friend bool operator==(const Mapper&, const Mapper&) = default;
};

/// The shortest piece a subdivided mapper takes, pixels.
inline constexpr int min_mapper_piece = 2;
/// The longest piece a subdivided mapper takes, pixels.
inline constexpr int max_mapper_piece = 4096;

/// The mapper's name: "exact", "affine", "subdivided:N", "quadratic", "quadratic:N" with
/// N its piece length. parse_mapper reads it back.
std::string mapper_name(Mapper mapper);

/// The kind's name, with "N" for the piece length: "exact", "affine", "subdivided",
/// "quadratic", "quadratic:N" (what a report shows for all mappers of one kind).
const char* mapper_kind_name(MapperKind kind);

/// The precision's name: "float", "double" or "fixed".
const char* precision_name(Precision precision);

/// Reads a mapper name as mapper_name writes it (and "subdivided" for subdivided:16);
/// nothing when `text` is not one, or its piece length is outside [2, 4096].
std::optional<Mapper> parse_mapper(std::string_view text);

} // namespace exactpixels
