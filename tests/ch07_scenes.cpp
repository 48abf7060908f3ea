// Chapter 7 tests: the shipped scenes render; each mesh runs only the stages it calls
// for; `auto` stays within its budget; the derived bounds and divide counts hold.
#include "exactpixels/base/png.hpp"
#include "exactpixels/scene/depth_buffer.hpp"
#include "exactpixels/scene/gouraud_error.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_pipeline.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "exactpixels/texture/perspective_error.hpp"
#include "exactpixels/texture/quadratic.hpp"
#include "exactpixels/texture/span_mappers.hpp"
#include "exactpixels/texture/texture.hpp"
#include "support/printing.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <unistd.h>

using namespace exactpixels;

namespace {

Scene shipped(const std::string& name) {
    return load_scene(shipped_scene_folder() / (name + ".toml"));
}

Scene with_mapper(Scene scene, MapperKind kind) {
    scene.options.mapper = {false, {kind, 16}};
    return scene;
}

/// A double that counts the divisions done with it.
struct Counted {
    double x = 0.0;
    static inline long long divisions = 0;
    Counted() = default;
    Counted(double v) : x(v) {} // NOLINT: converts like a double
    explicit operator double() const { return x; }
    friend Counted operator+(Counted a, Counted b) { return a.x + b.x; }
    friend Counted operator-(Counted a, Counted b) { return a.x - b.x; }
    friend Counted operator*(Counted a, Counted b) { return a.x * b.x; }
    friend Counted operator/(Counted a, Counted b) {
        ++divisions;
        return a.x / b.x;
    }
    Counted& operator+=(Counted b) { return x += b.x, *this; }
};

} // namespace

TEST_CASE("every shipped scene loads and renders at its size") {
    for (const auto& path : shipped_scenes()) {
        INFO(path.string());
        const Scene scene = load_scene(path);
        const RenderResult result = render_scene(scene);
        CHECK(result.image.width() == scene.width);
        CHECK(result.image.height() == scene.height);
        CHECK(result.report.raster.pixels > scene.width * scene.height / 20);
    }
}

TEST_CASE("a texture's alpha is not drawn: textures are opaque, as is the frame" *
          doctest::description("points: 1; exercise: ch07-plan-mesh")) {
    // A 2 x 2 PNG whose texels are transparent to opaque, drawn 2 pixels a texel over
    // the whole 4 x 4 image (world (-2, 2) is pixel (0, 0)'s corner, uv in texels).
    const std::filesystem::path folder =
        std::filesystem::temp_directory_path() /
        ("exactpixels-alpha-" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    Framebuffer texels(2, 2);
    texels.at(0, 0) = rgba(200, 10, 10, 0);
    texels.at(1, 0) = rgba(10, 200, 10, 1);
    texels.at(0, 1) = rgba(10, 10, 200, 128);
    texels.at(1, 1) = rgba(90, 90, 90, 255);
    write_png(folder / "glass.png", texels);
    for (const std::string filter : {"nearest", "bilinear"}) {
        CAPTURE(filter);
        const Scene scene = parse_scene(fmt::format(R"(
[image]
width = 4
height = 4
background = [1, 1, 1]
[camera]
projection = "orthographic"
view_height = 4
[render]
filter = "{}"
[textures.glass]
kind = "png"
file = "glass.png"
[[mesh]]
primitive = "quad"
texture = "glass"
corners = [[-2, 2, 0], [2, 2, 0], [2, -2, 0], [-2, -2, 0]]
uv = [[0, 0], [2, 0], [2, 2], [0, 2]]
)",
                                                    filter),
                                        "alpha.toml", folder);
        const Framebuffer image = render_scene(scene).image;
        for (int y = 0; y < 4; ++y) {
            for (int x = 0; x < 4; ++x) {
                CAPTURE(x);
                CAPTURE(y);
                const Rgba8 pixel = image.at(x, y);
                CHECK(pixel.a == 255);
                if (filter == "nearest") {
                    const Rgba8 texel = texels.at(x / 2, y / 2);
                    CHECK(pixel == rgba(texel.r, texel.g, texel.b, 255));
                }
            }
        }
    }
    std::filesystem::remove_all(folder);
}

TEST_CASE("a flat orthographic quad covers exactly the pixels whose centres it holds") {
    // 1 world unit = 1 pixel, the image centre at (4, 3): corners (-2, 2) and (2, -1)
    // land on the pixel edges x = 2 .. 6 and y = 1 .. 4.
    const Scene scene = parse_scene(R"(
[image]
width = 8
height = 6
[camera]
projection = "orthographic"
view_height = 6
[[mesh]]
primitive = "quad"
colour = [1, 0, 0]
corners = [[-2, 2, 0], [2, 2, 0], [2, -1, 0], [-2, -1, 0]]
[[mesh]]
primitive = "triangles"
colour = [0, 0, 1]
positions = [[-4, -1, 0], [-2, -1, 0], [-4, -3, 0]]
)",
                                    "mask.toml", ".");
    const RenderResult result = render_scene(scene);
    // The blue triangle's corners land on (0, 4), (2, 4) and (0, 6): its long edge
    // passes through the centres (1.5, 4.5) and (0.5, 5.5), and a centre on a right
    // edge is not covered (top-left rule), so only pixel (0, 4) is blue.
    const char* expected[] = {"........", "..RRRR..", "..RRRR..",
                              "..RRRR..", "B.......", "........"};
    for (int y = 0; y < 6; ++y) {
        for (int x = 0; x < 8; ++x) {
            const char want = expected[y][x];
            const Rgba8 colour = want == 'R'   ? rgba(255, 0, 0)
                                 : want == 'B' ? rgba(0, 0, 255)
                                               : rgba(0, 0, 0);
            INFO("pixel (" << x << ", " << y << ")");
            CHECK(result.image.at(x, y) == colour);
        }
    }
    CHECK(result.report.flat.pixels == 12 + 1);
    CHECK(result.report.texture.pixels == 0);
    CHECK(result.report.divides() == 0);
}

