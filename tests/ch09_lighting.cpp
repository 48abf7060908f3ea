// Chapter 9 tests of the lighting stage: Lambert and Blinn-Phong give the closed-form
// values the chapter derives; Gouraud and Phong agree where the lit colour is constant;
// computed normals are the surface's own. That it runs only when a scene has lights is
// chapter 7's stage plan (tests/ch07_stage_plan.cpp).
#include "exactpixels/base/png.hpp"
#include "exactpixels/scene/lighting.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "exactpixels/texture/srgb.hpp"
#include "support/printing.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

using namespace exactpixels;

namespace {

/// A 64 x 64 scene of one square facing the camera (its normal is -z), under `lights`,
/// seen by `camera` (TOML lines), with `material` lines added to the square's mesh.
Scene square_scene(const std::string& camera, const std::string& render,
                   const std::string& lights, const std::string& material, double z = 0.0,
                   double half = 1.0) {
    const std::string text = fmt::format(
        "[image]\nwidth = 64\nheight = 64\n[camera]\n{0}\n[render]\n{1}\n{2}\n"
        "[[mesh]]\nprimitive = \"quad\"\n"
        "corners = [[-{4}, -{4}, {3}], [{4}, -{4}, {3}], [{4}, {4}, {3}], [-{4}, {4}, "
        "{3}]]\n"
        "{5}\n",
        camera, render, lights, z, half, material);
    return parse_scene(text, "square.toml", ".");
}

const std::string orthographic = "projection = \"orthographic\"\nview_height = 2";

int worst_difference(const Framebuffer& a, const Framebuffer& b) {
    int worst = 0;
    for (std::size_t k = 0; k < a.pixels().size(); ++k) {
        const Rgba8 p = a.pixels()[k], q = b.pixels()[k];
        for (const int d : {p.r - q.r, p.g - q.g, p.b - q.b}) {
            worst = std::max(worst, std::abs(d));
        }
    }
    return worst;
}

Scene with_shading(Scene scene, Shading shading) {
    scene.options.shading = shading;
    return scene;
}

} // namespace

TEST_CASE("a directional light head-on gives exactly the diffuse colour") {
    const Colour diffuse{153 / 255.0, 51 / 255.0, 204 / 255.0};
    const Scene scene = square_scene(
        orthographic, "", "[[light]]\ntype = \"directional\"\ndirection = [0, 0, 1]",
        "colour = [0.6, 0.2, 0.8]");
    for (const Shading shading : {Shading::gouraud, Shading::phong}) {
        const RenderResult r = render_scene(with_shading(scene, shading));
        CHECK(r.report.lighting_on);
        for (const Rgba8 pixel : r.image.pixels()) {
            REQUIRE(pixel == to_rgba8(diffuse)); // the square covers every pixel
        }
    }
}

TEST_CASE("a light at 60 degrees gives exactly the encoded half of the decoded colour") {
    // Light travelling along (sqrt 3, 0, 1) meets the square's normal (0, 0, -1) at 60
    // degrees; with the double one unit above sqrt 3's nearest, normalising gives z = 1/2
    // exactly, so n.l = cos 60 = 1/2 with no rounding, and every code c must come out as
    // encode(decode(c) / 2) to the byte: the lighting adds nothing of its own to the
    // colour rule. Every code is tried, 86 squares of three channels each.
    for (int first = 0; first < 256; first += 3) {
        const std::array<int, 3> c{first, std::min(first + 1, 255),
                                   std::min(first + 2, 255)};
        const std::string colour = fmt::format("colour = [{}, {}, {}]", c[0] / 255.0,
                                               c[1] / 255.0, c[2] / 255.0);
        const Scene scene = square_scene(
            orthographic, "",
            "[[light]]\ntype = \"directional\"\ndirection = [1.7320508075688774, 0, 1]",
            colour);
        REQUIRE(scene.lights[0].direction.z == 0.5); // the cosine is exact
        for (const Shading shading : {Shading::gouraud, Shading::phong}) {
            const RenderResult r = render_scene(with_shading(scene, shading));
            const Rgba8 pixel = r.image.at(17, 40);
            const std::array<int, 3> got{pixel.r, pixel.g, pixel.b};
            for (std::size_t k = 0; k < 3; ++k) {
                const double half = 0.5 * srgb_decode(c[k] / 255.0);
                INFO("code ", c[k], " shading ", static_cast<int>(shading));
                CHECK(got[k] == std::lround(255.0 * srgb_encode(half)));
            }
        }
    }
}

