// section_render.cpp: a scene's [render]: the options that apply to every mesh.
#include "exactpixels/scene/scene_sections.hpp"

namespace exactpixels::scene_format {

namespace {

/// A mapper's name: "auto", or one parse_mapper knows.
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
            c.fail(
                node.source(), path,
                fmt::format("'{}': the piece length after '{}' must be a whole number of "
                            "pixels from {} to {}",
                            word, prefix, min_mapper_piece, max_mapper_piece));
        }
    }
    c.fail(node.source(), path,
           fmt::format("'{}' is not a mapper (allowed: auto, exact, affine, "
                       "quadratic, subdivided:N, quadratic:N)",
                       word));
}

} // namespace

void read_render(const Context& c, const toml::table& table, RenderOptions& options) {
    const TableReader t(c, table, "render",
                        {"precision", "mapper", "budget", "rounding", "depth", "colours",
                         "filter", "shading", "ambient"});
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

} // namespace exactpixels::scene_format