TEST_CASE("the sprite sheet shows each texel as a block of 8 pixels, exactly" *
          doctest::description("points: 1; exercise: ch07-plan-mesh")) {
    const Scene scene = shipped("sprites");
    const RenderResult result = render_scene(scene);
    const Texture f = f_texture(1);
    // Sprite 0 spans world x -120 .. -80, y 70 .. 14: pixels x 8 .. 47, y 10 .. 65.
    for (int y = 10; y < 66; ++y) {
        for (int x = 8; x < 48; ++x) {
            INFO("pixel (" << x << ", " << y << ")");
            CHECK(result.image.at(x, y) == f.texel((x - 8) / 8, (y - 10) / 8));
        }
    }
}

TEST_CASE("without perspective, auto renders as exact and divides nothing") {
    const Scene scene = shipped("sprites");
    const RenderResult automatic = render_scene(scene);
    for (const Precision precision :
         {Precision::float32, Precision::float64, Precision::fixed}) {
        Scene exact = with_mapper(scene, MapperKind::exact);
        exact.options.precision = precision;
        Scene same_auto = scene;
        same_auto.options.precision = precision;
        const RenderResult a = render_scene(same_auto), e = render_scene(exact);
        CHECK(a.image == e.image);
        CHECK(a.report.divides() == 0);
        CHECK(e.report.divides() == e.report.texture.pixels); // one per pixel
    }
    CHECK(automatic.report.mappers[std::size_t(MapperKind::affine)].pixels ==
          automatic.report.texture.pixels);
    CHECK(automatic.report.auto_choice.spans == 0); // constant w: nothing to decide
}

TEST_CASE("a scene without textures runs no texture stage" *
          doctest::description("points: 1; exercise: ch07-plan-mesh")) {
    const RenderResult result = render_scene(shipped("gouraud"));
    CHECK(result.report.texture.triangles == 0);
    CHECK(result.report.texture.pixels == 0);
    CHECK(result.report.divides() == 0);
    CHECK(result.report.colour.pixels > 0);
    CHECK(result.report.flat.pixels > 0); // the flat marker: no colour interpolation
    CHECK(result.report.colour.pixels + result.report.flat.pixels ==
          result.report.raster.pixels);
}

TEST_CASE("geometry in front of the near plane does no clipping work") {
    for (const char* name : {"corridor", "horizon", "gouraud", "sprites", "boxes"}) {
        INFO(name);
        CHECK(render_scene(shipped(name)).report.clipping.triangles == 0);
    }
    const RenderResult near = render_scene(shipped("near_plane"));
    CHECK(near.report.clipping.triangles > 0);
    CHECK(near.report.clipping.triangles < near.report.geometry.triangles);
    // A far plane behind every corner, and corners off screen but inside the guard band
    // (@sec:scene-clipping): still no triangle is cut.
    Scene corridor = shipped("corridor");
    corridor.camera.far = 1e5;
    const RenderResult far = render_scene(corridor);
    CHECK(far.report.clipping.triangles == 0);
    CHECK(far.image == render_scene(shipped("corridor")).image);
    Scene wide = shipped("horizon"); // a narrow view: corners land far off screen
    wide.camera.fov_degrees = 5.0;
    const RenderResult narrow = render_scene(wide);
    CHECK(narrow.report.clipping.triangles == 0);
    RenderReport report;
    double farthest = 0.0; // the farthest corner from the screen, px
    for (const auto& mesh : run_geometry(wide, report).meshes) {
        for (const ScreenTriangle& t : mesh) {
            for (const TexturedVertex& v : t.corners) {
                farthest = std::max({farthest, -v.position.x, v.position.x - wide.width,
                                     -v.position.y, v.position.y - wide.height});
            }
        }
    }
    CHECK(farthest > 1000.0);
    CHECK(farthest < guard_band_px);
}

TEST_CASE("auto scenes stay within their error budget against the exact reference" *
          doctest::description("points: 10; exercise: ch07-choose-mapper")) {
    for (const char* name : {"corridor", "horizon", "near_plane"}) {
        INFO(name);
        const Scene scene = shipped(name);
        const TexelError e = check_against_exact(scene);
        INFO("worst " << e.worst << ", mean " << e.mean);
        CHECK(e.pixels > 1000);
        // The bounds are exact in real arithmetic; double rounding adds far less than
        // 1e-6 texel to coordinates below 2^13.
        CHECK(e.worst <= scene.options.budget + 1e-6);
        // ... and auto is cheaper than exact.
        const long long auto_divides = render_scene(scene).report.divides();
        const long long exact_divides =
            render_scene(with_mapper(scene, MapperKind::exact)).report.divides();
        CHECK(auto_divides < exact_divides);
    }
}

TEST_CASE("a back-culled box draws only the faces turned to the camera") {
    const Scene scene = parse_scene(R"(
[image]
width = 64
height = 48
[camera]
position = [3.0, 2.5, -4.0]
target = [0.0, 0.0, 0.0]
[[mesh]]
primitive = "box"
cull = "back"
centre = [0.0, 0.0, 0.0]
size = [1.0, 2.0, 1.5]
)",
                                    "box.toml", ".");
    const RenderResult result = render_scene(scene);
    int facing = 0; // triangles whose outward normal points at the eye
    for (const auto& t : scene.meshes[0].triangles) {
        const glm::dvec3 centroid = (t[0].position + t[1].position + t[2].position) / 3.0;
        const glm::dvec3 normal =
            glm::cross(t[1].position - t[0].position, t[2].position - t[0].position);
        CHECK(glm::dot(normal, centroid) != 0.0);
        // Outward: the normal points away from the box centre (the origin).
        const glm::dvec3 outward = glm::dot(normal, centroid) > 0 ? normal : -normal;
        facing += glm::dot(outward, scene.camera.position - centroid) > 0.0;
    }
    CHECK(facing == 6); // three faces of a box seen from a corner direction
    CHECK(result.report.culling.triangles == 12 - facing);
    CHECK(result.report.raster.triangles == facing);
}

