// Chapter 7 tests: numbers that get through the scene format's checks must not crash the
// loader or poison the pixels. Every TOML number is read exactly or rejected; a deeply
// dotted key is refused before the parser can recurse on it; NaN and infinity are stopped
// before the first pixel in every precision, and --check counts them as failures.
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/exact.hpp"
#include "exactpixels/scene/mesh_transform.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <string>
#include <string_view>

using namespace exactpixels;

namespace {

/// A camera at the origin looking along +z with its near plane at `near`, and a textured
/// triangle with a corner on the view axis at depth `axis_depth` (as the scene writes
/// it).
std::string axis_scene(double near, std::string_view axis_depth, const char* precision,
                       const char* mapper) {
    return fmt::format("[image]\nwidth = 64\nheight = 48\n"
                       "[camera]\nposition = [0, 0, 0]\ntarget = [0, 0, 1]\nnear = {}\n"
                       "[render]\nprecision = \"{}\"\nmapper = \"{}\"\n"
                       "[textures.c]\nkind = \"checkerboard\"\nsize = [64, 64]\n"
                       "square = 8\n"
                       "[[mesh]]\nprimitive = \"triangles\"\ntexture = \"c\"\n"
                       "positions = [[0, 0, {}], [-2, -1, 3], [2, -1, 3]]\n"
                       "uv = [[0, 0], [64, 0], [0, 64]]\n",
                       near, precision, mapper, axis_depth);
}

std::string axis_scene(double near, double axis_depth, const char* precision,
                       const char* mapper) {
    return axis_scene(near, fmt::format("{}", axis_depth), precision, mapper);
}

} // namespace

TEST_CASE("a deeply dotted key is refused before the parser sees it") {
    std::string deep = "a";
    for (int k = 0; k < 100000; ++k) {
        deep += ".a";
    }
    CHECK_THROWS_WITH_AS(
        parse_scene(deep + " = 1\n", "d.toml", "."),
        doctest::Contains("d.toml:1: a dotted key has more than 64 parts"), Error);
    CHECK_THROWS_WITH_AS(parse_scene("[" + deep + "]\n", "d.toml", "."),
                         doctest::Contains("more than 64 parts"), Error);
    // Dots in strings, comments and floats on one line do not add up. (A key of 64 parts
    // and one of 65, and the integers a double cannot hold, are files of
    // tests/fixtures/bad_scenes.)
    const std::string dots(1000, '.');
    CHECK_NOTHROW(parse_scene("# " + dots + "\n[[mesh]]\nname = \"" + dots +
                                  "\"\nprimitive = \"quad\"\ncorners = [[0.5, 0.5, "
                                  "1.5], [1.5, 0.5, 1.5], [1.5, 1.5, 1.5], [0.5, 1.5, "
                                  "1.5]]\n",
                              "d.toml", "."));
}

// A stub of ch07-plan-mesh (no stage runs) breaks it, so it grades that exercise.
TEST_CASE("the smallest near plane with a corner on the view axis gives finite texels" *
          doctest::description("points: 1; exercise: ch07-plan-mesh")) {
    CHECK_THROWS_WITH_AS(
        parse_scene(axis_scene(min_camera_near / 2, 1.0, "double", "exact"), "n.toml",
                    "."),
        doctest::Contains("camera.near"), Error);
    for (const char* precision : {"float", "double", "fixed"}) {
        for (const char* mapper : {"exact", "auto", "affine"}) {
            for (const double depth : {min_camera_near, 1e-310}) { // on the plane, behind
                CAPTURE(precision);
                CAPTURE(mapper);
                CAPTURE(depth);
                const Scene scene = parse_scene(
                    axis_scene(min_camera_near, depth, precision, mapper), "n.toml", ".");
                const TexelError e = check_against_exact(scene);
                CHECK(e.not_finite == 0);
                CHECK(std::isfinite(e.worst));
                CHECK(std::isfinite(e.mean));
            }
        }
    }
    const TexelError on_plane = check_against_exact(parse_scene(
        axis_scene(min_camera_near, min_camera_near, "float", "exact"), "n.toml", "."));
    CHECK(on_plane.pixels > 0);
}