TEST_CASE("multiplying two codes instead of their light is off by at most 8 codes") {
    // What the colour stage does to a texel under a Gouraud-lit colour (codes times
    // codes), against the colour rule (decode both, multiply, encode), for every pair of
    // codes; the worst pairs are dark, where the sRGB curve is least like a power.
    int worst = 0, worst_bright = 0;
    for (int a = 0; a < 256; ++a) {
        for (int b = 0; b < 256; ++b) {
            const Colour ca{a / 255.0, 0.0, 0.0}, cb{b / 255.0, 0.0, 0.0};
            const int in_codes = to_rgba8(ca * cb).r;
            const int in_light =
                to_rgba8(linear_to_colour(colour_to_linear(ca) * colour_to_linear(cb))).r;
            const int error = std::abs(in_codes - in_light);
            worst = std::max(worst, error);
            if (a >= 128 && b >= 128) {
                worst_bright = std::max(worst_bright, error);
            }
        }
    }
    INFO("worst ", worst, ", both codes 128 or more ", worst_bright);
    CHECK(worst <= 8);
    CHECK(worst > 0); // an approximation, not an identity
    CHECK(worst_bright <= 4);
}

TEST_CASE("a light behind the surface leaves the ambient term only") {
    const Colour diffuse{0.6, 0.2, 0.8}, ambient{0.25, 0.5, 0.75};
    const Scene scene = square_scene(
        orthographic, "ambient = [0.25, 0.5, 0.75]",
        "[[light]]\ntype = \"directional\"\ndirection = [0.3, 0.2, -1]\nintensity = 5\n"
        "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nintensity = 5",
        "colour = [0.6, 0.2, 0.8]\nspecular = [1, 1, 1]\nshininess = 2");
    for (const Shading shading : {Shading::gouraud, Shading::phong}) {
        const RenderResult r = render_scene(with_shading(scene, shading));
        // Both decoded, multiplied in linear light, encoded (@eq:scene-colour-rule).
        const Rgba8 expected = to_rgba8(
            linear_to_colour(colour_to_linear(diffuse) * colour_to_linear(ambient)));
        for (const Rgba8 pixel : r.image.pixels()) {
            REQUIRE(pixel == expected);
        }
    }
}

TEST_CASE("Gouraud equals Phong on a flat plane under a directional light") {
    const std::string light =
        "[[light]]\ntype = \"directional\"\ndirection = [0.4, -0.3, 1]\nintensity = 0.9";
    // Seen in parallel, the eye direction is the same at every point, so even the
    // highlight is constant over the plane.
    const Scene parallel = square_scene(orthographic, "ambient = [0.1, 0.1, 0.1]", light,
                                        "colour = [0.6, 0.2, 0.8]\n"
                                        "specular = [0.5, 0.5, 0.5]\nshininess = 8");
    // In perspective the eye direction varies, so only the diffuse term is constant.
    const Scene pinhole = square_scene("position = [0.5, 0.3, -3]\ntarget = [0, 0, 0]",
                                       "ambient = [0.1, 0.1, 0.1]", light,
                                       "colour = [0.6, 0.2, 0.8]", 0.0, 3.0);
    for (const Scene& scene : {parallel, pinhole}) {
        const RenderResult g = render_scene(with_shading(scene, Shading::gouraud));
        const RenderResult p = render_scene(with_shading(scene, Shading::phong));
        CHECK(g.report.lighting.pixels == 0);
        CHECK(p.report.lighting.pixels == 64 * 64);
        CHECK(worst_difference(g.image, p.image) == 0);
    }
}

TEST_CASE("a point light falls off as its closed form at chosen pixels") {
    // Orthographic, 32 pixels per unit: pixel (i, j) sees the point
    // ((i + 0.5 - 32) / 32, (32 - j - 0.5) / 32, 0) of the square, whose normal is -z.
    const glm::dvec3 light{0.25, -0.1, -0.5};
    const double intensity = 0.1;
    const Scene scene = square_scene(
        orthographic, "shading = \"phong\"",
        "[[light]]\ntype = \"point\"\nposition = [0.25, -0.1, -0.5]\nintensity = 0.1",
        "");
    const RenderResult r = render_scene(scene);
    for (const auto& pixel : {std::pair{40, 35}, std::pair{32, 32}, std::pair{10, 20},
                              std::pair{5, 60}, std::pair{63, 0}}) {
        const int i = pixel.first;
        const int j = pixel.second;
        const glm::dvec3 p{(i + 0.5 - 32) / 32, (32 - j - 0.5) / 32, 0.0};
        const double d = glm::length(light - p);
        const double e = intensity * (-light.z) / (d * d * d); // I cos(theta) / d^2
        // e is linear light on a white surface: the pixel is its encoding.
        const double code = 255 * srgb_encode(e);
        INFO(i, " ", j, " ", code);
        CHECK(std::abs(r.image.at(i, j).g - code) <= 0.5 + 1e-9);
    }
}