TEST_CASE("the quadratic bound is never below the true worst quadratic error") {
    for (double r = 1.0 / 64.0; r <= 64.0; r *= 1.07) {
        INFO("r = " << r);
        const double truth = quadratic_error_max(r);
        CHECK(quadratic_error_bound(r) >= truth * (1.0 - 1e-9));
        CHECK(quadratic_error_bound(r) <= 3.1 * truth + 1e-12); // and not loose
    }
}

TEST_CASE("chord and parabola bounds hold on random spans") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> depth(0.5, 50.0), tex(-300.0, 300.0);
    std::uniform_int_distribution<int> length(2, 400);
    for (int trial = 0; trial < 300; ++trial) {
        // A span from depth w0 to w1 over `count` pixels with texel coordinates u0..u1.
        const int count = length(rng);
        const double w0 = depth(rng), w1 = depth(rng), u0 = tex(rng), u1 = tex(rng),
                     v0 = tex(rng), v1 = tex(rng);
        const double n = count - 1;
        const PerspectiveSpan<double> s{u0 / w0,
                                        v0 / w0,
                                        1 / w0,
                                        (u1 / w1 - u0 / w0) / n,
                                        (v1 / w1 - v0 / w0) / n,
                                        (1 / w1 - 1 / w0) / n,
                                        count};
        double chord = 0.0, parabola = 0.0;
        map_span_subdivided(s, count, [&](int k, double u, double v) {
            const UV<double> e = exact_at(s, k);
            chord = std::max({chord, std::abs(u - e.u), std::abs(v - e.v)});
        });
        map_span_quadratic(s, [&](int k, double u, double v) {
            const UV<double> e = exact_at(s, k);
            parabola = std::max({parabola, std::abs(u - e.u), std::abs(v - e.v)});
        });
        CHECK(chord <= chord_error_bound(s, 0, count - 1) + 1e-9);
        CHECK(parabola <= parabola_error_bound(s, 0, count - 1) + 1e-9);
    }
}

TEST_CASE("auto picks the cheapest mapper whose bound is within the budget" *
          doctest::description("points: 7; exercise: ch07-choose-mapper")) {
    // Constant depth along the span: the chord is exact, one piece, four divides.
    const PerspectiveSpan<double> flat{10.0, 5.0, 0.5, 0.25, 0.0, 0.0, 100};
    const AutoChoice c = choose_span_mapper(flat, 0.5);
    CHECK(c.mapper.kind == MapperKind::subdivided);
    CHECK(c.mapper.piece >= 100);
    CHECK(mapper_divides(c.mapper, 100) == 4);
    // A steep span: depth 1 to 40 over 200 pixels, 500 texels. A larger budget never
    // costs more divides, and whatever is chosen is within its budget.
    const PerspectiveSpan<double> steep{
        0.0, 0.0, 1.0, (500.0 / 40.0) / 199.0, 0.0, (1.0 / 40.0 - 1.0) / 199.0, 200};
    long long previous = mapper_divides({MapperKind::exact, 2}, 200) + 1;
    for (const double budget : {0.01, 0.1, 0.5, 2.0, 10.0, 100.0}) {
        INFO("budget " << budget);
        const AutoChoice choice = choose_span_mapper(steep, budget);
        const long long divides = mapper_divides(choice.mapper, 200);
        CHECK(divides <= previous);
        previous = divides;
        double worst = 0.0;
        const auto measure = [&](int k, double u, double v) {
            const UV<double> e = exact_at(steep, k);
            worst = std::max({worst, std::abs(u - e.u), std::abs(v - e.v)});
        };
        switch (choice.mapper.kind) {
        case MapperKind::subdivided:
            map_span_subdivided(steep, choice.mapper.piece, measure);
            break;
        case MapperKind::quadratic:
            map_span_quadratic(steep, measure);
            break;
        default:
            map_span_exact(steep, measure);
        }
        CHECK(worst <= budget + 1e-9);
    }
    CHECK(choose_span_mapper(steep, 0.01).mapper.kind == MapperKind::exact);
    // The chord's bound over the whole span: (sqrt 40 - 1) / (sqrt 40 + 1) * 500 = 363.
    CHECK(choose_span_mapper(steep, 364.0).mapper == Mapper{MapperKind::subdivided, 200});
    CHECK(choose_span_mapper(steep, 362.0).mapper != Mapper{MapperKind::subdivided, 200});
}