TEST_CASE("a scene number below the least normal double reads as the nearest on every "
          "library") {
    // libc++'s streams, through which toml++ reads a float, refused the tiny ones: the
    // loader reads them itself. Each is checked against its exact value.
    const Integer ten = 10;
    const struct {
        const char* written;
        Rational value;
    } numbers[] = {
        {"1e-320", Rational(1, pow(ten, 320))},
        {"1e-310", Rational(1, pow(ten, 310))},
        {"-1_0e-321", Rational(-1, pow(ten, 320))},
        {"+0.000_3e-310", Rational(3, pow(ten, 314))},
        {"4.9e-324", Rational(49, pow(ten, 325))}, // nearest: 2^-1074, the least double
        // Just above and just below half of 2^-1074: 2^-1074 and 0.
        {"2.4703282292062328e-324", Rational(24703282292062328, pow(ten, 340))},
        {"2.4703282292062327e-324", Rational(24703282292062327, pow(ten, 340))},
        {"2.2250738585072011e-308",
         Rational(22250738585072011, pow(ten, 324))}, // < 2^-1022
        {"1e-400",
         Rational(1, pow(ten, 400))}, // 0, as toml++ read it through GCC's library
        {"-1e-400", Rational(-1, pow(ten, 400))},
        {"0.1", Rational(1, 10)},
    };
    for (const auto& number : numbers) {
        const std::string written = number.written;
        CAPTURE(written);
        const Scene scene =
            parse_scene(axis_scene(min_camera_near, number.written, "double", "exact"),
                        "n.toml", ".");
        const double read = scene.meshes[0].triangles[0][0].position.z;
        const Rational error = abs(exact(read) - number.value);
        for (const double towards : {-1.0, 1.0}) {
            CHECK(error <= abs(exact(std::nextafter(read, towards)) - number.value));
        }
    }
    // Columns count code points, from after a byte-order mark.
    const Scene utf8 = parse_scene(
        "\xEF\xBB\xBFmesh = [{ name = \"\xC3\xA9t\xC3\xA9\", primitive = \"triangles\", "
        "texture = \"c\", positions = [[0, 0, 1e-320], [-2, -1, 3], [2, -1, 3]], "
        "uv = [[0, 0], [64, 0], [0, 64]] }]\n[textures.c]\nkind = \"checkerboard\"\n"
        "size = [64, 64]\nsquare = 8\n",
        "u.toml", ".");
    CHECK(utf8.meshes[0].triangles[0][0].position.z == 1e-320);
    // A number in a key's place, a syntax error after a tiny number and a number beyond
    // the doubles are refused as the files
    // tests/fixtures/bad_scenes/tiny_number_as_*.toml,
    // syntax_error_after_tiny_number.toml and number_beyond_doubles.toml show.
}

TEST_CASE("NaN and infinity are stopped before the first pixel in every precision") {
    // Past the loader's limits (a scene built in code): a near plane and a corner so
    // close to the eye that 1/w overflows.
    for (const char* precision : {"float", "double", "fixed"}) {
        CAPTURE(precision);
        Scene scene = parse_scene(axis_scene(min_camera_near, 1.0, precision, "exact"),
                                  "n.toml", ".");
        scene.camera.near = 1e-320;
        scene.meshes[0].triangles[0][0].position.z = 1e-310;
        share_positions(scene.meshes[0]); // the index follows the moved corner
        TexelMap map(scene.width, scene.height);
        CHECK_THROWS_WITH_AS(render_scene(scene, &map), doctest::Contains("not finite"),
                             Error);
        long long covered = 0;
        for (const bool c : map.covered) {
            covered += c;
        }
        CHECK(covered == 0);
    }
}

TEST_CASE(
    "--check counts non-finite texel coordinates as failures, apart from the error") {
    TexelMap map(2, 1), reference(2, 1);
    for (TexelMap* m : {&map, &reference}) {
        m->covered = {true, true};
        m->u = {1.0, 2.0};
        m->v = {1.0, 2.0};
    }
    map.u[0] = 1.25;
    CHECK(compare_texel_maps(reference, map).not_finite == 0);
    map.u[1] = std::numeric_limits<double>::quiet_NaN();
    const TexelError e = compare_texel_maps(reference, map);
    CHECK(e.not_finite == 1);
    CHECK(e.worst == 0.25); // the NaN neither hides in the max nor poisons the mean
    CHECK(e.mean == 0.25);
    CHECK(e.pixels == 1);
}
