// Chapter 0's output discipline, tested through all three commands (pattern, coverage,
// render), so in chapter 7's suite, whose kit has every layer: the one output
// discipline of every file the project writes
// (atomic_file.hpp). Nothing lost: a write that fails (a full disk, a file size limit)
// leaves the old file as it was and no temporary file. Nothing clobbered: an output that
// is an input, a device, a FIFO, a directory or a symbolic link is refused, and files
// that merely look like temporaries are neither destroyed nor followed.
#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/base/test_pattern.hpp"
#include "support/printing.hpp"
#include "support/process.hpp"

#include <doctest/doctest.h>

#include <array>
#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

using namespace exactpixels;
namespace fs = std::filesystem;
using testing::cli_path;
using testing::run_command;

namespace {

fs::path scratch_folder(const std::string& name) {
    auto folder = fs::temp_directory_path() /
                  ("exactpixels-output-" + name + "-" + std::to_string(::getpid()));
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

/// The names in `folder` (no temporary may hide among them).
std::set<std::string> names_in(const fs::path& folder) {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(folder)) {
        names.insert(entry.path().filename().string());
    }
    return names;
}

/// `path` in single quotes, for the shell.
std::string quoted(const fs::path& path) {
    std::string text = "'";
    text += path.string();
    text += '\'';
    return text;
}

/// A textured scene "scene.toml" in `folder` whose texture is "wall.png" beside it.
fs::path write_textured_scene(const fs::path& folder) {
    write_png(folder / "wall.png", draw_f_pattern(1));
    std::ofstream(folder / "scene.toml") << "[image]\nwidth = 16\nheight = 12\n"
                                            "[textures.wall]\nkind = \"png\"\n"
                                            "file = \"wall.png\"\n"
                                            "[[mesh]]\nprimitive = \"triangles\"\n"
                                            "positions = [[0, 0, 1], [1, 0, 1], "
                                            "[0, 1, 1]]\n"
                                            "uv = [[0, 0], [4, 0], [0, 4]]\n"
                                            "texture = \"wall\"\n";
    return folder / "scene.toml";
}

/// Runs the CLI with `arguments` under a file size limit of `blocks` (of 512 bytes, as
/// /bin/sh's ulimit counts them): every file the program writes past it fails (EFBIG).
testing::CommandResult run_limited(int blocks, const std::string& arguments,
                                   const std::string& input = "") {
    return run_command("sh -c \"ulimit -f " + std::to_string(blocks) + "; exec " +
                           cli_path() + " " + arguments + "\"",
                       input);
}

/// A pipe whose buffer is full: a write to its end [1] waits until someone reads [0].
std::array<int, 2> full_pipe() {
    int ends[2] = {-1, -1};
    REQUIRE(::pipe2(ends, O_CLOEXEC) == 0);
    ::fcntl(ends[1], F_SETFL, O_NONBLOCK);
    const std::string block(4096, 'x');
    while (::write(ends[1], block.data(), block.size()) > 0) {
    }
    while (::write(ends[1], "x", 1) > 0) { // whatever room a whole block did not fit
    }
    ::fcntl(ends[1], F_SETFL, 0); // the child's writes wait rather than fail
    return {ends[0], ends[1]};
}

/// Starts `exactpixels render SCENE -o OUT` with `stdout_fd` as its standard output,
/// standard error to /dev/null and every signal at its default action (a test runner
/// may have set some to be ignored, and the child would inherit that). Returns its pid.
pid_t start_render(const fs::path& scene, const fs::path& out, int stdout_fd) {
    const pid_t child = ::fork();
    if (child == 0) {
        for (const int signal : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) {
            std::signal(signal, SIG_DFL);
        }
        sigset_t none;
        sigemptyset(&none);
        ::sigprocmask(SIG_SETMASK, &none, nullptr);
        const int null = ::open("/dev/null", O_RDWR);
        ::dup2(null, 0);
        ::dup2(stdout_fd, 1);
        ::dup2(null, 2);
        ::execl(EXACTPIXELS_CLI, EXACTPIXELS_CLI, "render", scene.c_str(), "-o",
                out.c_str(), static_cast<char*>(nullptr));
        ::_exit(127);
    }
    REQUIRE(child > 0);
    return child;
}

/// Whether a temporary file (".ep-...") is in `folder`.
bool has_temporary(const fs::path& folder) {
    for (const std::string& name : names_in(folder)) {
        if (name.starts_with(".ep-")) {
            return true;
        }
    }
    return false;
}

/// Waits until a temporary file appears in `folder`, at most `limit`; whether it did.
bool wait_for_temporary(const fs::path& folder, std::chrono::milliseconds limit) {
    const auto end = std::chrono::steady_clock::now() + limit;
    while (!has_temporary(folder)) {
        if (std::chrono::steady_clock::now() > end) {
            return false;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return true;
}

/// The signal that ended the child `pid` (0 if it exited).
int wait_for_signal(pid_t pid) {
    int status = 0;
    REQUIRE(::waitpid(pid, &status, 0) == pid);
    return WIFSIGNALED(status) ? WTERMSIG(status) : 0;
}

/// The permission bits of `path`.
mode_t mode_of(const fs::path& path) {
    struct stat info {};
    REQUIRE(::stat(path.c_str(), &info) == 0);
    return info.st_mode & 0777;
}

} // namespace

TEST_CASE("a failed write keeps the old file and leaves no temporary") {
    const auto folder = scratch_folder("fsize");
    const fs::path out = folder / "f.png";
    write_png(out, draw_f_pattern(1));
    const std::string before = slurp(out);
    const auto names = names_in(folder);

    // pattern: a 4 KiB limit against a PNG of about 6 KiB.
    const auto pattern = run_limited(8, "pattern --cell 64 -o " + quoted(out));
    CHECK(pattern.exit_code == 2);
    CHECK(pattern.err.find(out.string()) != std::string::npos);
    CHECK(pattern.err.find("File too large") != std::string::npos);
    CHECK(slurp(out) == before);
    CHECK(names_in(folder) == names);

    // render: the shipped corridor's PNG is several KiB too.
    const auto render = run_limited(2, "render -o " + quoted(out));
    CHECK(render.exit_code == 2);
    CHECK(render.out.find("wrote") == std::string::npos);
    CHECK(slurp(out) == before);
    CHECK(names_in(folder) == names);

    // coverage -o: 64x64 counts are 8 KiB of text.
    const fs::path counts = folder / "counts.txt";
    std::ofstream(counts) << "old counts\n";
    const auto coverage = run_limited(4, "coverage -o " + quoted(counts), "64 64\n");
    CHECK(coverage.exit_code == 2);
    CHECK(coverage.err.find("counts.txt") != std::string::npos);
    CHECK(slurp(counts) == "old counts\n");
    CHECK(names_in(folder).size() == names.size() + 1);

    // Without the limit the same commands succeed: the limit was the only cause.
    CHECK(run_command(cli_path() + " pattern --cell 64 -o " + quoted(out)).exit_code ==
          0);
    CHECK(read_png(out) == draw_f_pattern(64));
    CHECK(
        run_command(cli_path() + " coverage -o " + quoted(counts), "64 64\n").exit_code ==
        0);
    CHECK(slurp(counts).size() == 64 * 64 * 2);
    fs::remove_all(folder);
}

TEST_CASE("standard output that cannot be written is an error with exit code 2") {
    const auto coverage = run_command("sh -c \"" + cli_path() + " coverage >/dev/full\"",
                                      "2 1\n0 0 2 0 0 1\n");
    CHECK(coverage.exit_code == 2);
    CHECK(coverage.err.find("standard output") != std::string::npos);
    CHECK(coverage.err.find("No space left") != std::string::npos);

    const auto folder = scratch_folder("stdout");
    const auto render = run_command("sh -c \"" + cli_path() + " render --report -o " +
                                    quoted(folder / "c.png") + " >/dev/full\"");
    CHECK(render.exit_code == 2);
    CHECK(render.err.find("standard output") != std::string::npos);

    // The same commands with a writable standard output succeed.
    CHECK(run_command(cli_path() + " coverage", "2 1\n0 0 2 0 0 1\n").out == "1 0\n");
    fs::remove_all(folder);
}

TEST_CASE("an output that is the scene file or one of its textures is refused") {
    const auto folder = scratch_folder("inputs");
    const fs::path scene = write_textured_scene(folder);
    const std::string scene_text = slurp(scene);
    const std::string texture_bytes = slurp(folder / "wall.png");
    fs::create_hard_link(folder / "wall.png", folder / "alias.png");

    const fs::path victims[] = {scene, folder / "wall.png", folder / "alias.png",
                                folder / "." / "scene.toml"};
    for (const fs::path& victim : victims) {
        CAPTURE(victim);
        const auto result = run_command(cli_path() + " render " + quoted(scene) + " -o " +
                                        quoted(victim));
        CHECK(result.exit_code == 2);
        CHECK(result.err.find("it is the input file") != std::string::npos);
        CHECK(result.out.empty());
    }
    CHECK(slurp(scene) == scene_text);
    CHECK(slurp(folder / "wall.png") == texture_bytes);
    CHECK(names_in(folder) ==
          std::set<std::string>{"scene.toml", "wall.png", "alias.png"});

    // Another name in the same folder is fine.
    const auto ok = run_command(cli_path() + " render " + quoted(scene) + " -o " +
                                quoted(folder / "out.png"));
    CHECK(ok.exit_code == 0);
    CHECK(read_png(folder / "out.png").width() == 16);
    fs::remove_all(folder);
}

TEST_CASE("coverage refuses an output that is the file read as standard input") {
    const auto folder = scratch_folder("stdin");
    const fs::path triangles = folder / "t.txt";
    const std::string text = "2 1\n0 0 2 0 0 1\n";
    std::ofstream(triangles) << text;
    fs::create_hard_link(triangles, folder / "alias.txt");
    for (const char* victim : {"t.txt", "alias.txt"}) {
        CAPTURE(victim);
        const auto result =
            run_command("sh -c \"" + cli_path() + " coverage -o " +
                        quoted(folder / victim) + " < " + quoted(triangles) + "\"");
        CHECK(result.exit_code == 2);
        CHECK(result.err.find("it is the file read as standard input") !=
              std::string::npos);
        CHECK(slurp(triangles) == text);
    }
    CHECK(names_in(folder) == std::set<std::string>{"t.txt", "alias.txt"});
    // Another output, or the input piped in, is fine.
    const auto ok =
        run_command("sh -c \"" + cli_path() + " coverage -o " +
                    quoted(folder / "counts.txt") + " < " + quoted(triangles) + "\"");
    CHECK(ok.exit_code == 0);
    CHECK(slurp(folder / "counts.txt") == "1 0\n");
    fs::remove_all(folder);
}

TEST_CASE("coverage: a read error on standard input is an error, not its end") {
    // A directory as standard input: the first read fails (EISDIR), which std::cin
    // reports as the end of the input.
    const auto result = run_command("sh -c \"" + cli_path() + " coverage < /\"");
    CHECK(result.exit_code == 2);
    CHECK(result.err.find("standard input: cannot read") != std::string::npos);
    CHECK(result.out.empty());
}

TEST_CASE("an output that is not a regular file is refused and left as it was") {
    const auto folder = scratch_folder("special");
    ::mkfifo((folder / "fifo").c_str(), 0600);
    fs::create_directory(folder / "dir");
    std::ofstream(folder / "precious") << "precious";
    fs::create_symlink(folder / "precious", folder / "link.png");
    const fs::path targets[] = {"/dev/null", folder / "fifo", folder / "dir",
                                folder / "link.png"};
    for (const fs::path& target : targets) {
        CAPTURE(target);
        CHECK_THROWS_WITH_AS(write_png(target, draw_f_pattern(1)),
                             doctest::Contains(target.string().c_str()), Error);
        const auto result = run_command(cli_path() + " pattern -o " + quoted(target));
        CHECK(result.exit_code == 2);
        const bool says_why = result.err.find("regular file") != std::string::npos ||
                              result.err.find("directory") != std::string::npos;
        CHECK(says_why);
    }
    struct stat info {};
    const bool still_a_device = ::stat("/dev/null", &info) == 0 && S_ISCHR(info.st_mode);
    CHECK(still_a_device);
    CHECK(fs::is_fifo(folder / "fifo"));
    CHECK(fs::is_empty(folder / "dir"));
    CHECK(fs::is_symlink(folder / "link.png"));
    CHECK(slurp(folder / "precious") == "precious");
    fs::remove_all(folder);
}

TEST_CASE("files named like the old temporary are neither destroyed nor followed") {
    const auto folder = scratch_folder("partial");
    std::ofstream(folder / "f.png.partial") << "someone's file";
    std::ofstream(folder / "precious") << "precious";
    fs::create_symlink(folder / "precious", folder / "g.png.partial");
    write_png(folder / "f.png", draw_f_pattern(2));
    write_png(folder / "g.png", draw_f_pattern(2));
    CHECK(slurp(folder / "f.png.partial") == "someone's file");
    CHECK(fs::is_symlink(folder / "g.png.partial"));
    CHECK(slurp(folder / "precious") == "precious");
    CHECK(read_png(folder / "g.png") == draw_f_pattern(2));
    CHECK(names_in(folder) == std::set<std::string>{"f.png", "f.png.partial", "g.png",
                                                    "g.png.partial", "precious"});
    fs::remove_all(folder);
}

TEST_CASE("an empty output path is an error for every command") {
    CHECK_THROWS_WITH_AS(write_png("", draw_f_pattern(1)),
                         doctest::Contains("output path is empty"), Error);
    CHECK_THROWS_AS(write_file_atomically("", "text", "x"), Error);
    const auto folder = scratch_folder("empty");
    for (const std::string command : {"pattern", "render", "coverage"}) {
        CAPTURE(command);
        const auto result = run_command("cd " + quoted(folder) + " && " + cli_path() +
                                            " " + command + " -o ''",
                                        "2 2\n");
        CHECK(result.exit_code == 2);
        CHECK(result.err.find("output path is empty") != std::string::npos);
    }
    CHECK(fs::is_empty(folder));
    fs::remove_all(folder);
}

TEST_CASE("an output name of 255 bytes, the longest legal one, is written") {
    const auto folder = scratch_folder("long");
    const fs::path out = folder / (std::string(251, 'a') + ".png");
    write_png(out, draw_f_pattern(1));
    CHECK(read_png(out) == draw_f_pattern(1));
    write_file_atomically(out, "PNG", slurp(out)); // replacing it works too
    CHECK(names_in(folder) == std::set<std::string>{out.filename().string()});
    fs::remove_all(folder);
}

TEST_CASE("a written file gets the usual permissions, not a temporary's") {
    const auto folder = scratch_folder("mode");
    const mode_t mask = ::umask(022);
    write_file_atomically(folder / "t.txt", "text", "hello\n");
    ::umask(mask);
    struct stat info {};
    REQUIRE(::stat((folder / "t.txt").c_str(), &info) == 0);
    CHECK((info.st_mode & 0777) == 0644);
    CHECK(slurp(folder / "t.txt") == "hello\n");
    fs::remove_all(folder);
}

TEST_CASE("a render whose standard output fails writes no file and replaces none") {
    const auto folder = scratch_folder("stdout-first");
    const fs::path scene = write_textured_scene(folder);
    std::ofstream(folder / "old.png") << "old picture";
    for (const char* out : {"new.png", "old.png"}) {
        for (const std::string flags : {"", " --report", " --check"}) {
            CAPTURE(out);
            CAPTURE(flags);
            const auto result =
                run_command("sh -c \"" + cli_path() + " render " + quoted(scene) + flags +
                            " -o " + quoted(folder / out) + " >/dev/full\"");
            CHECK(result.exit_code == 2);
            CHECK(result.err.find("standard output") != std::string::npos);
        }
    }
    CHECK(slurp(folder / "old.png") == "old picture");
    CHECK(names_in(folder) == std::set<std::string>{"scene.toml", "wall.png", "old.png"});
    fs::remove_all(folder);
}

TEST_CASE("a signal while the output is unfinished removes its temporary file") {
    const auto folder = scratch_folder("signal");
    const fs::path scene = write_textured_scene(folder);
    const std::set<std::string> before = names_in(folder);
    // The render prints its last line before it renames the PNG into place: on a full
    // pipe it waits there, its temporary file written, until the signal comes.
    for (const int signal : {SIGTERM, SIGINT, SIGHUP}) {
        CAPTURE(signal);
        const std::array<int, 2> pipe = full_pipe();
        const pid_t child = start_render(scene, folder / "out.png", pipe[1]);
        ::close(pipe[1]);
        CHECK(wait_for_temporary(folder, std::chrono::seconds(10)));
        ::kill(child, signal);
        CHECK(wait_for_signal(child) == signal);
        ::close(pipe[0]);
        REQUIRE(names_in(folder) == before); // a temporary left would fool the next wait
    }
    // A pipe nobody reads any more: printing the last line raises SIGPIPE.
    std::array<int, 2> closed = full_pipe();
    ::close(closed[0]);
    const pid_t child = start_render(scene, folder / "out.png", closed[1]);
    ::close(closed[1]);
    CHECK(wait_for_signal(child) == SIGPIPE);
    CHECK(names_in(folder) == before);
    fs::remove_all(folder);
}

TEST_CASE("a replaced file keeps its mode, a new one gets 0666 less the umask") {
    const auto folder = scratch_folder("keep-mode");
    std::ofstream(folder / "secret.txt") << "old";
    fs::permissions(folder / "secret.txt", fs::perms(0600));
    std::ofstream(folder / "shared.txt") << "old";
    fs::permissions(folder / "shared.txt", fs::perms(0664));
    const mode_t mask = ::umask(027);
    write_file_atomically(folder / "new.txt", "text", "new\n");
    write_file_atomically(folder / "secret.txt", "text", "new\n");
    write_file_atomically(folder / "shared.txt", "text", "new\n");
    ::umask(mask);
    CHECK(mode_of(folder / "new.txt") == 0640);
    CHECK(mode_of(folder / "secret.txt") == 0600);
    CHECK(mode_of(folder / "shared.txt") == 0664);
    CHECK(slurp(folder / "secret.txt") == "new\n");

    // Through a command, replacing its own earlier output.
    const fs::path png = folder / "f.png";
    REQUIRE(run_command(cli_path() + " pattern -o " + quoted(png)).exit_code == 0);
    fs::permissions(png, fs::perms(0600));
    REQUIRE(run_command(cli_path() + " pattern --cell 2 -o " + quoted(png)).exit_code ==
            0);
    CHECK(mode_of(png) == 0600);
    CHECK(read_png(png) == draw_f_pattern(2));
    fs::remove_all(folder);
}
