// Chapter 9 tests: Wavefront OBJ models (@sec:scene-models). A model is read with its
// MTL materials, its polygons cut into fans, placed by its transform; every malformed
// model is an Error naming the model's file, line and value, and the CLI exits with 2
// and writes nothing.
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/input_file.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/lab/model_generator.hpp"
#include "exactpixels/scene/lighting.hpp"
#include "exactpixels/scene/mesh_transform.hpp"
#include "exactpixels/scene/obj_model.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "support/printing.hpp"
#include "support/process.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <unistd.h>
#include <vector>

using namespace exactpixels;
namespace fs = std::filesystem;

namespace {

const fs::path models = fs::path(EXACTPIXELS_SOURCE_DIR) / "tests/fixtures/models";

/// A small scene that draws the fixture cube, seen from above, right and in front.
std::string cube_scene(const std::string& mesh_extra) {
    return "[image]\nwidth = 48\nheight = 40\n"
           "[camera]\nposition = [1.6, 1.3, -2.6]\ntarget = [0, 0, 0]\n"
           "[render]\ndepth = true\n"
           "[[mesh]]\nfile = \"cube.obj\"\n" +
           mesh_extra;
}

double triangle_area(const std::array<SceneVertex, 3>& t) {
    return 0.5 * glm::length(glm::cross(t[1].position - t[0].position,
                                        t[2].position - t[0].position));
}

} // namespace

TEST_CASE("an OBJ cube of quads loads as 12 triangles in its two materials") {
    long long texture_bytes = 0;
    const Model cube = read_obj_model(models / "cube.obj", texture_bytes);
    REQUIRE(cube.parts.size() == 2);
    CHECK(cube.parts[0].material == "labelled");
    CHECK(cube.parts[0].triangles.size() == 2);
    REQUIRE(cube.parts[0].texture.has_value());
    CHECK(texture_bytes == 4LL * cube.parts[0].texture->texture.width() *
                               cube.parts[0].texture->texture.height());
    CHECK(cube.parts[1].material == "plain");
    CHECK(cube.parts[1].triangles.size() == 10);
    CHECK(cube.parts[1].colour == Colour{0.9, 0.5, 0.2});
    CHECK_FALSE(cube.parts[1].texture.has_value());
    CHECK(cube.normals);
    // The front face (z = +0.5 in the file) comes out at z = -0.5, facing the default
    // camera, its normal -z; its texture coordinates turned into texels, v flipped.
    const auto& front = cube.parts[0].triangles[0];
    const double w = cube.parts[0].texture->texture.width();
    const double h = cube.parts[0].texture->texture.height();
    CHECK(front[0].position == glm::dvec3{-0.5, -0.5, -0.5});
    CHECK(front[0].normal == glm::dvec3{0.0, 0.0, -1.0});
    CHECK(front[0].uv == TexCoord{0.0, h});
    CHECK(front[2].uv == TexCoord{w, 0.0});
}

TEST_CASE("a convex polygon becomes a fan from its first corner that covers its area") {
    long long texture_bytes = 0;
    const Model pentagon = read_obj_model(models / "pentagon.obj", texture_bytes);
    REQUIRE(pentagon.parts.size() == 1);
    const auto& triangles = pentagon.parts[0].triangles;
    REQUIRE(triangles.size() == 3);
    double area = 0.0;
    for (const auto& t : triangles) {
        CHECK(t[0].position == triangles[0][0].position); // all share corner 1
        area += triangle_area(t);
    }
    // The fixture's corners are a unit-circle pentagon to 6 decimals: area 5/2 sin 72.
    CHECK(area ==
          doctest::Approx(2.5 * std::sin(2 * std::numbers::pi / 5)).epsilon(1e-6));
    CHECK_FALSE(pentagon.normals);
    CHECK(texture_bytes == 0);
}

