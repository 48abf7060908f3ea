// Chapter 7 tests: nothing unbounded. Every input the program reads has a stated limit,
// checked before the memory it bounds is allocated, so the worst input under the limits
// stays under a stated peak of memory, and an input over them is refused cheaply. Each
// case runs build/bin/exactpixels as a child process and reads its peak resident memory
// from the kernel (wait4's ru_maxrss).
#include "exactpixels/base/png.hpp"
#include "exactpixels/base/test_pattern.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "support/png_chunks.hpp"

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

// Under AddressSanitizer a process's resident memory is mostly the sanitizer's own
// shadow and quarantine, so the peaks below mean nothing there: those builds skip them
// (the release build of the test workflow runs them).
#if defined(__SANITIZE_ADDRESS__)
constexpr bool peaks_are_meaningful = false;
#else
constexpr bool peaks_are_meaningful = true;
#endif
// AddressSanitizer reserves terabytes of address space for its shadow at start, so it
// cannot run at all under a limit on the address space: those builds skip such tests.
constexpr bool address_space_can_be_limited = peaks_are_meaningful;

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
          doctest::skip(!peaks_are_meaningful)) {
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
          doctest::skip(!peaks_are_meaningful)) {
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

TEST_CASE("a render that runs out of memory exits 2 with one line and writes nothing" *
          doctest::skip(!address_space_can_be_limited)) {
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
