// Chapter 7 tests: every kind of bad scene is rejected with a message naming the file,
// the line and column, and the key path; the CLI exits with 2 and writes no file.
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "support/png_chunks.hpp"
#include "support/process.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

using namespace exactpixels;
namespace fs = std::filesystem;

namespace {

/// A scene that loads, plus one case's bad lines: `extra_image` (one line or none) goes
/// at line 4, then the mesh, whose `extra_mesh` line is line 7 (or 8 after an extra
/// image line).
std::string scene_with(const std::string& extra_image, const std::string& extra_mesh) {
    return "[image]\n"
           "width = 16\n"
           "height = 12\n" +
           extra_image +
           "[[mesh]]\n"
           "primitive = \"triangles\"\n"
           "positions = [[0, 0, 1], [1, 0, 1], [0, 1, 1]]\n" +
           extra_mesh;
}

/// A [textures] table of `count` textures t0, t1, ... each `{ fields }`.
std::string many_textures(int count, const std::string& fields) {
    std::string text = "[textures]\n";
    for (int k = 0; k < count; ++k) {
        text += fmt::format("t{} = {{ {} }}\n", k, fields);
    }
    return text;
}

/// One bad scene: its text, and where and what the message must name.
struct BadScene {
    const char* what;
    std::string text;
    std::string where;    // "LINE:COLUMN"
    std::string key_path; // the key path the message names
    std::string reason;   // a word of the explanation
};

/// The bad scenes whose textures the test makes (a corrupt PNG, one too wide, one of
/// width 0, a FIFO). Every other refused scene is a file of tests/fixtures/bad_scenes
/// (ch07_bad_scenes.cpp).
std::vector<BadScene> bad_scenes() {
    return {
        {"a corrupt texture file",
         scene_with("[textures.wood]\nkind = \"png\"\nfile = \"corrupt.png\"\n", ""),
         "6:8", "textures.wood.file", "corrupt.png"},
        {"a PNG texture wider than allowed",
         scene_with("[textures.wide]\nkind = \"png\"\nfile = \"wide.png\"\n", ""), "6:8",
         "textures.wide.file", "larger than the 4096 allowed"},
        {"a PNG texture of zero width",
         scene_with("[textures.z]\nkind = \"png\"\nfile = \"zero.png\"\n", ""), "6:8",
         "textures.z.file", "zero.png"},
        {"a texture file that is a FIFO",
         scene_with("[textures.pipe]\nkind = \"png\"\nfile = \"fifo.png\"\n", ""), "6:8",
         "textures.pipe.file", "not a regular file"},
    };
}

fs::path scratch_folder(const std::string& name) {
    auto folder = fs::temp_directory_path() /
                  ("exactpixels-ch07-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(folder);
    fs::create_directories(folder);
    std::ofstream(folder / "corrupt.png") << "\x89PNG\r\n\x1a\nthis is not a PNG";
    write_png(folder / "wide.png", Framebuffer(max_texture_side + 1, 1));
    // The PNG fixture with a width of 0 in its header, its CRC made right again.
    std::ifstream fixture(fs::path(EXACTPIXELS_SOURCE_DIR) / "tests/fixtures/png/f.png",
                          std::ios::binary);
    std::string bytes{std::istreambuf_iterator<char>(fixture), {}};
    const testing::PngChunk ihdr = testing::find_chunk(bytes, "IHDR");
    testing::write_u32(bytes, ihdr.data, 0);
    testing::fix_crc(bytes, ihdr);
    std::ofstream(folder / "zero.png", std::ios::binary) << bytes;
    ::mkfifo((folder / "fifo.png").c_str(), 0600); // nobody writes it: must not block
    return folder;
}

} // namespace

TEST_CASE("every bad scene names the file, line, column and key path") {
    const fs::path folder = scratch_folder("loader");
    for (const BadScene& bad : bad_scenes()) {
        INFO(bad.what);
        try {
            (void)parse_scene(bad.text, "bad.toml", folder);
            FAIL("the scene loaded: ", bad.what);
        } catch (const Error& error) {
            const std::string message = error.what();
            INFO(message);
            CHECK(message.rfind("bad.toml:" + bad.where + ": " + bad.key_path + ":", 0) ==
                  0);
            CHECK(message.find(bad.reason) != std::string::npos);
        }
    }
    fs::remove_all(folder);
}

TEST_CASE(
    "the render command rejects each bad scene with exit code 2 and writes nothing") {
    const fs::path folder = scratch_folder("cli");
    int k = 0;
    for (const BadScene& bad : bad_scenes()) {
        INFO(bad.what);
        const fs::path scene = folder / ("bad" + std::to_string(k) + ".toml");
        const fs::path output = folder / ("bad" + std::to_string(k++) + ".png");
        std::ofstream(scene) << bad.text;
        const auto result =
            testing::run_command(testing::cli_path() + " render '" + scene.string() +
                                 "' -o '" + output.string() + "'");
        INFO(result.err);
        CHECK(result.exit_code == 2);
        CHECK(result.err.find(scene.string() + ":" + bad.where + ": " + bad.key_path) !=
              std::string::npos);
        CHECK_FALSE(fs::exists(output));
    }
    fs::remove_all(folder);
}

TEST_CASE("a PNG texture over a limit is reported with its place once") {
    // The size checks run inside the PNG reader, whose errors the loader prefixes with
    // the place: they once named it themselves as well, so it came twice.
    const fs::path folder = scratch_folder("once");
    write_png(folder / "small.png", Framebuffer(1, 1));
    const std::string wide = scene_with("[textures.wide]\nkind = \"png\"\nfile = "
                                        "\"wide.png\"\n",
                                        "");
    const std::string wide_message =
        "bad.toml:6:8: textures.wide.file: " + (folder / "wide.png").string() +
        ": 4097x1 texels is larger than the 4096 allowed "
        "per side";
    CHECK_THROWS_WITH_AS((void)parse_scene(wide, "bad.toml", folder),
                         wide_message.c_str(), Error);
    // Two 4096 x 4096 textures fill the 128 MiB of texels; one texel more is refused
    // (toml++ keeps a table's keys in order: t0, t1, u).
    const std::string full =
        scene_with(many_textures(2, "kind = \"checkerboard\", size = [4096, 4096], "
                                    "square = 64") +
                       "u = { kind = \"png\", file = \"small.png\" }\n",
                   "");
    CHECK_THROWS_WITH_AS(
        (void)parse_scene(full, "bad.toml", folder),
        "bad.toml:7:28: textures.u.file: a 1x1 texture takes the scene's "
        "textures beyond the 134217728 bytes allowed",
        Error);

    // The command prints the same message, once, on one line.
    const fs::path scene = folder / "bad.toml";
    std::ofstream(scene) << wide;
    const auto result =
        testing::run_command(testing::cli_path() + " render '" + scene.string() +
                             "' -o '" + (folder / "out.png").string() + "'");
    CHECK(result.exit_code == 2);
    CHECK(result.err == "exactpixels render: " + (folder / wide_message).string() + "\n");
    CHECK_FALSE(fs::exists(folder / "out.png"));
    fs::remove_all(folder);
}

TEST_CASE("a missing scene file is named, exit code 2, no output") {
    const fs::path folder = scratch_folder("missing");
    const auto result = testing::run_command(
        testing::cli_path() + " render '" + (folder / "nowhere.toml").string() +
        "' -o '" + (folder / "out.png").string() + "'");
    CHECK(result.exit_code == 2);
    CHECK(result.err.find("nowhere.toml") != std::string::npos);
    CHECK_FALSE(fs::exists(folder / "out.png"));
    fs::remove_all(folder);
}

TEST_CASE("a triangle beyond the rasterizer's range is clipped and drawn, not an error") {
    const fs::path folder = scratch_folder("range");
    // 1e6 units at depth 5 with a focal length of 6 / tan 5 degrees = 68.6 px: 1.4e7 px
    // from the centre, beyond the 2^20 px of chapter 2's exact range. It used to be an
    // Error; the guard band (@sec:scene-clipping) cuts it, and the render succeeds.
    const std::string text = "[image]\nwidth = 12\nheight = 12\n[camera]\nfov = 10\n"
                             "[[mesh]]\nprimitive = \"triangles\"\n"
                             "positions = [[0, 0, 5], [1000000, 0, 5], [0, 1, 5]]\n";
    std::ofstream(folder / "far.toml") << text;
    const auto result = testing::run_command(testing::cli_path() + " render '" +
                                             (folder / "far.toml").string() + "' -o '" +
                                             (folder / "far.png").string() + "'");
    CHECK(result.exit_code == 0);
    CHECK(result.err.empty());
    CHECK(fs::exists(folder / "far.png"));
    fs::remove_all(folder);
}

namespace {

/// The message `render` prints for tests/fixtures/scenes/NAME, named as "bad.toml",
/// after checking that it is one line, exit code 2 and no output.
std::string render_fixture_message(const std::string& name) {
    const fs::path folder = scratch_folder("fixture");
    const fs::path scene = folder / "bad.toml";
    fs::copy_file(fs::path(EXACTPIXELS_SOURCE_DIR) / "tests/fixtures/scenes" / name,
                  scene);
    const auto result =
        testing::run_command("cd '" + folder.string() + "' && " + testing::cli_path() +
                             " render bad.toml -o out.png");
    CHECK(result.exit_code == 2);
    CHECK(result.out.empty());
    CHECK_FALSE(fs::exists(folder / "out.png"));
    fs::remove_all(folder);
    return result.err;
}

} // namespace

TEST_CASE("a control character in a scene string is escaped in the message") {
    // ESC and BEL reached the terminal raw: the red text and the title change acted.
    CHECK(render_fixture_message("escape_in_texture_name.toml") ==
          "exactpixels render: bad.toml:5:11: mesh[0].texture: no texture named "
          "'a\\x1b[31mb\\x07' under [textures]\n");
    CHECK(render_fixture_message("escape_in_key.toml") ==
          "exactpixels render: bad.toml:4:1: image.\\x1b]0;title\\x07: unknown key "
          "(allowed here: width, height, background)\n");
}

TEST_CASE("a key defined twice is named as the scene wrote it") {
    // toml++ named the key from a record holding its first characters twice: '"memesh"'.
    CHECK(render_fixture_message("redefined_quoted_table.toml") ==
          "exactpixels render: bad.toml:6:1: (syntax): Error while parsing table header: "
          "cannot redefine existing array '\"mesh\"' as table\n");
    CHECK(render_fixture_message("redefined_quoted_key.toml") ==
          "exactpixels render: bad.toml:4:25: (syntax): Error while parsing key-value "
          "pair: cannot redefine existing integer '\"w\"'\n");
}