TEST_CASE("a transform scales, then turns about x, y and z, then translates") {
    MeshTransform t;
    t.scale = {2.0, 3.0, 4.0};
    t.rotate_degrees = {90.0, 90.0, 0.0};
    t.translate = {1.0, 1.0, 1.0};
    // (1, 2, 3) scaled is (2, 6, 12); about x by 90 degrees (+y to +z) it is
    // (2, -12, 6); about y (+z to +x) it is (6, -12, -2); moved, (7, -11, -1). Whole
    // quarter turns are exact, so the comparison is too.
    CHECK(transform_point(t, {1.0, 2.0, 3.0}) == glm::dvec3{7.0, -11.0, -1.0});
    // About z, +x turns towards +y.
    t = {};
    t.rotate_degrees = {0.0, 0.0, 90.0};
    CHECK(transform_point(t, {1.0, 0.0, 0.0}) == glm::dvec3{0.0, 1.0, 0.0});
    // Any angle: the rotation keeps lengths (orthonormal columns, determinant 1).
    const glm::dmat3 r = rotation_matrix({17.0, -123.0, 301.5});
    CHECK(std::abs(glm::determinant(r) - 1.0) < 1e-15);
    const glm::dmat3 identity = glm::transpose(r) * r;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            CHECK(std::abs(identity[i][j] - (i == j ? 1.0 : 0.0)) < 1e-15);
        }
    }
}

TEST_CASE("normals stay perpendicular to their surface under a non-uniform scale") {
    SceneMesh mesh;
    const glm::dvec3 a{0, 0, 0}, b{1, 0, 1}, c{0, 1, 0};
    const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
    mesh.triangles.push_back({SceneVertex{a, {}, {1, 1, 1}, n},
                              SceneVertex{b, {}, {1, 1, 1}, n},
                              SceneVertex{c, {}, {1, 1, 1}, n}});
    MeshTransform t;
    t.scale = {1.0, 4.0, 0.25};
    t.rotate_degrees = {30.0, -40.0, 75.0};
    transform_mesh(mesh, t);
    const auto& moved = mesh.triangles[0];
    const glm::dvec3 normal = moved[0].normal;
    CHECK(std::abs(glm::length(normal) - 1.0) < 1e-15);
    CHECK(std::abs(glm::dot(normal, moved[1].position - moved[0].position)) < 1e-14);
    CHECK(std::abs(glm::dot(normal, moved[2].position - moved[0].position)) < 1e-14);
}

TEST_CASE("a model's front faces are the ones back-face culling keeps") {
    // A closed model drawn with depth looks the same with its back faces culled: the
    // OBJ's counter-clockwise faces stay counter-clockwise after the z flip.
    const Scene culled = parse_scene(cube_scene("cull = \"back\"\n"), "c.toml", models);
    const Scene all = parse_scene(cube_scene(""), "c.toml", models);
    const RenderResult culled_result = render_scene(culled);
    const Framebuffer& a = culled_result.image;
    const Framebuffer b = render_scene(all).image;
    CHECK(a.pixels() == b.pixels());
    // Seen from above, right and in front, three faces turn away: 6 triangles culled.
    CHECK(culled_result.report.culling.triangles == 6);
    // and the cube is there: the labelled front face and the plain sides both show.
    int covered = 0;
    for (const Rgba8& p : a.pixels()) {
        covered += p != Rgba8{0, 0, 0, 255};
    }
    CHECK(covered > 100);
    CHECK(culled.meshes.size() == 2);
    CHECK(culled.models.size() == 2); // the OBJ and its MTL
}

TEST_CASE("a model mesh takes translate, rotate and scale like an inline mesh") {
    const Scene moved =
        parse_scene(cube_scene("scale = 2\nrotate = [0, 90, 0]\ntranslate = [0, 0, 3]\n"),
                    "c.toml", models);
    // The front face's corner (-0.5, -0.5, -0.5): scaled (-1, -1, -1), turned about y
    // (+z to +x) (-1, -1, 1), moved (-1, -1, 4).
    CHECK(moved.meshes[0].triangles[0][0].position == glm::dvec3{-1.0, -1.0, 4.0});
    const Scene inline_mesh = parse_scene(
        "[[mesh]]\nprimitive = \"triangles\"\npositions = [[0, 0, 1], [1, 0, 1], "
        "[0, 1, 1]]\nscale = [1, 2, 3]\ntranslate = [5, 0, 0]\n",
        "i.toml", models);
    CHECK(inline_mesh.meshes[0].triangles[0][2].position == glm::dvec3{5.0, 2.0, 3.0});
}

