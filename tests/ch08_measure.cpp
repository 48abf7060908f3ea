// Chapter 8 tests, part 4: the measurement. The chapter's claims about which filter is
// closer to the reference are checked here against freshly computed errors, so the text
// cannot state an ordering that the data does not show.
#include "exactpixels/lab/filter_measure.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

using namespace exactpixels;

namespace {

/// Every configuration's error on the scene, by name: on the minified pixels, or on all
/// pixels when `all` is set.
std::map<std::string, double> errors_on(const AccuracyScene& scene, bool all = false) {
    const FilterScene fs = prepare_filter_scene(scene);
    const std::vector<LinearTexel> reference = reference_image(fs);
    const std::vector<bool> minified = all ? std::vector<bool>{} : minified_pixels(fs);
    std::map<std::string, double> e;
    for (const FilterConfig& c : filter_configs()) {
        e[c.name] = rms_code_error(filter_image(fs, c), reference, minified);
        MESSAGE(scene.name << " " << c.name << ": " << e[c.name]);
    }
    return e;
}

} // namespace

TEST_CASE("the reference of a pixel inside one texel is that texel, exactly") {
    // On the facing wall a pixel covers half a texel each way; where its centre is a
    // texel centre (odd columns and rows of the quad) the whole pixel lies in that texel.
    const AccuracyScene wall = wall_facing_scene();
    const FilterScene fs = prepare_filter_scene(wall);
    const std::vector<LinearTexel> reference = reference_image(fs);
    int inside = 0;
    for (std::size_t k = 0; k < fs.pixels.size(); ++k) {
        const TexCoord uv = fs.pixels[k].uv;
        if (uv.x - std::floor(uv.x) == 0.5 && uv.y - std::floor(uv.y) == 0.5) {
            ++inside;
            const int i = static_cast<int>(std::floor(uv.x)) % wall.texture.width();
            const int j = static_cast<int>(std::floor(uv.y)) % wall.texture.height();
            REQUIRE(reference[k] == decode_texel(wall.texture.texel(i, j)));
        }
    }
    CHECK(inside == static_cast<int>(fs.pixels.size()) / 4);
}

TEST_CASE(
    "on the facing wall bilinear matches the reference exactly and nearest does not" *
    doctest::description("points: 1; exercise: ch08-error")) {
    // Two pixels per texel, every other pixel centre on a texel edge: the pixel straddles
    // the edge half and half, which is exactly bilinear's 1/2, 1/2 at the tie.
    const std::map<std::string, double> e = errors_on(wall_facing_scene(), true);
    CHECK(e.at("bilinear") == 0.0);
    CHECK(e.at("trilinear") == 0.0);
    CHECK(e.at("nearest") > 0.0);
}

TEST_CASE("on the horizon the error falls filter by filter, nearest to anisotropic" *
          doctest::description("points: 2; exercise: ch08-error")) {
    const std::map<std::string, double> e = errors_on(horizon_floor_scene());
    CHECK(e.at("bilinear") < e.at("nearest"));
    CHECK(e.at("mip-nearest") < e.at("bilinear"));
    CHECK(e.at("trilinear") < e.at("mip-nearest"));
    CHECK(e.at("anisotropic-4") < e.at("trilinear"));
    CHECK(e.at("anisotropic-16") <= e.at("anisotropic-4"));
    // One level per triangle gives back most of what trilinear gained: its error is
    // nearer bilinear's than trilinear's.
    const double per_triangle = e.at("trilinear per-triangle");
    CHECK(std::abs(per_triangle - e.at("bilinear")) <
          std::abs(per_triangle - e.at("trilinear")));
}

TEST_CASE(
    "on the random field anisotropic beats trilinear, which beats bilinear and nearest" *
    doctest::description("points: 1; exercise: ch08-error")) {
    const std::map<std::string, double> e = errors_on(random_field_scene());
    CHECK(e.at("bilinear") < e.at("nearest"));
    CHECK(e.at("mip-nearest") < e.at("nearest"));
    CHECK(e.at("trilinear") < e.at("bilinear"));
    CHECK(e.at("anisotropic-16") < e.at("trilinear"));
    // Small triangles: the level hardly changes across one, so per-triangle derivatives
    // cost little there (within 10% of per-pixel trilinear).
    CHECK(std::abs(e.at("trilinear per-triangle") - e.at("trilinear")) <
          0.1 * e.at("trilinear"));
}