TEST_CASE("auto never picks a parabola that turns back inside its span" *
          doctest::description("points: 3; exercise: ch07-choose-mapper")) {
    // Chapter 3's figure 3.3 span: depth ratio 4, 64 texels over 64 pixels. Its parabola
    // is within a generous budget, but dips to -8/15 texel, outside the texels between
    // its ends (@eq:pursey-overshoot); auto takes the next mapper instead.
    const int count = 64;
    const PerspectiveSpan<double> dip{
        0.0, 0.0, 1.0, (64.0 / 4.0) / 63.0, 0.0, (1.0 / 4.0 - 1.0) / 63.0, count};
    double lowest = 0.0;
    map_span_quadratic(dip, [&](int, double u, double) { lowest = std::min(lowest, u); });
    CHECK(lowest < -0.5);
    CHECK(parabola_error_bound(dip, 0, count - 1) <= 100.0);
    CHECK(choose_span_mapper(dip, 100.0).mapper.kind != MapperKind::quadratic);
    // Random spans and budgets: whenever auto picks the parabola, its depth ratio is in
    // [1/3, 3] and every value it hands out lies between its end values.
    std::mt19937 rng(15);
    std::uniform_real_distribution<double> depth(0.5, 50.0), tex(-300.0, 300.0),
        budget(0.05, 50.0);
    std::uniform_int_distribution<int> length(2, 400);
    int parabolas = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        const int n = length(rng) - 1;
        const double w0 = depth(rng), w1 = depth(rng), u0 = tex(rng), u1 = tex(rng);
        const PerspectiveSpan<double> s{
            u0 / w0, 0.0, 1 / w0, (u1 / w1 - u0 / w0) / n, 0.0, (1 / w1 - 1 / w0) / n,
            n + 1};
        if (choose_span_mapper(s, budget(rng)).mapper.kind != MapperKind::quadratic) {
            continue;
        }
        ++parabolas;
        CHECK(pursey_is_monotonic(w1 / w0));
        const double low = std::min(u0, u1), high = std::max(u0, u1);
        const double slack = 1e-9 * (std::abs(u0) + std::abs(u1) + 1.0);
        map_span_quadratic(s, [&](int, double u, double) {
            CHECK(u >= low - slack);
            CHECK(u <= high + slack);
        });
    }
    CHECK(parabolas > 10);
}

TEST_CASE("Gouraud colours are off by the affine error under perspective, and only then" *
          doctest::description("points: 1; exercise: ch07-plan-mesh")) {
    // Orthographic sprites: w = 1 everywhere, screen-linear colours are exact (to the
    // double rounding of stepping a plane, far below 1e-12).
    CHECK(gouraud_perspective_error(shipped("sprites")).worst <= 1e-12);
    const Scene gouraud = shipped("gouraud");
    const auto only = [&](const std::string& name) {
        Scene one = gouraud;
        std::erase_if(one.meshes, [&](const SceneMesh& m) { return m.name != name; });
        REQUIRE(one.meshes.size() == 1);
        return gouraud_perspective_error(one);
    };
    // The fan lies in the plane z = 0, parallel to the screen: constant w, no error.
    const GouraudError fan = only("fan");
    CHECK(fan.pixels > 1000);
    CHECK(fan.worst <= 1e-12);
    // The tilted pair: corners at z from -0.5 to 1.5 seen from z = -5, so w from 4.5 to
    // 6.5 (depth ratio at most 13/9), and no channel changes by more than 0.8 between
    // corners. Chapter 3's affine bound for that span (@eq:affine-bound) caps the error,
    // and the measured error is a sizeable part of it.
    const GouraudError tilted = only("tilted pair");
    const double bound = 0.8 * affine_error_bound(13.0 / 9.0);
    MESSAGE("tilted pair: worst " << tilted.worst << ", bound " << bound);
    CHECK(tilted.pixels > 1000);
    CHECK(tilted.worst <= bound);
    CHECK(tilted.worst > bound / 2);
    // The whole scene: the figure program's table (tbl:gouraud-error) reports this.
    CHECK(gouraud_perspective_error(gouraud).worst == tilted.worst);
}

TEST_CASE("mapper_divides counts every division chapter 3's mappers perform") {
    const PerspectiveSpan<Counted> s{3.0, -2.0, 0.9, 0.01, 0.02, -0.001, 0};
    const auto ignore = [](int, Counted, Counted) {};
    for (const int count : {1, 2, 7, 16, 17, 100}) {
        PerspectiveSpan<Counted> span = s;
        span.count = count;
        const AffineSpan<Counted> affine{1.0, 2.0, 0.5, 0.25, count};
        for (const int n : {2, 5, 16}) {
            INFO("count " << count << ", n " << n);
            const auto counted = [&](auto run) {
                Counted::divisions = 0;
                run();
                return Counted::divisions;
            };
            CHECK(counted([&] { map_span_exact(span, ignore); }) ==
                  mapper_divides({MapperKind::exact, n}, count));
            CHECK(counted([&] { map_span_affine(affine, ignore); }) ==
                  mapper_divides({MapperKind::affine, n}, count));
            CHECK(counted([&] { map_span_subdivided(span, n, ignore); }) ==
                  mapper_divides({MapperKind::subdivided, n}, count));
            CHECK(counted([&] { map_span_quadratic(span, ignore); }) ==
                  mapper_divides({MapperKind::quadratic, n}, count));
            CHECK(counted([&] { map_span_quadratic_subdivided(span, n, ignore); }) ==
                  mapper_divides({MapperKind::quadratic_subdivided, n}, count));
        }
    }
}

TEST_CASE("plan_mesh asks for a stage only when the mesh uses it" *
          doctest::description("points: 1; exercise: ch07-plan-mesh")) {
    SceneMesh bare;
    MeshStages s = plan_mesh(bare);
    CHECK_FALSE(s.texture);
    CHECK_FALSE(s.colour);
    CHECK_FALSE(s.tint);
    SceneMesh textured;
    textured.texture = 0;
    textured.colour = {1.0, 0.5, 1.0};
    s = plan_mesh(textured);
    CHECK(s.texture);
    CHECK_FALSE(s.colour);
    CHECK(s.tint);
    SceneMesh shaded;
    shaded.vertex_colours = true;
    shaded.colour = {0.2, 0.2, 0.2}; // ignored: vertex colours win
    s = plan_mesh(shaded);
    CHECK(s.colour);
    CHECK_FALSE(s.tint);
    CHECK_FALSE(s.texture);
}