TEST_CASE("the specular peak is at the pixel where the half vector equals the normal") {
    // Eye at the origin, the square at z = 2 facing it, f = 32 pixels (90 degrees over
    // 64 pixels). A light from l ~ (a, b, -1) has its mirror direction through the
    // point along (a, b, 1): pixel (32 + 32 a, 32 - 32 b).
    const double a = 8.5 / 32, b = -5.5 / 32;
    const Scene scene = square_scene(
        "fov = 90\nposition = [0, 0, 0]\ntarget = [0, 0, 1]", "shading = \"phong\"",
        fmt::format("[[light]]\ntype = \"directional\"\ndirection = [{}, {}, 1]", -a, -b),
        "colour = [0, 0, 0]\nspecular = [1, 1, 1]\nshininess = 400", 2.0, 8.0);
    const RenderResult r = render_scene(scene);
    int best = -1, at_x = -1, at_y = -1, ties = 0;
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) {
            const int value = r.image.at(x, y).r;
            ties += value == best;
            if (value > best) {
                best = value, at_x = x, at_y = y, ties = 0;
            }
        }
    }
    CHECK(at_x == 40);
    CHECK(at_y == 37);
    CHECK(ties == 0);
    CHECK(best == 255); // n.h = 1 there: the full specular colour
}

TEST_CASE("face normals point out of every face of a box") {
    const Scene scene = parse_scene("[[mesh]]\nprimitive = \"box\"\ncentre = [1, 2, 3]\n"
                                    "size = [1, 2, 0.5]\n",
                                    "box.toml", ".");
    const SceneMesh& box = scene.meshes[0];
    const std::vector<CornerNormals> normals = mesh_normals(box);
    for (std::size_t t = 0; t < box.triangles.size(); ++t) {
        const glm::dvec3 middle =
            (box.triangles[t][0].position + box.triangles[t][1].position +
             box.triangles[t][2].position) /
            3.0;
        // Outward: the normal and the way from the box's centre agree on the face's
        // axis, which is the only nonzero component of the normal.
        const glm::dvec3 out = middle - glm::dvec3{1, 2, 3};
        CHECK(glm::dot(normals[t][0], out) > 0.0);
        CHECK(std::abs(glm::length(normals[t][0]) - 1.0) < 1e-15);
    }
}

TEST_CASE(
    "smooth normals of the shipped torus are within 0.5 degrees of the analytic ones") {
    // lit.toml's torus: axis along y through (0, 0.62, 1), ring radius 1 (make_lit.py).
    const Scene scene = load_scene(shipped_scene_folder() / "lit.toml");
    const auto torus = std::find_if(scene.meshes.begin(), scene.meshes.end(),
                                    [](const SceneMesh& m) { return m.name == "torus"; });
    const bool has_torus = torus != scene.meshes.end();
    REQUIRE(has_torus);
    REQUIRE(torus->normals == NormalSource::smooth);
    const std::vector<CornerNormals> normals = mesh_normals(*torus);
    double worst = 0.0, worst_face = 0.0;
    SceneMesh faceted = *torus;
    faceted.normals = NormalSource::face;
    const std::vector<CornerNormals> faces = mesh_normals(faceted);
    for (std::size_t t = 0; t < normals.size(); ++t) {
        for (std::size_t k = 0; k < 3; ++k) {
            const glm::dvec3 q = torus->triangles[t][k].position - glm::dvec3{0, 0.62, 1};
            const glm::dvec3 ring = glm::normalize(glm::dvec3{q.x, 0.0, q.z});
            const glm::dvec3 exact = glm::normalize(q - ring);
            const auto angle = [&](glm::dvec3 n) {
                return std::acos(std::clamp(glm::dot(n, exact), -1.0, 1.0)) * 180.0 /
                       std::acos(-1.0);
            };
            worst = std::max(worst, angle(normals[t][k]));
            worst_face = std::max(worst_face, angle(faces[t][k]));
        }
    }
    MESSAGE("smooth: ", worst, " degrees; face normals: ", worst_face, " degrees");
    CHECK(worst < 0.5);
    CHECK(worst_face > 5.0); // the face normals are off by about half a grid step
}

