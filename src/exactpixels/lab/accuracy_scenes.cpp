#include "exactpixels/lab/accuracy_scenes.hpp"

#include "exactpixels/base/split_mix.hpp"
#include "exactpixels/texture/perspective.hpp"
#include "exactpixels/texture/rounding.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace exactpixels {

namespace {

std::vector<std::array<TexturedVertex, 3>> quad(TexturedVertex a, TexturedVertex b,
                                                TexturedVertex c, TexturedVertex d) {
    return {{a, b, c}, {a, c, d}};
}

} // namespace

//> wall-facing
AccuracyScene wall_facing_scene() {
    // Corners on pixel centres, w = 2 everywhere; u = (304.5 - x) / 2 runs right to
    // left and v = (y - 16.5) / 2 downwards, so both are whole numbers at every other
    // pixel centre: exact ties that only the rounding rule decides.
    const auto corner = [](double x, double y) {
        return TexturedVertex{{x, y}, 2.0, {(304.5 - x) / 2.0, (y - 16.5) / 2.0}};
    };
    return {"wall", 320, 240,
            quad(corner(16.5, 16.5), corner(304.5, 16.5), corner(304.5, 224.5),
                 corner(16.5, 224.5)),
            checkerboard_texture(64, 64, 8)};
}
//< wall-facing

AccuracyScene grazing_floor_scene() {
    constexpr int width = 320, height = 240;
    const Pinhole eye{0.625 * width, {0.5 * width, 0.5 * height}};
    const double roll = 80.0 * std::numbers::pi / 180.0; // the camera is rolled
    constexpr double near = 1.0, far = 28.0, half_width = 6.0, texels_per_unit = 1.0;
    const auto corner = [&](double x, double z) { // a floor point one unit below the eye
        const double y = -1.0;
        const glm::dvec3 view{x * std::cos(roll) - y * std::sin(roll),
                              x * std::sin(roll) + y * std::cos(roll), z};
        return project(eye, view,
                       {(x + half_width) * texels_per_unit, (far - z) * texels_per_unit});
    };
    return {"floor", width, height,
            quad(corner(-half_width, near), corner(half_width, near),
                 corner(half_width, far), corner(-half_width, far)),
            checkerboard_texture(16, 16, 1)};
}

AccuracyScene random_field_scene() {
    constexpr int width = 320, height = 240;
    SplitMix random(20240605);
    AccuracyScene scene{"field", width, height, {}, f_texture(4)};
    for (const double size : {4.0, 16.0, 64.0}) {
        for (int n = 0; n < 20; ++n) {
            const Point2 centre{random.uniform(0.0, width), random.uniform(0.0, height)};
            const double scale = random.uniform(0.25, 2.0); // texels per pixel
            const TexCoord offset{random.uniform(0.0, 64.0), random.uniform(0.0, 64.0)};
            std::array<TexturedVertex, 3> t{};
            for (TexturedVertex& v : t) {
                const Point2 d{random.uniform(-0.5, 0.5) * size,
                               random.uniform(-0.5, 0.5) * size};
                v = {centre + d, random.uniform(1.0, 8.0), offset + scale * d};
            }
            scene.triangles.push_back(t);
        }
    }
    return scene;
}

std::vector<AccuracyScene> accuracy_scenes() {
    return {wall_facing_scene(), grazing_floor_scene(), random_field_scene()};
}

//> accuracy-mappers
std::vector<MapperConfig> accuracy_mappers() {
    using K = MapperKind;
    using P = Precision;
    // Each configuration is named by its mapper's one spelling and its precision
    // ("quadratic:16 fixed"), with " +rule" when chapter 4's rule is chosen.
    const auto m = [](K kind, P precision, int span = 16, bool choose = false) {
        const MapperSettings settings{{kind, span}, precision, {}, Wrap::repeat};
        const std::string name =
            mapper_name(settings.mapper) + " " + precision_name(precision);
        return MapperConfig{choose ? name + " +rule" : name, settings, choose};
    };
    std::vector<MapperConfig> list = {
        m(K::affine, P::fixed), // the baseline of every time ratio
        m(K::affine, P::float32),
        m(K::affine, P::float64),
    };
    for (const int n : {4, 8, 16, 32}) {
        list.push_back(m(K::subdivided, P::float32, n));
        list.push_back(m(K::subdivided, P::fixed, n));
    }
    list.push_back(m(K::quadratic, P::float32));
    list.push_back(m(K::quadratic, P::float64));
    list.push_back(m(K::quadratic, P::fixed));
    for (const int n : {8, 16}) {
        list.push_back(m(K::quadratic_subdivided, P::float32, n));
        list.push_back(m(K::quadratic_subdivided, P::fixed, n));
    }
    list.push_back(m(K::exact, P::float32));
    list.push_back(m(K::exact, P::float64));
    list.push_back(m(K::exact, P::fixed));
    // Five of them again with chapter 4's rule chosen per triangle: four 16.16 loops and
    // the exact mapper in double.
    list.push_back(m(K::affine, P::fixed, 16, true));
    list.push_back(m(K::subdivided, P::fixed, 16, true));
    list.push_back(m(K::quadratic_subdivided, P::fixed, 16, true));
    list.push_back(m(K::exact, P::float64, 16, true));
    list.push_back(m(K::exact, P::fixed, 16, true));
    return list;
}
//< accuracy-mappers

MapperConfig reference_mapper() {
    return {
        "reference", {{MapperKind::exact}, Precision::float64, {}, Wrap::repeat}, true};
}

MapperSettings settings_for(const MapperConfig& mapper,
                            const std::array<TexturedVertex, 3>& triangle) {
    MapperSettings s = mapper.settings;
    if (mapper.choose_rounding) {
        s.rounding = choose_rounding(triangle, s.mapper.kind);
    }
    return s;
}

void draw_with(Framebuffer& frame, const AccuracyScene& scene,
               const MapperConfig& mapper) {
    for (const auto& triangle : scene.triangles) {
        draw_textured_triangle(frame, triangle, scene.texture,
                               settings_for(mapper, triangle));
    }
}

void map_with(TexelMap& map, const AccuracyScene& scene, const MapperConfig& mapper) {
    for (const auto& triangle : scene.triangles) {
        map_textured_triangle(map, triangle, settings_for(mapper, triangle));
    }
}

TexelError measure_mapper_error(const AccuracyScene& scene, const MapperConfig& mapper) {
    TexelMap reference(scene.width, scene.height), candidate(scene.width, scene.height);
    map_with(reference, scene, reference_mapper());
    map_with(candidate, scene, mapper);
    return compare_texel_maps(reference, candidate);
}

} // namespace exactpixels
