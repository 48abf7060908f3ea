#include "exactpixels/texture/mapper.hpp"

#include <charconv>

namespace exactpixels {

std::string mapper_name(Mapper mapper) {
    switch (mapper.kind) {
    case MapperKind::exact:
        return "exact";
    case MapperKind::affine:
        return "affine";
    case MapperKind::subdivided:
        return "subdivided:" + std::to_string(mapper.piece);
    case MapperKind::quadratic:
        return "quadratic";
    case MapperKind::quadratic_subdivided:
        return "quadratic:" + std::to_string(mapper.piece);
    }
    return "?";
}

const char* mapper_kind_name(MapperKind kind) {
    switch (kind) {
    case MapperKind::exact:
        return "exact";
    case MapperKind::affine:
        return "affine";
    case MapperKind::subdivided:
        return "subdivided";
    case MapperKind::quadratic:
        return "quadratic";
    case MapperKind::quadratic_subdivided:
        return "quadratic:N";
    }
    return "?";
}

const char* precision_name(Precision precision) {
    switch (precision) {
    case Precision::float32:
        return "float";
    case Precision::float64:
        return "double";
    case Precision::fixed:
        return "fixed";
    }
    return "?";
}

std::optional<Mapper> parse_mapper(std::string_view text) {
    if (text == "exact") {
        return Mapper{MapperKind::exact};
    }
    if (text == "affine") {
        return Mapper{MapperKind::affine};
    }
    if (text == "quadratic") {
        return Mapper{MapperKind::quadratic};
    }
    if (text == "subdivided") {
        return Mapper{MapperKind::subdivided, 16};
    }
    // "subdivided:N" or "quadratic:N", N decimal digits only.
    const std::size_t colon = text.find(':');
    if (colon == std::string_view::npos) {
        return std::nullopt;
    }
    const std::string_view head = text.substr(0, colon), digits = text.substr(colon + 1);
    const MapperKind kind = head == "subdivided"  ? MapperKind::subdivided
                            : head == "quadratic" ? MapperKind::quadratic_subdivided
                                                  : MapperKind::exact;
    if (kind == MapperKind::exact || digits.empty() || digits.size() > 4) {
        return std::nullopt;
    }
    int piece = 0;
    const auto [end, error] =
        std::from_chars(digits.data(), digits.data() + digits.size(), piece);
    if (error != std::errc{} || end != digits.data() + digits.size() ||
        piece < min_mapper_piece || piece > max_mapper_piece) {
        return std::nullopt;
    }
    return Mapper{kind, piece};
}

} // namespace exactpixels