namespace {

/// Writes a one-quad model facing the viewer (+z in OBJ, -z in the scene) of diffuse
/// colour Kd 0.6 0.2 0.8 into `folder`, each corner with the normal `vn`.
void write_quad_model(const fs::path& folder, const std::string& vn) {
    fs::create_directories(folder);
    std::ofstream(folder / "quad.mtl") << "newmtl violet\nKd 0.6 0.2 0.8\n";
    std::ofstream(folder / "quad.obj")
        << "mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvn " << vn
        << "\nusemtl violet\nf 1//1 2//1 3//1 4//1\n";
}

/// A 64 x 64 orthographic scene that the quad model fills, lit by `light` (TOML lines),
/// with `mesh_extra` lines added to the model's mesh.
std::string quad_scene(const std::string& light, const std::string& mesh_extra) {
    return "[image]\nwidth = 64\nheight = 64\n"
           "[camera]\nprojection = \"orthographic\"\nview_height = 2\n" +
           light + "\n[[mesh]]\nfile = \"quad.obj\"\n" + mesh_extra;
}

} // namespace

TEST_CASE("a model mesh takes the lighting keys of an inline mesh") {
    const Scene scene =
        parse_scene(cube_scene("normals = \"given\"\nshading = \"gouraud\"\n"
                               "specular = [0.25, 0.5, 1]\nshininess = 7\n"),
                    "c.toml", models);
    REQUIRE(scene.meshes.size() == 2);
    for (const SceneMesh& mesh : scene.meshes) { // every material's mesh gets them
        CHECK(mesh.normals == NormalSource::given);
        CHECK(mesh.shading == Shading::gouraud);
        CHECK(mesh.specular == Colour{0.25, 0.5, 1.0});
        CHECK(mesh.shininess == 7.0);
    }
    const Scene plain =
        parse_scene(cube_scene("normals = \"smooth\"\n"), "c.toml", models);
    CHECK(plain.meshes[1].normals == NormalSource::smooth);
    CHECK_FALSE(plain.meshes[1].shading.has_value()); // the scene's, as inline
}

TEST_CASE("given normals are the OBJ's, with z negated") {
    // A tilted vn on a flat quad: no computed normal could be it.
    const fs::path folder = fs::temp_directory_path() /
                            ("exactpixels-ch07-given-" + std::to_string(::getpid()));
    write_quad_model(folder, "0 3 4");
    const Scene scene =
        parse_scene(quad_scene("", "normals = \"given\"\n"), "q.toml", folder);
    const std::vector<CornerNormals> normals = mesh_normals(scene.meshes[0]);
    REQUIRE(normals.size() == 2);
    for (const CornerNormals& corners : normals) {
        for (const glm::dvec3& n : corners) {
            CHECK(n.x == 0.0);
            CHECK(n.y == doctest::Approx(0.6).epsilon(1e-15));
            CHECK(n.z == doctest::Approx(-0.8).epsilon(1e-15));
        }
    }
    // The cube's vn are its faces' normals: the labelled front face (vn 0 0 1) faces -z.
    const Scene cube = parse_scene(cube_scene("normals = \"given\"\n"), "c.toml", models);
    for (const CornerNormals& corners : mesh_normals(cube.meshes[0])) {
        for (const glm::dvec3& n : corners) {
            CHECK(n == glm::dvec3{0.0, 0.0, -1.0});
        }
    }
    fs::remove_all(folder);
}

TEST_CASE("every number drawn is the number the check read") {
    // tinyobjloader reads 0.3 as 3 * 0.1, one bit above the double nearest 0.3, and a
    // normal of 401 digits as infinity; the model holds the check's values, bit for bit.
    long long texture_bytes = 0;
    const Model model = read_obj_model(models / "numbers.obj", texture_bytes);
    REQUIRE(model.parts.size() == 1);
    const ModelPart& part = model.parts[0];
    CHECK(part.colour == Colour{0.3, 0.7, 0.9});
    REQUIRE(part.triangles.size() == 2);
    const std::array<SceneVertex, 3>& first = part.triangles[0];
    CHECK(first[0].position == glm::dvec3{0.3, 0.0, -0.0});
    CHECK(first[1].position == glm::dvec3{0.0, 0.7, -0.0});
    CHECK(first[2].position == glm::dvec3{0.0, 0.0, -0.3});
    CHECK(first[0].uv == glm::dvec2{0.0, 0.0}); // no texture: uv are texels of none
    for (const SceneVertex& v : first) {        // (1, 0, 1), z negated, of length 1
        CHECK(v.normal == glm::normalize(glm::dvec3{1.0, 0.0, -1.0}));
    }
    // A leading +, leading zeros, "1."; and a denormal normal, which has a direction.
    const std::array<SceneVertex, 3>& second = part.triangles[1];
    CHECK(second[0].position == glm::dvec3{0.5, 7.0, -1.0});
    CHECK(second[0].normal == glm::dvec3{0.0, 1.0, -0.0});
}

