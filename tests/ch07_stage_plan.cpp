// Chapter 7 tests of the stage plan on lit and model scenes (the lighting and the models
// themselves are chapter 9's, tests/ch09_lighting.cpp and tests/ch09_models.cpp): a scene
// without lights runs no lighting stage, and a model several meshes name is read once.
// Both grade chapter 7's exercise ch07-plan-mesh, so they stay in chapter 7's suite.
#include "exactpixels/base/png.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "support/printing.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <string>
#include <vector>

using namespace exactpixels;
namespace fs = std::filesystem;

namespace {

const fs::path models = fs::path(EXACTPIXELS_SOURCE_DIR) / "tests/fixtures/models";

} // namespace

// A stub of ch07-plan-mesh (no stage runs) breaks it, so it grades that exercise.
TEST_CASE("without a light no lighting stage runs and the shipped scenes are unchanged" *
          doctest::description("points: 2; exercise: ch07-plan-mesh")) {
    // The references were rendered by the renderer before it had a lighting stage (boxes
    // and near_plane again when auto began mapping whole triangles affine, issue 34).
    std::vector<std::filesystem::path> scenes = shipped_scenes();
    scenes.push_back(shipped_scene_folder() / "horizon_filtered.toml");
    for (const auto& path : scenes) {
        const Scene scene = load_scene(path);
        if (!scene.lights.empty()) {
            continue;
        }
        INFO(path.string());
        const RenderResult result = render_scene(scene);
        CHECK_FALSE(result.report.lighting_on);
        CHECK(result.report.lighting.triangles == 0);
        CHECK(result.report.lighting.pixels == 0);
        CHECK(format_report(result.report).find("lighting stage: off") !=
              std::string::npos);
        const Framebuffer before =
            read_png(std::filesystem::path(EXACTPIXELS_SOURCE_DIR) /
                     ("tests/fixtures/ch07_unlit/" + path.stem().string() + ".png"));
        CHECK(result.image == before);
    }
}

TEST_CASE("a model named by several meshes is read once and its texture held once" *
          doctest::description("points: 1; exercise: ch07-plan-mesh")) {
    // tests/fixtures/models/three_cubes.toml names cube.obj three times, spelled three
    // ways, moved apart by its translate: three cubes of two materials each.
    const Scene scene = load_scene(models / "three_cubes.toml");
    REQUIRE(scene.meshes.size() == 6);
    CHECK(scene.models.size() == 2);   // cube.obj and cube.mtl, each read once
    CHECK(scene.textures.size() == 1); // the F of cube.mtl, held once
    for (std::size_t k = 0; k < 2; ++k) {
        const SceneMesh& middle = scene.meshes[k + 2];
        for (const std::size_t other : {k, k + 4}) {
            const SceneMesh& mesh = scene.meshes[other];
            CHECK(mesh.texture == middle.texture);
            REQUIRE(mesh.triangles.size() == middle.triangles.size());
            const double dx = other < k + 2 ? -1.2 : 1.2; // each cube's translate
            for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
                for (std::size_t v = 0; v < 3; ++v) {
                    const glm::dvec3 moved =
                        mesh.triangles[t][v].position - middle.triangles[t][v].position;
                    CHECK(moved.x == doctest::Approx(dx));
                    CHECK(moved.y == 0.0);
                    CHECK(moved.z == 0.0);
                }
            }
        }
    }
    CHECK(render_scene(scene).report.texture.pixels > 0); // the shared index is valid
}