TEST_CASE("the chapter's TOML listings are scenes the loader accepts") {
    std::ifstream in(std::string(EXACTPIXELS_SOURCE_DIR) +
                     "/chapters/07-scenes/chapter.md");
    REQUIRE(in);
    std::string line, block;
    bool inside = false;
    int blocks = 0;
    while (std::getline(in, line)) {
        if (!inside && line == "```{.toml}") {
            inside = true;
            block.clear();
        } else if (inside && line == "```") {
            inside = false;
            ++blocks;
            // Model files (`file = "../models/..."`) are found from the shipped scenes.
            const Scene scene = parse_scene(block, "chapter.md", shipped_scene_folder());
            CHECK_FALSE(scene.meshes.empty());
        } else if (inside) {
            block += line + "\n";
        }
    }
    CHECK(blocks >= 1);
}

// ---- The depth stage (@sec:scene-depth) ----

namespace {

/// A camera-facing or tilted quad as a TOML mesh: corners, flat colour.
std::string quad_mesh(const std::string& name, const std::string& corners,
                      const std::string& colour) {
    return "[[mesh]]\nname = \"" + name +
           "\"\nprimitive = \"quad\"\ncorners = " + corners + "\ncolour = " + colour +
           "\n";
}

const std::string depth_header = R"(
[image]
width = 96
height = 72
[camera]
position = [0.0, 0.0, -4.0]
target = [0.0, 0.0, 0.0]
)";

// Two tilted quads that overlap on screen without crossing in space: "near" is nearer
// than "far" everywhere they overlap.
const std::string near_quad = quad_mesh(
    "near", "[[-1.4, -1.0, -0.5], [0.6, -1.0, 0.3], [0.6, 1.0, 0.3], [-1.4, 1.0, -0.5]]",
    "[1.0, 0.2, 0.2]");
const std::string far_quad = quad_mesh(
    "far", "[[-0.6, -1.2, 1.5], [1.5, -1.2, 0.9], [1.5, 0.8, 0.9], [-0.6, 0.8, 1.5]]",
    "[0.2, 0.3, 1.0]");

Scene depth_scene(const std::string& render, const std::string& meshes) {
    return parse_scene(depth_header + render + meshes, "depth.toml", ".");
}

} // namespace

TEST_CASE("two overlapping quads give the same image in either file order") {
    const RenderResult near_first = render_scene(depth_scene("", near_quad + far_quad));
    const RenderResult far_first = render_scene(depth_scene("", far_quad + near_quad));
    CHECK(near_first.report.depth_on);
    CHECK(far_first.report.depth_on);
    CHECK(near_first.image == far_first.image);
    // The reference: painted far to near without a depth stage, the order that is right.
    const RenderResult painted =
        render_scene(depth_scene("[render]\ndepth = false\n", far_quad + near_quad));
    CHECK_FALSE(painted.report.depth_on);
    CHECK(near_first.image == painted.image);
    // Drawn near first, the far quad lost exactly the pixels the near one covers twice.
    const RenderResult wrong =
        render_scene(depth_scene("[render]\ndepth = false\n", near_quad + far_quad));
    long long differ = 0;
    for (std::size_t k = 0; k < wrong.image.pixels().size(); ++k) {
        differ += wrong.image.pixels()[k] != painted.image.pixels()[k];
    }
    CHECK(differ > 100); // the overlap is large: without depth the order matters
    CHECK(near_first.report.hidden.pixels == differ);
    CHECK(far_first.report.hidden.pixels == 0); // near drawn last: nothing fails the test
    // The spans counted (once per triangle, SpanCounts): the depth stage tests every
    // span drawn; a span counts as hidden only where a pixel of it is, and the near
    // quad's never are.
    for (const RenderReport* report : {&near_first.report, &far_first.report}) {
        CHECK(report->depth.spans == report->raster.spans);
        CHECK(report->depth.pixels == report->raster.pixels);
    }
    CHECK(far_first.report.hidden.spans == 0);
    CHECK(near_first.report.hidden.spans > 0);
    CHECK(near_first.report.hidden.spans < near_first.report.depth.spans / 2);
}

// A stub of ch07-plan-mesh (no stage runs) breaks it, so it grades that exercise.
TEST_CASE("a box without back-face culling is drawn correctly by the depth stage" *
          doctest::description("points: 1; exercise: ch07-plan-mesh")) {
    const std::string box = R"(
[image]
width = 80
height = 64
[camera]
position = [3.0, 2.5, -4.0]
target = [0.0, 0.0, 0.0]
[textures.f]
kind = "f"
cell = 2
[[mesh]]
primitive = "box"
texture = "f"
centre = [0.0, 0.0, 0.0]
size = [1.0, 2.0, 1.5]
texels_per_unit = 16
)";
    const Scene culled = parse_scene(box + "cull = \"back\"\n", "box.toml", ".");
    const Scene whole = parse_scene(box, "box.toml", ".");
    const RenderResult reference = render_scene(culled);
    const RenderResult result = render_scene(whole);
    CHECK_FALSE(reference.report.depth_on); // a culled convex mesh cannot overlap itself
    CHECK(result.report.depth_on);          // all twelve faces can
    CHECK(result.report.raster.triangles == 12);
    CHECK(result.report.hidden.pixels > 0);
    CHECK(result.image == reference.image);
    // Without either, the back faces drawn last show through: the image is wrong.
    Scene painted = whole;
    painted.options.depth = DepthMode::off;
    CHECK_FALSE(render_scene(painted).image == reference.image);
}