TEST_CASE("the lit scene's report shows the lighting stage, its modes and counts") {
    const Scene scene = load_scene(shipped_scene_folder() / "lit.toml");
    const RenderResult r = render_scene(scene);
    CHECK(r.report.lighting_on);
    CHECK(r.report.depth_on);
    CHECK(r.report.lit_vertices == 3 * 12); // the box, lit per vertex: 12 triangles
    CHECK(r.report.lighting.pixels > 0);
    const std::string text = format_report(r.report);
    INFO(text);
    CHECK(text.find("lighting stage: on (2 lights; phong 2 meshes, gouraud 1 mesh)") !=
          std::string::npos);
}

TEST_CASE("a point light at the lit point brings no light and no infinity") {
    const ViewLight light{LightType::point, {}, {1.0, 2.0, 3.0}, {1.0, 1.0, 1.0}};
    const Incident in = incident(light, {1.0, 2.0, 3.0});
    CHECK(in.towards == glm::dvec3{0.0, 0.0, 0.0});
    CHECK(in.irradiance.r == 1.0 / (min_light_distance * min_light_distance));
    const Colour c = light_colour({light}, {0.1, 0.2, 0.3}, {1.0, 1.0, 1.0},
                                  Material{{1.0, 1.0, 1.0}, 8.0}, {1.0, 2.0, 3.0},
                                  {0.0, 0.0, -1.0}, {0.0, 0.0, -1.0});
    CHECK(c == Colour{0.1, 0.2, 0.3}); // the ambient term only
}

TEST_CASE("normals given per vertex are the ones lit") {
    const std::string light =
        "[[light]]\ntype = \"directional\"\ndirection = [0.3, -0.4, 1]";
    const Scene face = square_scene(orthographic, "", light, "colour = [0.6, 0.2, 0.8]");
    // The face's own normal, given at each corner (any length): the same picture.
    const Scene given =
        square_scene(orthographic, "", light,
                     "colour = [0.6, 0.2, 0.8]\nnormals = [[0, 0, -2], [0, 0, -2], "
                     "[0, 0, -2], [0, 0, -2]]");
    REQUIRE(given.meshes[0].normals == NormalSource::given);
    CHECK(mesh_normals(given.meshes[0])[0][0] == glm::dvec3{0.0, 0.0, -1.0});
    // Normals turned towards the light: every pixel brighter than the face's.
    const Scene turned =
        square_scene(orthographic, "", light,
                     "colour = [0.6, 0.2, 0.8]\nnormals = [[-0.3, 0.4, -1], "
                     "[-0.3, 0.4, -1], [-0.3, 0.4, -1], [-0.3, 0.4, -1]]");
    for (const Shading shading : {Shading::gouraud, Shading::phong}) {
        const Framebuffer a = render_scene(with_shading(face, shading)).image;
        const Framebuffer b = render_scene(with_shading(given, shading)).image;
        const Framebuffer c = render_scene(with_shading(turned, shading)).image;
        CHECK(a == b);
        CHECK(c.at(10, 10).r > a.at(10, 10).r);
        CHECK(c.at(10, 10) == to_rgba8(Colour{0.6, 0.2, 0.8})); // n = l: head-on
    }
}

TEST_CASE("a back-culled triangle is not lit per vertex") {
    // A box seen from outside: the faces turned away are culled before the lighting
    // stage, so Gouraud lights exactly the corners of the triangles that are drawn.
    const Scene scene = parse_scene(
        "[image]\nwidth = 64\nheight = 64\n[camera]\nposition = [2, 1.5, -3]\n"
        "target = [0, 0, 0]\n[[light]]\ntype = \"directional\"\ndirection = [1, -1, 2]\n"
        "[[mesh]]\nprimitive = \"box\"\ncentre = [0, 0, 0]\nsize = [1, 1, 1]\n"
        "shading = \"gouraud\"\ncull = \"back\"\n",
        "box.toml", ".");
    RenderReport report;
    const SceneGeometry geometry = run_geometry(scene, report);
    REQUIRE(geometry.meshes.size() == 1);
    const auto drawn = static_cast<long long>(geometry.meshes[0].size());
    CHECK(report.geometry.triangles == 12);
    CHECK(report.culling.triangles == 12 - drawn);
    CHECK(drawn == 6); // three faces of a box are seen from a corner's direction
    CHECK(report.lit_vertices == 3 * drawn);
    CHECK(render_scene(scene).report.lit_vertices == 3 * drawn);
}
