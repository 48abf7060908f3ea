// Chapter 7 tests: nothing unbounded. Every input the program reads has a stated limit,
// checked before the memory it bounds is allocated, so the worst input under the limits
// stays under a stated peak of memory, and an input over them is refused cheaply. Each
// case runs build/bin/exactpixels as a child process and reads its peak resident memory
// from the kernel (wait4's ru_maxrss).
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/base/test_pattern.hpp"
#include "exactpixels/lab/model_generator.hpp"
#include "exactpixels/scene/obj_model.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "support/printing.hpp"
#include "support/measured_facts.hpp"
#include "support/png_chunks.hpp"
#include "support/scene_files.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <malloc.h>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

using namespace exactpixels;
namespace fs = std::filesystem;

namespace {

constexpr long long mebibyte = 1LL << 20;

// Builds under AddressSanitizer skip three kinds of test here. A process's resident memory
// is then mostly the sanitizer's own shadow and quarantine, so peaks mean nothing (the
// release build of the test workflow measures them); the sanitizer reserves terabytes of
// address space at start, so it cannot run under a limit on the address space; and the
// largest scenes take many seconds instead of a fraction of one.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool sanitized = true;
#else
constexpr bool sanitized = false;
#endif

/// How a child ended and the most memory it held.
struct Peak {
    int exit_code = -1;
    long long bytes = 0; ///< peak resident set size
};

/// Runs build/bin/exactpixels with `arguments`, standard input from `input` (a file),
/// standard output to /dev/null and standard error to `errors`, its address space
/// limited to `address_space` bytes when that is not 0 (as `ulimit -v` does).
Peak run_measured(const std::vector<std::string>& arguments,
                  const fs::path& input = "/dev/null",
                  const fs::path& errors = "/dev/null", long long address_space = 0) {
    std::vector<char*> argv;
    std::string program = EXACTPIXELS_CLI;
    argv.push_back(program.data());
    std::vector<std::string> copies = arguments;
    for (std::string& argument : copies) {
        argv.push_back(argument.data());
    }
    argv.push_back(nullptr);
    // A forked child starts with this process's resident pages, and the kernel keeps
    // that high-water mark through execv: ru_maxrss would be this process's size
    // whenever it exceeds the child's own peak. Freed memory the allocator kept from
    // earlier tests (the big torus's renders) goes back to the system first.
    ::malloc_trim(0);
    const pid_t child = ::fork();
    if (child == 0) {
        const int in = ::open(input.c_str(), O_RDONLY);
        const int null = ::open("/dev/null", O_WRONLY);
        const int err = ::open(errors.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
        ::dup2(in, 0);
        ::dup2(null, 1);
        ::dup2(err, 2);
        if (address_space > 0) {
            const auto bytes = static_cast<rlim_t>(address_space);
            const struct rlimit limit { bytes, bytes };
            ::setrlimit(RLIMIT_AS, &limit);
        }
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    int status = 0;
    struct rusage usage {};
    REQUIRE(::wait4(child, &status, 0, &usage) == child);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, usage.ru_maxrss * 1024LL};
}

fs::path scratch_folder(const std::string& name) {
    auto folder = fs::temp_directory_path() /
                  ("exactpixels-limits-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(folder);
    fs::create_directories(folder);
    return folder;
}

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

} // namespace

TEST_CASE("inputs over the limits are refused early, with little memory" *
          doctest::skip(sanitized)) {
    const fs::path folder = scratch_folder("over");
    // An endless scene file: refused after max_scene_file_bytes.
    const Peak zero = run_measured({"render", "/dev/zero", "-o", folder / "o.png"});
    CHECK(zero.exit_code == 2);
    CHECK(zero.bytes < 32 * mebibyte);

    // A 99-byte PNG whose header claims 16384 x 16383 pixels (1 GiB of texels).
    std::string png =
        slurp(fs::path(EXACTPIXELS_SOURCE_DIR) / "tests/fixtures/png/f.png");
    const testing::PngChunk ihdr = testing::find_chunk(png, "IHDR");
    testing::write_u32(png, ihdr.data, 16384);
    testing::write_u32(png, ihdr.data + 4, 16383);
    testing::fix_crc(png, ihdr);
    std::ofstream(folder / "huge.png", std::ios::binary) << png;
    std::ofstream(folder / "huge.toml")
        << "[textures.t]\nkind = \"png\"\nfile = \"huge.png\"\n[[mesh]]\n"
           "primitive = \"quad\"\ncorners = [[0, 0, 5], [1, 0, 5], [1, 1, 5], [0, 1, "
           "5]]\n"
           "texture = \"t\"\n";
    const Peak huge =
        run_measured({"render", folder / "huge.toml", "-o", folder / "o.png"});
    CHECK(huge.exit_code == 2);
    CHECK(huge.bytes < 32 * mebibyte);

    // A coverage frame of 16384 x 16384 pixels (1 GiB of counts).
    std::ofstream(folder / "frame.txt") << "16384 16384\n";
    const Peak frame = run_measured({"coverage"}, folder / "frame.txt");
    CHECK(frame.exit_code == 2);
    CHECK(frame.bytes < 32 * mebibyte);
    CHECK_FALSE(fs::exists(folder / "o.png"));
    fs::remove_all(folder);
}

TEST_CASE("the worst inputs under the limits stay under the stated peaks" *
          doctest::skip(sanitized)) {
    const fs::path folder = scratch_folder("under");
    // The largest image and the most texel memory a scene may have.
    std::ofstream(folder / "big.toml") << fmt::format(
        "[image]\nwidth = {0}\nheight = {0}\n"
        "[textures.a]\nkind = \"checkerboard\"\nsize = [{1}, {1}]\nsquare = 64\n"
        "[textures.b]\nkind = \"grid\"\nsize = [{1}, {1}]\nspacing = 64\n"
        "[[mesh]]\nprimitive = \"triangles\"\n"
        "positions = [[-1, -1, 5], [1, -1, 5], [0, 1, 5]]\n"
        "uv = [[0, 0], [4096, 0], [0, 4096]]\ntexture = \"a\"\n",
        4096, max_texture_side);
    const Peak big =
        run_measured({"render", folder / "big.toml", "-o", folder / "b.png"});
    CHECK(big.exit_code == 0);
    CHECK(big.bytes < 512 * mebibyte); // 128 MiB of texels, 64 MiB of frame, the PNG

    // The same scene with --check: two TexelMaps of the largest image beside it. The
    // peak stays under the stated bound, and above the two maps alone (the maps were
    // really made, so the measurement sees the check).
    const Peak checked =
        run_measured({"render", folder / "big.toml", "--check", "-o", folder / "c.png"});
    CHECK(checked.exit_code == 0);
    const double maps = 2.0 * texel_map_bytes_per_pixel * double(max_image_pixels);
    CHECK(double(checked.bytes) > maps);
    CHECK(checked.bytes < max_check_peak_bytes);
    MESSAGE(fmt::format("render --check peak: {:.0f} MiB (bound {} MiB, maps {:.0f} MiB)",
                        double(checked.bytes) / double(mebibyte),
                        max_check_peak_bytes / mebibyte, maps / double(mebibyte)));

    // The largest scene file, all of it vertex data (the parser's worst case).
    std::string text = "[image]\nwidth = 64\nheight = 64\n[[mesh]]\n"
                       "primitive = \"triangles\"\npositions = [\n";
    for (int k = 0;; ++k) {
        const std::string triangle =
            fmt::format("[{0}, 0, 9], [{0}, 1, 9], [{1}, 0, 9],\n", k, k + 1);
        if (text.size() + triangle.size() + 2 > max_scene_file_bytes) {
            break;
        }
        text += triangle;
    }
    text += "]\n";
    std::ofstream(folder / "long.toml") << text;
    const Peak parsed =
        run_measured({"render", folder / "long.toml", "-o", folder / "l.png"});
    CHECK(parsed.exit_code == 0);
    CHECK(parsed.bytes < 256 * mebibyte);

    // The largest coverage frame: 2^24 pixels.
    std::ofstream(folder / "frame.txt") << "4096 4096\n0 0 4096 0 0 4096\n";
    const Peak frame =
        run_measured({"coverage", "-o", folder / "c.txt"}, folder / "frame.txt");
    CHECK(frame.exit_code == 0);
    CHECK(frame.bytes < 256 * mebibyte);
    fs::remove_all(folder);
}

namespace {

/// The message of the Error that parsing `text` (a scene in `folder`) throws, or "".
std::string scene_error(const std::string& text, const fs::path& folder) {
    try {
        (void)parse_scene(text, "s.toml", folder);
    } catch (const Error& error) {
        return error.what();
    }
    return "";
}

} // namespace

TEST_CASE("model references over the limits are refused before they are copied") {
    const fs::path folder = scratch_folder("references");
    const fs::path cube = fs::path(EXACTPIXELS_SOURCE_DIR) / "tests/fixtures/models";
    // Generated, not fixtures: thousands of entries. The cube has two materials, so
    // 2049 references make 4098 meshes.
    std::string many;
    for (int k = 0; k < max_scene_meshes / 2 + 1; ++k) {
        many += "[[mesh]]\nfile = \"cube.obj\"\n";
    }
    CHECK(scene_error(many, cube) ==
          fmt::format("s.toml:{}:8: mesh[{}].file: the model's 2 materials take the "
                      "scene beyond the {} meshes allowed",
                      max_scene_meshes + 2, max_scene_meshes / 2, max_scene_meshes));

    // A model of 2^15 triangles, a grid of 128 x 128 quads: 32 references are the
    // scene's 2^20 triangles, the 33rd is refused before its copy is made.
    std::string grid;
    for (int y = 0; y <= 128; ++y) {
        for (int x = 0; x <= 128; ++x) {
            grid += fmt::format("v {} {} 0\n", x, y);
        }
    }
    for (int y = 0; y < 128; ++y) {
        for (int x = 0; x < 128; ++x) {
            const int a = y * 129 + x + 1;
            grid += fmt::format("f {} {} {} {}\n", a, a + 1, a + 130, a + 129);
        }
    }
    std::ofstream(folder / "grid.obj") << grid;
    std::string copies;
    for (int k = 0; k < 33; ++k) {
        copies += "[[mesh]]\nfile = \"grid.obj\"\n";
    }
    CHECK(scene_error(copies, folder) ==
          fmt::format("s.toml:66:8: mesh[32].file: the model's 32768 triangles take the "
                      "scene beyond the {} triangles allowed",
                      max_scene_triangles));

    // A second model file that would take the scene's models beyond
    // max_scene_model_bytes is refused from its size, before a byte of it is read (a
    // sparse file of zeros: reading it would be an error too, a different one).
    std::ofstream(folder / "huge.obj").close();
    fs::resize_file(folder / "huge.obj",
                    static_cast<std::uintmax_t>(max_model_file_bytes));
    const std::string two =
        "[[mesh]]\nfile = \"grid.obj\"\n[[mesh]]\nfile = \"huge.obj\"\n";
    CHECK(scene_error(two, folder) ==
          fmt::format("s.toml:4:8: mesh[1].file: {}: {} bytes take the scene's model "
                      "files beyond the {} bytes allowed together",
                      (folder / "huge.obj").string(), max_model_file_bytes,
                      max_scene_model_bytes));
    fs::remove_all(folder);
}

TEST_CASE("every shipped scene asks for a small part of the fill-work limit") {
    // Every scene that ships in chapters/07-scenes/scenes/ (chapter 8's among them) and
    // the big torus of chapter 7's speed section, which the book build generates.
    std::vector<fs::path> scenes = exactpixels::testing::scene_files(shipped_scene_folder());
    REQUIRE(scenes.size() >= 12);
    const fs::path folder = scratch_folder("fill");
    write_generated_model(big_torus_model(), folder);
    std::ofstream(folder / "big_torus.toml") << big_torus_scene();
    scenes.push_back(folder / "big_torus.toml");
    long long largest = 0;
    for (const fs::path& path : scenes) {
        const Scene scene = load_scene(path);
        RenderReport report;
        const std::vector<long long> work =
            fill_work(run_geometry(scene, report), Viewport{scene.width, scene.height});
        long long sum = 0;
        for (const long long mesh : work) {
            sum += mesh;
        }
        INFO(path.filename().string(), ": ", sum, " pixels");
        CHECK(sum > 0);
        largest = std::max(largest, sum);
    }
    fs::remove_all(folder);
    // The limit is far above every scene the book draws.
    CHECK(100 * largest < max_fill_work);
    testing::record_fact("ch07_fill_work_largest", double(largest));
    testing::record_fact("ch07_fill_work_margin",
                         double(max_fill_work) / double(largest));
    MESSAGE(fmt::format("largest shipped fill work: {} pixels, {:.0f} times under the "
                        "limit",
                        largest, double(max_fill_work) / double(largest)));
}

TEST_CASE("a scene over the fill-work limit is refused before it is drawn") {
    // tests/fixtures/scenes/fill_work_over.toml: 17 triangles whose bounding boxes each
    // cover the 4096 x 4096 image; 16 are exactly max_fill_work.
    REQUIRE(max_fill_work == 16LL * 4096 * 4096);
    const fs::path path =
        fs::path(EXACTPIXELS_SOURCE_DIR) / "tests/fixtures/scenes/fill_work_over.toml";
    Scene scene = load_scene(path);
    REQUIRE(scene.meshes.size() == 17);
    try {
        (void)render_scene(scene);
        FAIL("the scene was drawn");
    } catch (const Error& error) {
        CHECK(std::string(error.what()) ==
              fmt::format("{}:59:1: mesh[16]: the triangles up to this mesh ask for {} "
                          "pixels of drawing (their bounding boxes in the image), more "
                          "than the {} allowed",
                          path.string(), 17LL * 4096 * 4096, max_fill_work));
    }
    // At the limit the scene is drawn: 2^28 pixels of boxes, half of them covered, a
    // fraction of a second, but many seconds under the sanitizers, which skip it.
    if (!sanitized) {
        scene.meshes.pop_back();
        const RenderResult drawn = render_scene(scene);
        CHECK(drawn.report.raster.triangles == 16);
        CHECK(drawn.report.raster.pixels == 16LL * 4096 * 4095 / 2); // top-left rule
    }
}
TEST_CASE("a render that runs out of memory exits 2 with one line and writes nothing" *
          doctest::skip(sanitized)) {
    const fs::path folder = scratch_folder("memory");
    // The largest image with --check needs about 900 MiB; the process may have 384.
    std::ofstream(folder / "big.toml")
        << "[image]\nwidth = 4096\nheight = 4096\n"
           "[textures.a]\nkind = \"checkerboard\"\nsize = [64, 64]\nsquare = 8\n"
           "[[mesh]]\nprimitive = \"triangles\"\n"
           "positions = [[-1, -1, 5], [1, -1, 5], [0, 1, 5]]\n"
           "uv = [[0, 0], [4, 0], [0, 4]]\ntexture = \"a\"\n";
    const fs::path errors = folder / "errors.txt";
    const Peak result =
        run_measured({"render", folder / "big.toml", "--check", "-o", folder / "big.png"},
                     "/dev/null", errors, 384 * mebibyte);
    CHECK(result.exit_code == 2);
    const std::string message = slurp(errors);
    CHECK(message.find("exactpixels render: ") == 0);
    CHECK(message.find("memory") != std::string::npos);
    CHECK(std::count(message.begin(), message.end(), '\n') == 1);
    std::vector<std::string> names; // no PNG, no temporary file
    for (const auto& entry : fs::directory_iterator(folder)) {
        names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    CHECK(names == std::vector<std::string>{"big.toml", "errors.txt"});
    fs::remove_all(folder);
}