TEST_CASE("a byte-order mark at the start of an OBJ or MTL file is skipped") {
    long long texture_bytes = 0;
    const Model model = read_obj_model(models / "bom.obj", texture_bytes);
    REQUIRE(model.parts.size() == 1);
    CHECK(model.parts[0].material == "a");
    CHECK(model.parts[0].colour == Colour{0.5, 0.25, 1.0});
    REQUIRE(model.parts[0].triangles.size() == 1);
    CHECK(model.parts[0].triangles[0][1].position == glm::dvec3{1.0, 0.0, -0.0});
}

namespace {

/// The message of the Error that reading tests/fixtures/models/NAME as a model throws.
std::string model_error(const std::string& name) {
    long long texture_bytes = 0;
    try {
        (void)read_obj_model(models / name, texture_bytes);
    } catch (const Error& error) {
        return error.what();
    }
    FAIL("the model loaded: " << name);
    return "";
}

} // namespace

TEST_CASE("a file that is not a model or not a material library is named, not quoted") {
    const std::string accounts = (models / "accounts.txt").string();
    // A passwd-like file named by mtllib: its text was the message.
    const std::string library = model_error("not-a-library.obj");
    CHECK(library.find(accounts + ":1: ") != std::string::npos);
    CHECK(library.find("not a material library") != std::string::npos);
    CHECK(library.find("root") == std::string::npos); // the file's text
    // The same file named as the model itself ("'root:x:0:0:...' is not supported").
    CHECK(model_error("accounts.txt") ==
          accounts +
              ":1: the line does not start with a statement name: not an OBJ model");
}

TEST_CASE("a model triangle the scale takes beyond doubles names its face's line") {
    const std::string face = (models / "scaled-face.obj").string() + ":9)";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"scale = 1e6\ntranslate = [0, 1, 0]", "reaches 1000001 after the transform"},
        {"scale = 1e-300", "is degenerate"},
        {"scale = [1, 1e-320, 1]",
         "takes the normal of triangle 0 (the face at " + face + " beyond the doubles"},
    };
    for (const auto& one : cases) {
        const std::string& scale = one.first;
        const std::string& reason = one.second;
        INFO(scale);
        try {
            (void)parse_scene("[[mesh]]\nfile = \"scaled-face.obj\"\n" + scale + "\n",
                              "s.toml", models);
            FAIL("the scene loaded");
        } catch (const Error& error) {
            const std::string message = error.what();
            INFO(message);
            CHECK(message.rfind("s.toml:1:1: mesh[0]: ", 0) == 0);
            CHECK(message.find("triangle 0 (the face at " + face) != std::string::npos);
            CHECK(message.find(reason) != std::string::npos);
        }
    }
}

TEST_CASE("a normal the scale stretches beyond 1e154 keeps its direction") {
    // (0, 1, 0) / 1e-160: glm::normalize squares 1e160 to infinity, and gave 0.
    const Scene scene = parse_scene("[[mesh]]\nfile = \"scaled-face.obj\"\n"
                                    "normals = \"given\"\nscale = [1, 1e-160, 1]\n",
                                    "s.toml", models);
    for (const CornerNormals& corners : mesh_normals(scene.meshes[0])) {
        for (const glm::dvec3& n : corners) {
            CHECK(n == glm::dvec3{0.0, 1.0, 0.0});
        }
    }
}