TEST_CASE("a scene whose meshes cannot overlap runs no depth stage") {
    const std::string apart =
        quad_mesh("left",
                  "[[-1.8, -0.5, 0.0], [-0.8, -0.5, 0.0], [-0.8, 0.5, 0.5], "
                  "[-1.8, 0.5, 0.5]]",
                  "[1, 1, 0]") +
        quad_mesh("right",
                  "[[0.8, -0.5, 0.0], [1.8, -0.5, 1.0], [1.8, 0.5, 1.0], "
                  "[0.8, 0.5, 0.0]]",
                  "[0, 1, 1]");
    const RenderResult result = render_scene(depth_scene("", apart));
    CHECK_FALSE(result.report.depth_on);
    CHECK(result.report.depth.triangles == 0);
    CHECK(result.report.depth.pixels == 0);
    CHECK(format_report(result.report).find("depth stage: off") != std::string::npos);
    const RenderResult forced =
        render_scene(depth_scene("[render]\ndepth = true\n", apart));
    CHECK(forced.report.depth_on);
    CHECK(forced.report.depth.triangles == 4);
    CHECK(forced.report.depth.pixels == forced.report.raster.pixels);
    CHECK(forced.report.hidden.pixels == 0);
    CHECK(forced.image == result.image);
}

TEST_CASE("depth auto leaves the image of every scene laid out in order as it was") {
    // The five scenes of the first sections are laid out so that file order is right
    // (boxes.toml, made to need depth, is tested below).
    for (const char* name : {"corridor", "horizon", "gouraud", "sprites", "near_plane"}) {
        INFO(name);
        Scene scene = shipped(name);
        const RenderResult with_auto = render_scene(scene);
        scene.options.depth = DepthMode::off;
        const RenderResult without = render_scene(scene);
        CHECK(with_auto.image == without.image);
    }
}

TEST_CASE("a depth tie between coplanar triangles goes to the one drawn later") {
    // Camera-facing quads at the same depth: 1/w is the same constant on both, so the
    // keys are exactly equal and every overlapping pixel is a tie.
    const std::string a = quad_mesh(
        "a", "[[-1, -1, 1], [0.5, -1, 1], [0.5, 0.5, 1], [-1, 0.5, 1]]", "[1,0,0]");
    const std::string b = quad_mesh(
        "b", "[[-0.5, -0.5, 1], [1, -0.5, 1], [1, 1, 1], [-0.5, 1, 1]]", "[0,0,1]");
    for (const std::string& order : {a + b, b + a}) {
        const RenderResult tested =
            render_scene(depth_scene("[render]\ndepth = true\n", order));
        const RenderResult painted =
            render_scene(depth_scene("[render]\ndepth = false\n", order));
        CHECK(tested.report.hidden.pixels == 0); // every tie passed the test
        CHECK(tested.image == painted.image);    // later on top, as without depth
    }
}

TEST_CASE("float 1/w resolves the same relative depth near and far") {
    const double near = 0.1;
    for (double w = near; w <= 1e4; w *= 1.37) {
        INFO(w);
        const double e = depth_resolution(w);
        CHECK(e >= std::ldexp(1.0, -25));
        CHECK(e <= 1.01 * std::ldexp(1.0, -23));
        // Depths farther apart than e (relative) always store different keys, nearer
        // one larger; and some pair e apart at most shares a key (the range itself).
        const float q = nearness_key(1.0 / w);
        CHECK(nearness_key(1.0 / (w * (1.0 + 1.01 * e))) < q);
        CHECK(nearness_key(1.0 / (w * (1.0 - 1.01 * e))) > q);
        long long shared = 0;
        for (int k = -8; k <= 8; ++k) {
            shared += nearness_key(1.0 / (w * (1.0 + k * e / 16))) == q;
        }
        CHECK(shared >= 8); // half of a window as wide as e shares the key
        // A 24-bit fixed-point 1/w loses resolution in proportion to the distance.
        const double fixed = fixed_depth_resolution(w, near, 24);
        CHECK(fixed == doctest::Approx(w / near * std::ldexp(1.0, -24)).epsilon(0.01));
    }
    CHECK(fixed_depth_resolution(1e3, near, 24) > 1000.0 * depth_resolution(1e3));
}

TEST_CASE("the depth stage separates parallel quads near and far") {
    for (const double w : {0.2, 3.0, 500.0}) {
        INFO(w);
        const double far_w = w * (1.0 + std::ldexp(1.0, -21));
        const auto at = [](double z, double s) {
            return fmt::format("[[{0}, {0}, {1}], [{2}, {0}, {1}], [{2}, {2}, {1}], "
                               "[{0}, {2}, {1}]]",
                               -s, z, s);
        };
        // The camera at the origin looks along +z; the quads fill most of the image.
        const std::string scene =
            "[image]\nwidth = 48\nheight = 40\n[camera]\nposition = [0, 0, 0]\n"
            "target = [0, 0, 1]\nnear = 0.1\n[render]\ndepth = true\n" +
            quad_mesh("near", at(w, 0.4 * w), "[1, 0, 0]") +
            quad_mesh("far", at(far_w, 0.4 * w), "[0, 0, 1]");
        const RenderResult r = render_scene(parse_scene(scene, "parallel.toml", "."));
        long long red = 0, blue = 0;
        for (const Rgba8 pixel : r.image.pixels()) {
            red += pixel.r == 255;
            blue += pixel.b != 0;
        }
        CHECK(blue == 0); // the far quad shows nowhere
        CHECK(red > 500);
        // Every pixel of the far quad failed the test: all but the near quad's.
        CHECK(r.report.hidden.pixels == r.report.raster.pixels - red);
    }
}

