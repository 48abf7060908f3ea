// Chapter 7 tests: the refused scenes, as files. Each file of tests/fixtures/bad_scenes
// shows one thing the scene format refuses: its first line says what, and a comment
//   # expect error: LINE:COLUMN: KEY.PATH: MESSAGE
// holds the message `render` must print after the file's name. Every file is rendered
// through the command line from inside that folder, so the messages name the scene and
// the textures and models it points at (../models/, tests/fixtures/models/) by the paths
// the scene wrote. Scenes that need generated input (a corrupt PNG, a FIFO, a file of
// megabytes) stay in ch07_bad_input.cpp and ch07_limits.cpp.
#include "support/process.hpp"
#include "support/scene_files.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace {

const std::string expect_prefix = "# expect error: ";

/// The lines of `path` that hold an expected message, each without the prefix.
std::vector<std::string> expected_messages(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::vector<std::string> found;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind(expect_prefix, 0) == 0) {
            found.push_back(line.substr(expect_prefix.size()));
        }
    }
    return found;
}

/// Renders every .toml file of `folder` from inside it, writing (it must not) into
/// `scratch`, and returns one line per way a file was not refused as it expects; a
/// folder without scene files is a failure too.
std::vector<std::string> refusal_failures(const fs::path& folder,
                                          const fs::path& scratch) {
    const std::vector<fs::path> scenes = exactpixels::testing::scene_files(folder);
    std::vector<std::string> failures;
    if (scenes.empty()) {
        failures.push_back(folder.string() + ": no scene files");
    }
    for (const fs::path& scene : scenes) {
        const std::string name = scene.filename().string();
        const std::vector<std::string> expected = expected_messages(scene);
        if (expected.size() != 1) {
            failures.push_back(name + ": " + std::to_string(expected.size()) +
                               " lines start '" + expect_prefix + "' (need one)");
            continue;
        }
        const fs::path output = scratch / (scene.stem().string() + ".png");
        const auto result = exactpixels::testing::run_command(
            "cd '" + folder.string() + "' && " + exactpixels::testing::cli_path() +
            " render '" + name + "' -o '" + output.string() + "'");
        const std::string want = "exactpixels render: " + name + ":" + expected[0] + "\n";
        if (result.exit_code != 2) {
            failures.push_back(name + ": exit code " + std::to_string(result.exit_code));
        }
        if (result.err != want || !result.out.empty()) {
            failures.push_back(name + ": printed '" + result.out + result.err +
                               "', expected '" + want + "'");
        }
        if (fs::exists(output)) {
            failures.push_back(name + ": wrote " + output.string());
        }
    }
    return failures;
}

fs::path scratch_folder(const std::string& name) {
    const fs::path folder =
        fs::temp_directory_path() /
        ("exactpixels-bad-scenes-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(folder);
    fs::create_directories(folder);
    return folder;
}

const fs::path bad_scenes =
    fs::path(EXACTPIXELS_SOURCE_DIR) / "tests/fixtures/bad_scenes";

} // namespace

TEST_CASE("every scene of tests/fixtures/bad_scenes is refused with the message it "
          "expects") {
    // Some name a model of tests/fixtures/models/ as ../models/NAME.obj.
    REQUIRE(
        fs::is_directory(fs::path(EXACTPIXELS_SOURCE_DIR) / "tests/fixtures/models/"));
    const fs::path scratch = scratch_folder("all");
    for (const std::string& failure : refusal_failures(bad_scenes, scratch)) {
        FAIL_CHECK(failure);
    }
    fs::remove_all(scratch);
}

TEST_CASE("the bad-scene runner fails on a changed message and on an empty folder") {
    const fs::path scratch = scratch_folder("runner");
    const fs::path folder = scratch / "scenes";
    fs::create_directories(folder);
    CHECK(refusal_failures(folder, scratch).size() == 1); // no scene files
    // One scene whose expected message differs by one character from the one printed.
    std::ifstream in(bad_scenes / "nan.toml", std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    std::string changed = text.str();
    const std::size_t at = changed.find("not a finite number");
    REQUIRE(at != std::string::npos);
    changed.replace(at, 3, "NOT");
    std::ofstream(folder / "nan.toml", std::ios::binary) << changed;
    const std::vector<std::string> failures = refusal_failures(folder, scratch);
    REQUIRE(failures.size() == 1);
    CHECK(failures[0].rfind("nan.toml: printed ", 0) == 0);
    // Without its expect line it fails too, and a scene that loads fails on its exit
    // code.
    std::ofstream(folder / "nan.toml", std::ios::binary)
        << "[[mesh]]\nprimitive = \"quad\"\n";
    CHECK(refusal_failures(folder, scratch).size() == 1);
    std::ofstream(folder / "nan.toml", std::ios::binary)
        << "# expect error: 1:1: mesh: x\n[[mesh]]\nprimitive = \"quad\"\n"
           "corners = [[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]]\n";
    CHECK(refusal_failures(folder, scratch).size() == 3); // exit 0, no message, a PNG
    fs::remove_all(scratch);
}