TEST_CASE("a model quad lit head-on gives exactly its diffuse colour") {
    const fs::path folder = fs::temp_directory_path() /
                            ("exactpixels-ch07-head-on-" + std::to_string(::getpid()));
    write_quad_model(folder, "0 0 1");
    const std::string light = "[[light]]\ntype = \"directional\"\ndirection = [0, 0, 1]";
    const Rgba8 diffuse = to_rgba8(Colour{0.6, 0.2, 0.8}); // the MTL's Kd
    for (const char* normals : {"face", "smooth", "given"}) {
        for (const char* shading : {"gouraud", "phong"}) {
            INFO(normals, " ", shading);
            const Scene scene = parse_scene(
                quad_scene(light, fmt::format("normals = \"{}\"\nshading = \"{}\"\n",
                                              normals, shading)),
                "q.toml", folder);
            const RenderResult r = render_scene(scene);
            CHECK(r.report.lighting_on);
            for (const Rgba8 pixel : r.image.pixels()) {
                REQUIRE(pixel == diffuse); // the quad covers every pixel
            }
        }
    }
    fs::remove_all(folder);
}

TEST_CASE("the committed models are what the generator makes, byte for byte") {
    const fs::path folder =
        fs::path(EXACTPIXELS_SOURCE_DIR) / "chapters/07-scenes/models";
    for (const GeneratedModel& model : shipped_models()) {
        INFO(model.name);
        const auto read = [&](const std::string& file) {
            return read_input_file(folder / file, "model", max_model_file_bytes,
                                   InputKind::regular_file);
        };
        CHECK(read(model.name + ".obj") == model.obj);
        CHECK(read(model.name + ".mtl") == model.mtl);
        for (const auto& texture : model.textures) {
            const auto& file = texture.first;
            const auto& image = texture.second;
            INFO(file);
            CHECK(read_png(folder / file) == image); // the pixels (the encoder may vary)
        }
    }
}

TEST_CASE("the shipped model scenes load and draw every model's triangles") {
    for (const char* name : {"torus", "room", "terrain", "lit_torus"}) {
        INFO(name);
        const Scene scene =
            load_scene(shipped_scene_folder() / (std::string(name) + ".toml"));
        const RenderResult result = render_scene(scene);
        CHECK(result.report.raster.triangles > 0);
        CHECK(result.report.raster.pixels > scene.width * scene.height / 10);
    }
    // The lit torus: textured, depth-tested, lit per pixel with the OBJ's own normals.
    const Scene lit = load_scene(shipped_scene_folder() / "lit_torus.toml");
    const RenderResult lit_result = render_scene(lit);
    CHECK(lit.meshes[0].normals == NormalSource::given);
    CHECK(lit.meshes[0].texture.has_value());
    CHECK(lit_result.report.lighting_on);
    CHECK(lit_result.report.depth_on);
    CHECK(lit_result.report.phong_meshes == 1);
    CHECK(lit_result.report.lighting.pixels > 0);
    long long texture_bytes = 0;
    const Model torus = read_obj_model(fs::path(EXACTPIXELS_SOURCE_DIR) /
                                           "chapters/07-scenes/models/torus.obj",
                                       texture_bytes);
    REQUIRE(torus.parts.size() == 1);
    CHECK(torus.parts[0].triangles.size() == 2 * 36 * 18);
    CHECK(torus.normals);
}

TEST_CASE("the speed scene's model has at least 100,000 triangles at 1280 x 720") {
    const fs::path folder = fs::temp_directory_path() /
                            ("exactpixels-ch07-big-" + std::to_string(::getpid()));
    fs::create_directories(folder);
    write_generated_model(big_torus_model(), folder);
    std::ofstream(folder / "big_torus.toml") << big_torus_scene();
    const Scene scene = load_scene(folder / "big_torus.toml");
    fs::remove_all(folder);
    CHECK(scene.width == 1280);
    CHECK(scene.height == 720);
    REQUIRE(scene.meshes.size() == 1);
    CHECK(scene.meshes[0].triangles.size() >= 100000);
}