TEST_CASE("the boxes scene looks the same in every order of its meshes") {
    Scene scene = shipped("boxes");
    const RenderResult result = render_scene(scene);
    CHECK(result.report.depth_on);
    CHECK(result.report.hidden.pixels > 0);
    std::sort(scene.meshes.begin(), scene.meshes.end(),
              [](const SceneMesh& a, const SceneMesh& b) { return a.name < b.name; });
    int orders = 0;
    do { // all 24 orders of the four meshes
        INFO(orders);
        CHECK(render_scene(scene).image == result.image);
        ++orders;
    } while (std::next_permutation(
        scene.meshes.begin(), scene.meshes.end(),
        [](const SceneMesh& a, const SceneMesh& b) { return a.name < b.name; }));
    CHECK(orders == 24);
    // Without the depth stage no order is right: the long box passes through the tall
    // one, so each hides part of the other.
    scene.options.depth = DepthMode::off;
    CHECK_FALSE(render_scene(scene).image == result.image);
}

// ---- Perspective-correct vertex colours (@sec:scene-colours) ----

namespace {

/// The largest difference, at the points of a grid of n steps of screen barycentrics,
/// between the screen-linear and the perspective-correct interpolation of each of
/// `values` (its three corner values) over corners at depths w.
double worst_screen_error(const std::array<double, 3>& w,
                          const std::vector<std::array<double, 3>>& values, int n) {
    double worst = 0.0;
    for (int i = 0; i <= n; ++i) {
        for (int j = 0; i + j <= n; ++j) {
            const std::array<double, 3> l{double(i) / n, double(j) / n,
                                          double(n - i - j) / n};
            const double q = l[0] / w[0] + l[1] / w[1] + l[2] / w[2];
            for (const std::array<double, 3>& c : values) {
                const double screen = l[0] * c[0] + l[1] * c[1] + l[2] * c[2];
                const double exact =
                    (l[0] * c[0] / w[0] + l[1] * c[1] / w[1] + l[2] * c[2] / w[2]) / q;
                worst = std::max(worst, std::abs(screen - exact));
            }
        }
    }
    return worst;
}

} // namespace

