// Chapter 8's filters in chapter 7's scene renderer: the `filter` key, what `auto`
// decides per triangle, and what it buys on the horizon scene.
#include "exactpixels/base/error.hpp"
#include "exactpixels/lab/filter_measure.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "exactpixels/scene/supersampled_reference.hpp"
#include "exactpixels/texture/srgb.hpp"
#include "exactpixels/texture/texture.hpp"
#include "support/printing.hpp"

#include <doctest/doctest.h>

#include <string>
#include <vector>

using namespace exactpixels;

namespace {

Scene shipped(const std::string& name) {
    return load_scene(shipped_scene_folder() / (name + ".toml"));
}

} // namespace

TEST_CASE(
    "the filter key defaults to nearest, and nearest is the texel-per-pixel image") {
    for (const auto& path : shipped_scenes()) {
        Scene scene = load_scene(path);
        CHECK(scene.options.filter == SceneFilter::nearest);
        const RenderResult before = render_scene(scene);
        CHECK(before.report.filter.triangles == 0);
        CHECK(before.report.mip_chains == 0);
        scene.options.filter = SceneFilter::bilinear;
        const RenderResult bilinear = render_scene(scene);
        // Textured scenes change under a filter; untextured ones cannot.
        CHECK((bilinear.image == before.image) == (before.report.texture.pixels == 0));
    }
}

// A stub of ch07-plan-mesh (no stage runs) breaks it, so it grades that exercise.
TEST_CASE("auto builds no mip chain where no triangle is minified" *
          doctest::description("points: 2; exercise: ch07-plan-mesh")) {
    // A 16 x 16 texture over an orthographic 240 x 240 square: 15 pixels per texel.
    const std::string text = R"(
[image]
width = 240
height = 240
[camera]
projection = "orthographic"
view_height = 2.0
position = [0.0, 0.0, -4.0]
[render]
filter = "auto"
[textures.checker]
kind = "checkerboard"
size = [16, 16]
square = 4
[[mesh]]
primitive = "triangles"
texture = "checker"
positions = [[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0],
             [-1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0]]
uv = [[0.0, 16.0], [16.0, 16.0], [16.0, 0.0], [0.0, 16.0], [16.0, 0.0], [0.0, 0.0]]
)";
    const Scene scene = parse_scene(text, "magnified.toml", ".");
    const RenderReport r = render_scene(scene).report;
    CHECK(r.filter.triangles == 2);
    CHECK(r.filter_triangles[0] == 2); // bilinear
    CHECK(r.mip_chains == 0);
    CHECK(format_report(r).find("0 mip chains built") != std::string::npos);
    // The horizon, minified towards the top, builds its one chain.
    const RenderReport h = render_scene(shipped("horizon_filtered")).report;
    CHECK(h.mip_chains == 1);
    CHECK(h.filter_triangles[1] + h.filter_triangles[2] > 0);
}

// A stub of ch07-plan-mesh (no stage runs) breaks it, so it grades that exercise.
TEST_CASE("on the horizon auto is closer than nearest to the supersampled reference" *
          doctest::description("points: 2; exercise: ch07-plan-mesh")) {
    const Scene scene = shipped("horizon_filtered");
    const std::vector<LinearTexel> reference = supersampled_reference(scene, 8);
    Scene nearest = scene;
    nearest.options.filter = SceneFilter::nearest;
    const double e_nearest =
        rms_code_error(linear_pixels(render_scene(nearest).image), reference);
    const double e_auto =
        rms_code_error(linear_pixels(render_scene(scene).image), reference);
    MESSAGE("rms error in 8-bit codes: nearest ", e_nearest, ", auto ", e_auto);
    CHECK(e_auto < e_nearest);
}

TEST_CASE("the supersampled reference at one sample per pixel is the nearest render") {
    Scene scene = shipped("horizon_filtered");
    scene.width = 80;
    scene.height = 60;
    const std::vector<LinearTexel> one = supersampled_reference(scene, 1);
    scene.options.filter = SceneFilter::nearest;
    CHECK(one == linear_pixels(render_scene(scene).image));
    CHECK_THROWS_AS(supersampled_reference(scene, 0), Error);
    CHECK_THROWS_AS(supersampled_reference(scene, supersample_max_factor + 1), Error);
    scene.width = max_image_side / 2 + 1;
    CHECK_THROWS_AS(supersampled_reference(scene, 2), Error);
}

// A stub of ch07-plan-mesh (no stage runs) breaks it, so it grades that exercise.
TEST_CASE("the renderer filters 8-bit texels as sRGB codes, in linear light" *
          doctest::description("points: 1; exercise: ch07-plan-mesh")) {
    // Chapter 8's rule, in the renderer: an 8-bit texel is an sRGB code, and filtering
    // averages light. A 64 x 64 checkerboard of 1-texel squares (codes 235 and 40) on a
    // 16 x 16 orthographic square is minified 4 : 1, level 2 exactly, where every texel
    // is the mean of a 4 x 4 block: half the light of each code. Every pixel is that
    // mean encoded once, not the mean of the two codes (137 or 138), which is what
    // averaging the codes as if they were light would give.
    const std::string text = R"(
[image]
width = 16
height = 16
[camera]
projection = "orthographic"
view_height = 2.0
position = [0.0, 0.0, -4.0]
[render]
filter = "trilinear"
[textures.checker]
kind = "checkerboard"
size = [64, 64]
square = 1
[[mesh]]
primitive = "triangles"
texture = "checker"
positions = [[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0],
             [-1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0]]
uv = [[0.0, 64.0], [64.0, 64.0], [64.0, 0.0], [0.0, 64.0], [64.0, 0.0], [0.0, 0.0]]
)";
    const Scene scene = parse_scene(text, "linear_light.toml", ".");
    const RenderResult r = render_scene(scene);
    REQUIRE(r.report.mip_chains == 1);
    const std::uint8_t light_mean =
        linear16_to_srgb(0.5 * (srgb_to_linear16(235) + srgb_to_linear16(40)));
    CHECK(light_mean > 160); // far from the codes' mean, 137.5
    for (const Rgba8 p : r.image.pixels()) {
        CHECK(p.r == light_mean);
        CHECK(p.g == light_mean);
        CHECK(p.b == light_mean);
    }
    // The supersampled reference averages in the same light: the nearest render at 4 x 4
    // samples per pixel hits every texel of the block once.
    for (const LinearTexel& t : supersampled_reference(scene, 4)) {
        CHECK(encode_linear(t).r == light_mean);
    }
}