namespace {

/// One bad model: the OBJ text, the MTL text (or none), the scene's `file`, where the
/// message must point ("model.obj:LINE"), and a word of the explanation.
struct BadModel {
    const char* what;
    std::string obj;
    std::string mtl;
    std::string where;
    std::string reason;
    std::string file = "model.obj";
};

const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

std::vector<BadModel> bad_models() {
    std::string many_corners = triangle + "f";
    for (int k = 0; k <= max_face_corners; ++k) {
        many_corners += " 1";
    }
    return {
        {"an index beyond the vertex count", triangle + "f 1 2 4\n", "", "model.obj:4",
         "index 4 in face corner '4' is beyond the 3 positions"},
        {"index 0", triangle + "f 0 1 2\n", "", "model.obj:4", "index 0"},
        {"a negative index beyond the vertex count", triangle + "f -1 -2 -4\n", "",
         "model.obj:4", "index -4 in face corner '-4' reaches back beyond the 3"},
        {"a texture coordinate index with none read", triangle + "f 1/1 2/1 3/1\n", "",
         "model.obj:4", "beyond the 0 texture coordinates"},
        {"a normal index that is not a number", triangle + "f 1//x 2//1 3//1\n", "",
         "model.obj:4", "'x' in face corner '1//x' is not an index"},
        {"a face of 2 corners", triangle + "f 1 2\n", "", "model.obj:4",
         "a face of 2 corners"},
        {"a face of too many corners", many_corners + "\n", "", "model.obj:4",
         "a face of 65 corners"},
        {"a non-numeric coordinate", "v 0 zero 0\n", "", "model.obj:1",
         "'zero' is not a number"},
        {"a NaN", "v nan 0 0\n", "", "model.obj:1", "nan is out of range"},
        // Forms that tinyobjloader reads as a number (or as 0) and the check refuses.
        {"a plus before a minus", "v +-1 -1 0\n", "", "model.obj:1",
         "'+-1' is not a number"},
        {"two plus signs", "v 0 ++1 0\n", "", "model.obj:1", "'++1' is not a number"},
        {"an exponent without digits", "v 1e 0 0\n", "", "model.obj:1",
         "'1e' is not a number"},
        {"a point alone", "vt . 0\n", "", "model.obj:1", "'.' is not a number"},
        {"a minus alone", "vn 0 - 1\n", "", "model.obj:1", "'-' is not a number"},
        {"a hexadecimal number", "v 0x1p3 0 0\n", "", "model.obj:1",
         "'0x1p3' is not a number"},
        {"infinity", "vn inf 0 0\n", "", "model.obj:1", "inf is out of range"},
        {"a number that reads as 0", "v 1e-400 0 0\n", "", "model.obj:1",
         "1e-400 is out of range (beyond a double, or so close to 0"},
        {"a number beyond a double", "vt 0 1e309\n", "", "model.obj:1",
         "1e309 is out of range (beyond a double"},
        {"a plus before a minus in a colour", "mtllib model.mtl\n" + triangle,
         "newmtl a\nKd 0 +-1 0\n", "model.mtl:2", "'+-1' is not a number"},
        {"a coordinate beyond the world", "v 2e6 0 0\n", "", "model.obj:1",
         "2e6 is out of range"},
        {"a control character", "v 0 0\x01 0\n", "", "model.obj:1",
         "control character 0x01"},
        {"a zero normal", "vn 0 0 0\n", "", "model.obj:1", "length 0"},
        {"an unsupported statement", triangle + "l 1 2\n", "", "model.obj:4",
         "'l' is not supported"},
        {"a missing material", triangle + "usemtl wood\nf 1 2 3\n", "", "model.obj:4",
         "material 'wood' is not defined"},
        {"a missing material file", "mtllib nowhere.mtl\n" + triangle, "", "model.obj:1",
         "nowhere.mtl"},
        // tinyobjloader splits mtllib names at spaces only and takes '\\' as an escape:
        // each of these read two ways once made the reader look up a name the check
        // never read (an abort).
        {"a tab after the mtllib name", "mtllib model.mtl\t\n" + triangle + "usemtl a\n",
         "newmtl a\nKd .5 .5 .5\n", "model.obj:1", "a tab or a backslash"},
        {"two tabs between mtllib and the name",
         "mtllib\t\tmodel.mtl\n" + triangle + "usemtl a\n", "newmtl a\nKd .5 .5 .5\n",
         "model.obj:1", "a tab or a backslash"},
        {"a backslash in the mtllib name", "mtllib mo\\del.mtl\n" + triangle, "",
         "model.obj:1", "a tab or a backslash"},
        {"a missing texture", "mtllib model.mtl\n" + triangle,
         "newmtl a\nmap_Kd nowhere.png\n", "model.mtl:2", "nowhere.png"},
        {"a colour out of range", "mtllib model.mtl\n" + triangle, "newmtl a\nKd 2 0 0\n",
         "model.mtl:2", "2 is out of range"},
        {"a material name after two blanks", "mtllib model.mtl\n" + triangle,
         "newmtl  a\n", "model.mtl:1", "one blank between newmtl and the name"},
        {"a material defined twice", "mtllib model.mtl\n" + triangle,
         "newmtl a\nnewmtl a\n", "model.mtl:2", "defined twice"},
        {"a degenerate face", "v 0 0 0\nv 1 1 0\nv 2 2 0\nf 1 2 3\n", "", "model.obj:4",
         "degenerate"},
        {"a non-convex face", "v 0 0 0\nv 2 0 0\nv 1 0.5 0\nv 1 2 0\nf 1 2 3 4\n", "",
         "model.obj:5", "not strictly convex (corner 3 of 4"},
        {"a self-crossing face",
         "v 0 1 0\nv -0.951 0.309 0\nv -0.588 -0.809 0\nv 0.588 -0.809 0\n"
         "v 0.951 0.309 0\nf 1 3 5 2 4\n",
         "", "model.obj:6", "not a simple polygon"},
        {"a model with no face", triangle, "", "model.obj:1", "no faces"},
        {"a model file that is not there", "", "", "nowhere.obj", "cannot read",
         "nowhere.obj"},
        {"a model file that is a directory", "", "", "folder.obj", "is a directory",
         "folder.obj"},
    };
}

fs::path scratch_folder(const std::string& name) {
    auto folder = fs::temp_directory_path() /
                  ("exactpixels-ch07-models-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(folder);
    fs::create_directories(folder / "folder.obj");
    return folder;
}

/// Writes one case's model (and material) files into `folder`.
void write_model(const fs::path& folder, const BadModel& bad) {
    fs::remove(folder / "model.obj");
    fs::remove(folder / "model.mtl");
    if (bad.file == "model.obj") {
        std::ofstream(folder / "model.obj") << bad.obj;
    }
    if (!bad.mtl.empty()) {
        std::ofstream(folder / "model.mtl") << bad.mtl;
    }
}

} // namespace

TEST_CASE("every bad model names the model's file and line and the value") {
    const fs::path folder = scratch_folder("loader");
    for (const BadModel& bad : bad_models()) {
        INFO(bad.what);
        write_model(folder, bad);
        try {
            (void)parse_scene("[[mesh]]\nfile = \"" + bad.file + "\"\n", "bad.toml",
                              folder);
            FAIL("the model loaded: ", bad.what);
        } catch (const Error& error) {
            const std::string message = error.what();
            INFO(message);
            CHECK(message.rfind("bad.toml:2:8: mesh[0].file: ", 0) == 0);
            CHECK(message.find((folder / bad.where).string()) != std::string::npos);
            CHECK(message.find(bad.reason) != std::string::npos);
        }
    }
    fs::remove_all(folder);
}

TEST_CASE("more positions than allowed are refused before they are stored") {
    std::string text;
    text.reserve(8 * static_cast<std::size_t>(max_model_vertices + 1));
    for (long long k = 0; k <= max_model_vertices; ++k) {
        text += "v 0 0 0\n";
    }
    long long texture_bytes = 0;
    try {
        (void)parse_obj_model(text, "big.obj", ".", texture_bytes);
        FAIL("the model loaded");
    } catch (const Error& error) {
        CHECK(std::string(error.what()) ==
              fmt::format("big.obj:{}: more than the {} positions allowed",
                          max_model_vertices + 1, max_model_vertices));
    }
}

TEST_CASE(
    "the render command rejects each bad model with exit code 2 and writes nothing") {
    const fs::path folder = scratch_folder("cli");
    for (const BadModel& bad : bad_models()) {
        INFO(bad.what);
        write_model(folder, bad);
        const fs::path scene = folder / "bad.toml";
        const fs::path output = folder / "bad.png";
        std::ofstream(scene) << "[[mesh]]\nfile = \"" + bad.file + "\"\n";
        const auto result =
            testing::run_command(testing::cli_path() + " render '" + scene.string() +
                                 "' -o '" + output.string() + "'");
        INFO(result.err);
        CHECK(result.exit_code == 2);
        CHECK(result.err.find(scene.string() + ":2:8: mesh[0].file: ") !=
              std::string::npos);
        CHECK(result.err.find((folder / bad.where).string()) != std::string::npos);
        CHECK_FALSE(fs::exists(output));
    }
    fs::remove_all(folder);
}