TEST_CASE("the screen-colour error bound holds on random triangles") {
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> depth(1.0, 30.0), unit(0.0, 1.0);
    double closest = 0.0; // the largest measured / bound seen
    for (int trial = 0; trial < 400; ++trial) {
        const std::array<double, 3> w{depth(rng), depth(rng), depth(rng)};
        std::array<Colour, 3> c{};
        for (Colour& colour : c) {
            colour = {unit(rng), unit(rng), unit(rng)};
        }
        const double bound = colour_error_bound(w, c);
        std::vector<std::array<double, 3>> channels(3);
        for (std::size_t k = 0; k < 3; ++k) {
            channels[k] = {c[0][k], c[1][k], c[2][k]};
        }
        const double worst = 255.0 * worst_screen_error(w, channels, 64);
        CHECK(worst <= bound * (1.0 + 1e-12));
        closest = std::max(closest, worst / bound);
    }
    CHECK(closest > 0.3); // not a loose bound: within a factor of 3.4 somewhere
    CHECK(colour_error_bound({2.0, 2.0, 2.0}, {Colour{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}) ==
          0.0);
}

TEST_CASE("the affine bound over a whole triangle holds on random triangles") {
    std::mt19937_64 rng(34);
    std::uniform_real_distribution<double> ratio(0.0, 6.0), unit(0.0, 1.0),
        texels(-300.0, 300.0);
    double closest = 0.0; // the largest measured / bound seen
    int agree = 0;        // triangle_affine_fits against the bound itself
    for (int trial = 0; trial < 400; ++trial) {
        std::array<TexturedVertex, 3> c{};
        for (TexturedVertex& v : c) { // depth ratios up to e^6 = 403
            v = {{0.0, 0.0}, 0.5 * std::exp(ratio(rng)), {texels(rng), texels(rng)}};
        }
        const double bound = triangle_affine_error_bound(c);
        const double worst = worst_screen_error(
            {c[0].w, c[1].w, c[2].w},
            {{c[0].uv.x, c[1].uv.x, c[2].uv.x}, {c[0].uv.y, c[1].uv.y, c[2].uv.y}}, 96);
        CHECK(worst <= bound * (1.0 + 1e-9) + 1e-9);
        closest = std::max(closest, worst / bound);
        const double budget = bound * (0.5 + unit(rng)); // half to one and a half
        agree += triangle_affine_fits(c, budget) == (bound <= budget);
    }
    CHECK(closest > 0.95); // tight: the grid comes within 5 % of it somewhere
    CHECK(agree == 400);
    // Constant depth: affine is exact, the bound 0 and any budget fits.
    const std::array<TexturedVertex, 3> flat{
        {{{0, 0}, 2.0, {0, 0}}, {{1, 0}, 2.0, {500, 0}}, {{0, 1}, 2.0, {0, 900}}}};
    CHECK(triangle_affine_error_bound(flat) == 0.0);
    CHECK(triangle_affine_fits(flat, 1e-9));
    // An edge from w = 1 to w = 4 over 3 texels: the bound is 3 (2 - 1) / (2 + 1) = 1.
    const std::array<TexturedVertex, 3> edge{
        {{{0, 0}, 1.0, {0, 0}}, {{1, 0}, 4.0, {3, 0}}, {{0, 1}, 1.0, {0, 0}}}};
    CHECK(triangle_affine_error_bound(edge) == 1.0);
    CHECK(triangle_affine_fits(edge, 1.0));
    CHECK(!triangle_affine_fits(edge, 0.999));
}

// Without the texture stage (the stub of ch07-plan-mesh) no mapper runs: it grades that.
TEST_CASE("auto maps a triangle affine whole where its bound fits, per span elsewhere" *
          doctest::description("points: 1; exercise: ch07-plan-mesh")) {
    // The horizon's triangles reach the horizon: none fits, and nothing changes there.
    for (const std::string name : {"corridor", "horizon", "near_plane", "boxes", "lit"}) {
        INFO(name);
        const Scene scene = shipped(name);
        Scene per_span = scene;
        per_span.options.mapper.per_triangle = false;
        const RenderReport now = render_scene(scene).report;
        const RenderReport before = render_scene(per_span).report;
        const auto affine = static_cast<std::size_t>(MapperKind::affine);
        // Per span, affine runs only where the depth is constant (and is not auto's).
        const bool changes = name != "horizon";
        CHECK((now.mappers[affine].pixels > before.mappers[affine].pixels) == changes);
        CHECK((now.divides() < before.divides()) == changes);
        CHECK(now.divides() <= before.divides());
        CHECK(now.texture.pixels == before.texture.pixels);
        // Both within the budget against the exact reference.
        CHECK(check_against_exact(scene).worst <= scene.options.budget + 1e-6);
        CHECK(check_against_exact(per_span).worst <= scene.options.budget + 1e-6);
    }
}

namespace {

// A long triangle from near the camera far into the distance, red near, blue far.
const std::string steep_triangle = R"(
[image]
width = 64
height = 64
[camera]
position = [0.0, 0.0, 0.0]
target = [0.0, 0.0, 1.0]
fov = 60
[[mesh]]
name = "steep"
primitive = "triangles"
positions = [[-1.0, -1.0, 1.0], [1.0, -1.0, 1.0], [0.0, 0.3, 12.0]]
colours = [[1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
)";

/// The colour of the steep triangle at the point a pixel centre sees: the ray from the
/// eye through (px, py) meets the triangle's plane; barycentrics there, in world space.
Colour seen_colour(const Scene& scene, double px, double py) {
    const auto& t = scene.meshes[0].triangles[0];
    const double f =
        0.5 * scene.height / std::tan(scene.camera.fov_degrees * std::acos(-1.0) / 360.0);
    const glm::dvec3 ray{(px - 0.5 * scene.width) / f, -(py - 0.5 * scene.height) / f,
                         1.0};
    const glm::dvec3 a = t[0].position, b = t[1].position, c = t[2].position;
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const glm::dvec3 p = ray * (glm::dot(n, a) / glm::dot(n, ray));
    const double area = glm::length(n);
    const double la = glm::length(glm::cross(b - p, c - p)) / area;
    const double lb = glm::length(glm::cross(c - p, a - p)) / area;
    return la * t[0].colour + lb * t[1].colour + (1.0 - la - lb) * t[2].colour;
}

} // namespace

// A stub of ch07-plan-mesh (no stage runs) breaks it, so it grades that exercise.
TEST_CASE("perspective-correct colours are the colour of the point each pixel sees" *
          doctest::description("points: 1; exercise: ch07-plan-mesh")) {
    Scene scene = parse_scene(steep_triangle + "[render]\ncolours = \"perspective\"\n",
                              "steep.toml", ".");
    const RenderResult corrected = render_scene(scene);
    scene.options.colours = ColourInterpolation::screen;
    const RenderResult screen = render_scene(scene);
    int corrected_worst = 0, screen_worst = 0;
    long long covered = 0;
    for (int y = 0; y < scene.height; ++y) {
        for (int x = 0; x < scene.width; ++x) {
            const Rgba8 got = corrected.image.at(x, y);
            if (got == Rgba8{0, 0, 0, 255}) {
                continue; // background
            }
            ++covered;
            const Rgba8 want = to_rgba8(seen_colour(scene, x + 0.5, y + 0.5));
            const Rgba8 linear = screen.image.at(x, y);
            for (const auto& [a, b] : {std::pair{got.r, want.r}, {got.b, want.b}}) {
                corrected_worst = std::max(corrected_worst, std::abs(int(a) - int(b)));
            }
            for (const auto& [a, b] : {std::pair{linear.r, want.r}, {linear.b, want.b}}) {
                screen_worst = std::max(screen_worst, std::abs(int(a) - int(b)));
            }
        }
    }
    CHECK(covered > 500);
    CHECK(corrected_worst <= 1); // rounding to 8 bits only
    CHECK(screen_worst > 20);    // the uncorrected path is visibly wrong here
    CHECK(corrected.report.colour_perspective.pixels == corrected.report.colour.pixels);
    CHECK(corrected.report.colour_perspective.divides == corrected.report.colour.pixels);
    CHECK(screen.report.colour_perspective.pixels == 0);
}

// A stub of ch07-plan-mesh (no stage runs) breaks it, so it grades that exercise.
TEST_CASE("auto corrects colours only on meshes whose bound exceeds the budget" *
          doctest::description("points: 1; exercise: ch07-plan-mesh")) {
    const Scene scene = parse_scene(steep_triangle + R"(
[[mesh]]
name = "facing"
primitive = "triangles"
positions = [[-0.5, 0.5, 3.0], [0.5, 0.5, 3.0], [0.0, 0.9, 3.0]]
colours = [[0.0, 1.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 1.0]]
[render]
colours = "auto"
)",
                                    "auto.toml", ".");
    const RenderResult result = render_scene(scene);
    CHECK(result.report.colour.triangles == 2);
    CHECK(result.report.colour_perspective.triangles == 1); // the steep one only
    Scene everything = scene;
    everything.options.colours = ColourInterpolation::perspective;
    const RenderResult all = render_scene(everything);
    CHECK(all.report.colour_perspective.triangles == 2);
    // Constant depth: both paths agree, so auto's image is the all-perspective one to
    // within 8-bit rounding of the divide.
    int worst = 0;
    for (std::size_t k = 0; k < all.image.pixels().size(); ++k) {
        const Rgba8 a = all.image.pixels()[k], b = result.image.pixels()[k];
        worst = std::max({worst, std::abs(int(a.r) - int(b.r)),
                          std::abs(int(a.g) - int(b.g)), std::abs(int(a.b) - int(b.b))});
    }
    CHECK(worst <= 1);
}
