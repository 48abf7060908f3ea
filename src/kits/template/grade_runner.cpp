// grade_runner.cpp: the assignment kit's grader, which holds up when the code it grades
// does not. Every kit builds it as `build/bin/grade-runner` (it uses nothing of the
// library, so it builds even when the student's code does not compile).
//
//   grade-runner --tests PROGRAM --grade-file FILE [--results-json FILE]
//                [--time-limit SECONDS] [--time-limits FILE] [--build-dir DIR --target
//                NAME]
//                [--total-points N] [--source-dir DIR] [--exercises FILE]
//                [--submission DIR] [--hidden-tests DIR] [--run-as UID:GID]
//   grade-runner --tests PROGRAM --measure FILE
//
// --measure runs each test case of PROGRAM (the solution's) once and writes its time
// limits to FILE (time_limits.txt): "budget SECONDS", then "LIMIT MEASURED NAME" per test
// case, by the rule at limit_multiple below; it fails if a test case fails.
//
// With --submission (a student's folder holding src/), it first puts the text of each of
// the submission's exercise regions into the same region of the kit at --source-dir
// (take_regions): nothing else of a submission is used, and a region whose text could
// reach outside it is refused (region_refusal) and graded with its stub.
//
// With --build-dir, it then builds NAME there (`cmake --build DIR --target NAME`); when
// the compiler's errors point into a taken region, that region gets its stub back and
// the build is tried again, so a region that does not compile costs its own exercise
// only (errors elsewhere put every taken region back). If the build still fails, the
// grade says so, with the compiler's first error (paths shown relative to
// --source-dir), and scores 0 of --total-points. Then it asks PROGRAM (a doctest test
// program linking tests/support/grade_reporter.cpp) for its test cases and runs each in
// a process of its own, stopped after its time limit (from --time-limits FILE, else
// --time-limit, else test_time_limit_seconds below); all of them together stop at the
// budget of FILE (else default_budget_seconds), and the test cases left are reported as
// not run. A test case that crashes (a signal such as a segmentation fault or an abort),
// hangs past the limit, exits early or throws scores 0 with a line saying what happened,
// and every other test case still runs and scores.
//
// With --run-as UID:GID (the grader running as root), the build and every test process
// run as that user, in an empty home of their own; after the build, --hidden-tests DIR
// (the hidden tests' sources) is removed, and --source-dir and --build-dir become root's
// and read-only to that user (lock_down), so code under test cannot change what a later
// test case runs or reads.
//
// Each test case reports to the runner through pipes (see Channel), never a file, and
// its line is printed as soon as it ended, "[I/N] STATUS E/D EXERCISE NAME (S s)"; a
// crash or time-out adds the command that runs that one case again.
//
// FILE gets the grade reporter's lines (STATUS EARNED/DECLARED EXERCISE NAME, then the
// reasons of a failure indented by two spaces, then TOTAL); they are printed as well.
// --results-json writes the same grade in Gradescope's results.json format
// (https://gradescope-autograders.readthedocs.io/en/latest/specs/): the total "score",
// an "output" summary, and per test case "name", "score", "max_score", "status" (passed
// or failed), "output" (the reasons), "tags" (the exercise, see --exercises) and
// "visibility" (the reporter's: "after_published" for a hidden test); with any hidden
// test case, "stdout_visibility" is "hidden" and the summary counts the visible ones.
// Skipped test cases are left out of both totals, as in the grade reporter.
//
// --exercises names the kit's exercises.txt (lines "ID KIND MARKS", written by make-kit
// from the chapter's exercise tags): the grade then opens with one line per exercise,
// "# ID [KIND, N marks]: EARNED/DECLARED points", before the test case lines, and the
// JSON tags of its tests add the kind and "difficulty N".
//
// Exit status: 0 when the grade was written (whatever it says), 2 when it could not be
// (bad options, a file that cannot be written, a test program that cannot list its
// tests), with a message naming what failed.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <grp.h>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string.h>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace {

/// Seconds a test case that time_limits.txt does not list may run before it is stopped
/// and scores 0: at least three times the slowest test case of any chapter's solution,
/// as tests/assignments_kits.cpp checks on every kit, so that it stops an endless loop
/// but not a slow machine. (Chapter 7's "the worst inputs under the limits stay under
/// the stated peaks" takes about 9 s.)
constexpr int test_time_limit_seconds = 60;
/// The rule of `--measure`, which times each test case of the solution and writes
/// time_limits.txt: a test case's limit is limit_multiple times the solution's time plus
/// limit_floor_seconds, rounded up to a whole second; all test cases together get
/// budget_multiple times the solution's total plus budget_floor_seconds. The floor
/// covers a machine that is busy or slower; the multiple, a solution that is slower
/// than the book's but not endless.
constexpr int limit_multiple = 5;
constexpr int limit_floor_seconds = 5;
constexpr int budget_multiple = 3;
constexpr int budget_floor_seconds = 30;
/// Seconds all test cases together may take when time_limits.txt sets no budget.
constexpr int default_budget_seconds = 300;
/// Seconds the build of a submission may take.
constexpr int build_time_limit_seconds = 900;
/// Lines of a crashed test case's own output quoted in its grade.
constexpr std::size_t output_tail_lines = 10;
/// Characters a quoted output line is cut to.
constexpr std::size_t output_line_chars = 200;

struct GradeError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

std::string read_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

void write_text(const fs::path& path, const std::string& text) {
    if (path.has_parent_path()) {
        fs::create_directories(path.parent_path());
    }
    std::ofstream out(path, std::ios::binary);
    out << text;
    out.close();
    if (!out) {
        throw GradeError("cannot write " + path.string());
    }
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (!line.empty() && line.back() == '\r') {
            line.pop_back();
        }
        lines.push_back(line);
    }
    return lines;
}

bool starts_with(const std::string& text, const std::string& prefix) {
    return text.compare(0, prefix.size(), prefix) == 0;
}

/// How a child process ended.
struct Ended {
    bool timed_out = false;
    int signal = 0;    ///< the signal that killed it, 0 if none
    int exit_code = 0; ///< when it exited by itself
};

/// The private line from the grader to one test process: the grade reporter
/// (tests/support/grade_reporter.cpp) reads a fresh random key from one pipe and writes
/// its lines, each starting with that key, into another; it finds the two descriptors in
/// EXACTPIXELS_GRADE_CHANNEL. No file name is passed, so there is no report file for the
/// code under test to rewrite, and a line without the key is not the reporter's: only
/// the grader writes the grade, after the test process ended.
struct Channel {
    std::string key;  ///< 32 hex digits from /dev/urandom
    std::string text; ///< what came back, every line, keyed or not
};

std::string fresh_key() {
    std::ifstream random("/dev/urandom", std::ios::binary);
    unsigned char bytes[16] = {};
    if (!random.read(reinterpret_cast<char*>(bytes), sizeof bytes)) {
        throw GradeError("cannot read /dev/urandom");
    }
    std::string key;
    for (const unsigned char byte : bytes) {
        key += "0123456789abcdef"[byte >> 4];
        key += "0123456789abcdef"[byte & 15];
    }
    return key;
}

/// The lines of `channel` that carry its key, without it.
std::vector<std::string> keyed_lines(const Channel& channel) {
    std::vector<std::string> lines;
    const std::string prefix = channel.key + " ";
    for (const auto& line : lines_of(channel.text)) {
        if (starts_with(line, prefix)) {
            lines.push_back(line.substr(prefix.size()));
        }
    }
    return lines;
}

/// The user that builds and runs the code under test, when the grader runs as root
/// (--run-as UID:GID); unset, the children run as the grader.
struct Identity {
    bool set = false;
    uid_t uid = 0;
    gid_t gid = 0;
    fs::path home; ///< the folder its processes start in (prepare_home)
};

using Milliseconds = std::chrono::milliseconds;

/// Runs `argv` with standard output and error going to `output`, in a process group of
/// its own that is killed whole after `limit`, as the user `as` when set; with
/// `channel`, the process gets its key and gives back its lines through two pipes (see
/// Channel).
Ended run(const std::vector<std::string>& argv, const fs::path& output,
          Milliseconds limit, const Identity& as, Channel* channel = nullptr) {
    int key_pipe[2] = {-1, -1}, report_pipe[2] = {-1, -1};
    if (channel != nullptr && (::pipe(key_pipe) != 0 || ::pipe(report_pipe) != 0)) {
        throw GradeError(std::string("cannot make a pipe: ") + std::strerror(errno));
    }
    const pid_t pid = ::fork();
    if (pid < 0) {
        throw GradeError(std::string("cannot start a process: ") + std::strerror(errno));
    }
    if (pid == 0) {
        ::setpgid(0, 0);
        std::signal(SIGPIPE, SIG_DFL); // as any program expects it, not as the grader's

        std::FILE* out = std::freopen(output.c_str(), "w", stdout);
        if (out == nullptr || ::dup2(::fileno(stdout), 2) < 0) {
            ::_exit(126);
        }
        if (channel != nullptr) {
            ::close(key_pipe[1]);
            ::close(report_pipe[0]);
            const std::string fds =
                std::to_string(key_pipe[0]) + "," + std::to_string(report_pipe[1]);
            ::setenv("EXACTPIXELS_GRADE_CHANNEL", fds.c_str(), 1);
        }
        // The output file and the pipes are open: now give up root for good.
        if (as.set && ((!as.home.empty() && ::chdir(as.home.c_str()) != 0) ||
                       ::setgroups(0, nullptr) != 0 || ::setgid(as.gid) != 0 ||
                       ::setuid(as.uid) != 0)) {
            std::fprintf(stderr, "cannot become user %d: %s\n", static_cast<int>(as.uid),
                         std::strerror(errno));
            ::_exit(126);
        }
        std::vector<char*> args;
        for (const auto& arg : argv) {
            args.push_back(const_cast<char*>(arg.c_str()));
        }
        args.push_back(nullptr);
        ::execv(args[0], args.data());
        std::fprintf(stderr, "cannot run %s: %s\n", args[0], std::strerror(errno));
        ::_exit(127);
    }
    ::setpgid(pid, pid);
    if (channel != nullptr) {
        ::close(key_pipe[0]);
        ::close(report_pipe[1]);
        // 32 bytes fit in any pipe's buffer: this write does not wait for the reader.
        const std::string key = channel->key + "\n";
        [[maybe_unused]] const auto written =
            ::write(key_pipe[1], key.data(), key.size());
        ::close(key_pipe[1]);
        ::fcntl(report_pipe[0], F_SETFL, O_NONBLOCK);
    }
    // Read while the process runs, so that a full pipe never stops it.
    const auto drain = [&] {
        if (channel == nullptr) {
            return;
        }
        char buffer[4096];
        for (ssize_t got; (got = ::read(report_pipe[0], buffer, sizeof buffer)) > 0;) {
            channel->text.append(buffer, static_cast<std::size_t>(got));
        }
    };
    const auto deadline = std::chrono::steady_clock::now() + limit;
    Ended ended;
    int status = 0;
    for (;;) {
        drain();
        const pid_t done = ::waitpid(pid, &status, WNOHANG);
        if (done == pid) {
            break;
        }
        if (done < 0 && errno != EINTR) {
            throw GradeError(std::string("waitpid: ") + std::strerror(errno));
        }
        if (std::chrono::steady_clock::now() >= deadline) {
            ::kill(-pid, SIGKILL);
            ::kill(pid, SIGKILL);
            ::waitpid(pid, &status, 0);
            ended.timed_out = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ::kill(-pid, SIGKILL); // anything the test left running in its group
    drain();
    if (channel != nullptr) {
        ::close(report_pipe[0]);
    }
    if (ended.timed_out) {
        return ended;
    }
    if (WIFSIGNALED(status)) {
        ended.signal = WTERMSIG(status);
    } else if (WIFEXITED(status)) {
        ended.exit_code = WEXITSTATUS(status);
    }
    return ended;
}

std::string signal_name(int signal) {
    static const std::map<int, std::string> names = {
        {SIGSEGV, "SIGSEGV, a segmentation fault: memory that is not yours was read or "
                  "written"},
        {SIGABRT, "SIGABRT, an abort: std::abort, a failed assert or an uncaught "
                  "exception"},
        {SIGFPE, "SIGFPE, an arithmetic error such as an integer division by zero"},
        {SIGBUS, "SIGBUS, a bus error: a misaligned or invalid memory access"},
        {SIGILL, "SIGILL, an illegal instruction"},
        {SIGKILL, "SIGKILL, killed from outside (out of memory?)"}};
    const auto found = names.find(signal);
    return found != names.end()
               ? found->second
               : "signal " + std::to_string(signal) + " (" + ::strsignal(signal) + ")";
}

/// The last lines a test program printed, each cut short, as quoted reason lines.
std::vector<std::string> output_tail(const fs::path& output) {
    auto lines = lines_of(read_text(output));
    lines.erase(std::remove_if(lines.begin(), lines.end(),
                               [](const std::string& line) {
                                   return line.find_first_not_of(" \t") ==
                                          std::string::npos;
                               }),
                lines.end());
    std::vector<std::string> tail;
    if (lines.empty()) {
        return tail;
    }
    tail.push_back("its last output:");
    const std::size_t first =
        lines.size() > output_tail_lines ? lines.size() - output_tail_lines : 0;
    for (std::size_t i = first; i < lines.size(); ++i) {
        std::string line = lines[i].substr(0, output_line_chars);
        for (char& c : line) {
            if (c == '\t') {
                c = ' ';
            }
        }
        tail.push_back("| " + line);
    }
    return tail;
}

/// One test case as the test program lists it, and then its result.
struct Case {
    bool skip = false;
    int points = 0;
    std::string exercise = "-";
    std::string name;
    /// Gradescope's visibility: "visible", or for a hidden test (tests/hidden/)
    /// "after_published" unless its description says otherwise.
    std::string visibility = "visible";
    bool passed = false;
    double seconds = 0; ///< how long it ran
    std::vector<std::string> reasons;
};

/// "TEST RUN|SKIP POINTS EXERCISE VISIBILITY NAME" lines, from `--list-test-cases
/// --reporters=grade`.
std::vector<Case> list_cases(const fs::path& program, const fs::path& scratch,
                             const Identity& as) {
    Channel channel{fresh_key(), {}};
    const Ended ended =
        run({program.string(), "--list-test-cases", "--no-skip", "--reporters=grade"},
            scratch / "list-output.txt", std::chrono::seconds(test_time_limit_seconds),
            as, &channel);
    if (ended.timed_out || ended.signal != 0 || ended.exit_code != 0) {
        throw GradeError(program.string() + " could not list its test cases" +
                         (ended.timed_out ? " (it timed out)" : "") + "; its output:\n" +
                         read_text(scratch / "list-output.txt"));
    }
    std::vector<Case> cases;
    for (const auto& line : keyed_lines(channel)) {
        std::istringstream in(line);
        std::string word, mode;
        Case test;
        in >> word >> mode >> test.points >> test.exercise >> test.visibility;
        in.get();
        std::getline(in, test.name);
        if (word != "TEST" || (mode != "RUN" && mode != "SKIP") || in.bad()) {
            continue; // doctest's own header lines
        }
        test.skip = mode == "SKIP";
        cases.push_back(test);
    }
    return cases;
}

/// Runs test case number `index` (1-based, in listing order) in a process of its own,
/// stopped after `limit` with `timeout_reason` as the reason.
void run_case(const fs::path& program, std::size_t index, Case& test,
              const fs::path& scratch, Milliseconds limit,
              const std::string& timeout_reason, const Identity& as) {
    const fs::path output = scratch / "case-output.txt";
    const std::string n = std::to_string(index);
    // Without --no-exitcode: a test case that fails makes the program exit non-zero, so
    // a PASS line needs the exit status to agree with it.
    Channel channel{fresh_key(), {}};
    const Ended ended = run({program.string(), "--reporters=grade", "--no-skip",
                             "--first=" + n, "--last=" + n},
                            output, limit, as, &channel);
    // The reporter's line for this test case and the reasons below it.
    bool found = false, reported_pass = false;
    int results = 0;
    std::vector<std::string> reported;
    const auto lines = keyed_lines(channel);
    for (const auto& line : lines) {
        if ((starts_with(line, "PASS ") || starts_with(line, "FAIL ")) &&
            line.size() >= test.name.size() &&
            line.compare(line.size() - test.name.size(), test.name.size(), test.name) ==
                0) {
            ++results;
        }
    }
    for (const auto& line : lines) {
        if (found && starts_with(line, "  ")) {
            reported.push_back(line.substr(2));
            continue;
        }
        if (found) {
            break;
        }
        const bool pass = starts_with(line, "PASS ");
        if ((pass || starts_with(line, "FAIL ")) && line.size() >= test.name.size() &&
            line.compare(line.size() - test.name.size(), test.name.size(), test.name) ==
                0) {
            found = true;
            reported_pass = pass;
        }
    }
    test.passed = false;
    if (ended.timed_out) {
        test.reasons.push_back(timeout_reason);
    } else if (ended.signal != 0) {
        test.reasons.push_back("crashed: the test program died of " +
                               signal_name(ended.signal));
    } else if (ended.exit_code != 0 && !found) {
        test.reasons.push_back("the test program stopped early with exit status " +
                               std::to_string(ended.exit_code) +
                               " (exit() or std::terminate in the code under test?)");
    } else if (!found) {
        test.reasons.push_back("the test program reported no result for this test case");
    } else if (results != 1) {
        test.reasons.push_back("the test program reported " + std::to_string(results) +
                               " results for this one test case");
    } else if (reported_pass != (ended.exit_code == 0)) {
        test.reasons.push_back(
            "the test program's exit status disagrees with its report");
    } else {
        test.passed = reported_pass;
    }
    test.reasons.insert(test.reasons.end(), reported.begin(), reported.end());
    if (!test.passed &&
        (ended.timed_out || ended.signal != 0 || (ended.exit_code != 0 && !found))) {
        test.reasons.push_back("to run this test case alone: " + program.string() +
                               " --first=" + n + " --last=" + n +
                               " (to find a memory error, configure a build with "
                               "-DCMAKE_CXX_FLAGS=-fsanitize=address and run it there)");
        const auto tail = output_tail(output);
        test.reasons.insert(test.reasons.end(), tail.begin(), tail.end());
    }
}

/// Why the text of a submitted exercise region cannot be taken, or "" when it can. A
/// region's text goes into the kit's file in place of the stub, so it must stay inside
/// its region: no preprocessor line (an #include of the grader's files, a #define of
/// CHECK), no line continuation that could make one, no brace closed that it did not
/// open (to leave the function and add code that runs before main), no comment or
/// literal left open past the end marker, no inline assembly or _Pragma.
std::string region_refusal(const std::vector<std::string>& lines) {
    enum class In { code, block_comment, string, character, raw_string };
    In in = In::code;
    std::string raw_end; // )delimiter" of the raw string literal being read
    int depth = 0;
    for (const auto& line : lines) {
        const auto first = line.find_first_not_of(" \t");
        if (in == In::code && first != std::string::npos &&
            (line[first] == '#' || line.compare(first, 2, "%:") == 0)) {
            return "it holds a preprocessor line";
        }
        if (!line.empty() && line.back() == '\\') {
            return "it holds a line continuation (a backslash at the end of a line)";
        }
        std::string word;
        for (std::size_t i = 0; i <= line.size(); ++i) {
            const char c = i < line.size() ? line[i] : '\n';
            const char next = i + 1 < line.size() ? line[i + 1] : '\n';
            if (in == In::code &&
                (std::isalnum(static_cast<unsigned char>(c)) || c == '_')) {
                word += c;
                continue;
            }
            // In 1'000 the quote separates digits; it opens no character literal.
            const bool digit_separator =
                in == In::code && c == '\'' && !word.empty() &&
                std::isdigit(static_cast<unsigned char>(word[0]));
            if (in == In::code && !word.empty()) {
                static const std::set<std::string> refused = {"asm", "__asm", "__asm__",
                                                              "_Pragma", "__attribute__"};
                if (refused.count(word) != 0) {
                    return "it uses " + word;
                }
                const bool raw = word.back() == 'R' && c == '"';
                word.clear();
                if (raw) {
                    const auto open = line.find('(', i);
                    if (open == std::string::npos) {
                        return "it holds a raw string literal cut by a line end";
                    }
                    raw_end = ")" + line.substr(i + 1, open - i - 1) + "\"";
                    in = In::raw_string;
                    i = open;
                    continue;
                }
            }
            switch (in) {
            case In::code:
                if (c == '/' && next == '/') {
                    i = line.size(); // a line comment: the rest of the line
                } else if (c == '/' && next == '*') {
                    in = In::block_comment;
                    ++i;
                } else if (c == '"') {
                    in = In::string;
                } else if (c == '\'' && !digit_separator) {
                    in = In::character;
                } else if (c == '{' || (c == '<' && next == '%')) {
                    ++depth;
                } else if (c == '}' || (c == '%' && next == '>')) {
                    if (--depth < 0) {
                        return "it closes a brace that it did not open";
                    }
                }
                break;
            case In::block_comment:
                if (c == '*' && next == '/') {
                    in = In::code;
                    ++i;
                }
                break;
            case In::string:
            case In::character:
                if (c == '\\') {
                    ++i;
                } else if (c == (in == In::string ? '"' : '\'')) {
                    in = In::code;
                } else if (c == '\n') {
                    return "it holds a literal cut by a line end";
                }
                break;
            case In::raw_string:
                if (line.compare(i, raw_end.size(), raw_end) == 0) {
                    i += raw_end.size() - 1;
                    in = In::code;
                }
                break;
            }
        }
    }
    if (in != In::code) {
        return "it leaves a comment or a literal open";
    }
    if (depth != 0) {
        return "it leaves a brace open";
    }
    return "";
}

/// The exercise regions of a file's lines: id -> the line numbers (0-based) of its
/// "// EXERCISE id: hint" and "// END EXERCISE id" comments.
std::map<std::string, std::pair<std::size_t, std::size_t>>
exercise_regions(const std::vector<std::string>& lines) {
    const std::string begin = "// EXERCISE ", end = "// END EXERCISE ";
    std::map<std::string, std::pair<std::size_t, std::size_t>> regions;
    std::map<std::string, std::size_t> open;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const auto first = lines[i].find_first_not_of(" \t");
        const std::string text = first == std::string::npos ? "" : lines[i].substr(first);
        if (starts_with(text, begin)) {
            std::string id = text.substr(begin.size());
            id = id.substr(0, id.find(':'));
            open[id] = i;
        } else if (starts_with(text, end)) {
            std::string id = text.substr(end.size());
            id = id.substr(0, id.find_first_of(" \t"));
            const auto opened = open.find(id);
            if (opened != open.end() && regions.count(id) == 0) {
                regions[id] = {opened->second, i};
                open.erase(opened);
            }
        }
    }
    return regions;
}

/// What take_regions did: a note per exercise, and the regions taken with the kit's
/// file and stub of each, to put the stub back when the taken text does not compile.
struct Taken {
    struct Region {
        fs::path file;
        std::vector<std::string> stub;
    };
    std::map<std::string, std::string> notes; ///< exercise id -> what happened to it
    std::map<std::string, Region> regions;    ///< exercise id -> where its text went

    std::string text() const {
        std::string joined;
        for (const auto& [id, note] : notes) {
            joined += (joined.empty() ? "" : "\n") + id + ": " + note;
        }
        return joined;
    }
};

/// Replaces the lines of region `id` of `file` with `body`.
void replace_region(const fs::path& file, const std::string& id,
                    const std::vector<std::string>& body) {
    auto lines = lines_of(read_text(file));
    const auto at = exercise_regions(lines).at(id);
    lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(at.first + 1),
                lines.begin() + static_cast<std::ptrdiff_t>(at.second));
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(at.first + 1), body.begin(),
                 body.end());
    std::string text;
    for (const auto& line : lines) {
        text += line + "\n";
    }
    write_text(file, text);
}

/// Puts the text of each exercise region of `submission` (a folder holding src/) into
/// the same region of the kit at `kit`, when region_refusal accepts it; every other
/// line stays the kit's.
Taken take_regions(const fs::path& submission, const fs::path& kit) {
    Taken taken;
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(kit / "src")) {
        if (entry.is_regular_file()) {
            files.push_back(entry.path());
        }
    }
    std::sort(files.begin(), files.end());
    for (const auto& file : files) {
        const auto kit_lines = lines_of(read_text(file));
        const auto regions = exercise_regions(kit_lines);
        if (regions.empty()) {
            continue;
        }
        const fs::path rel = fs::relative(file, kit);
        const fs::path theirs = submission / rel;
        const auto their_lines = fs::is_regular_file(theirs) ? lines_of(read_text(theirs))
                                                             : std::vector<std::string>{};
        const auto their_regions = exercise_regions(their_lines);
        for (const auto& [id, at] : regions) {
            const auto found = their_regions.find(id);
            if (found == their_regions.end()) {
                taken.notes[id] = "not found in the submission's " +
                                  rel.generic_string() + ", graded with its stub";
                continue;
            }
            const std::vector<std::string> body(
                their_lines.begin() +
                    static_cast<std::ptrdiff_t>(found->second.first + 1),
                their_lines.begin() + static_cast<std::ptrdiff_t>(found->second.second));
            const std::string refusal = region_refusal(body);
            if (!refusal.empty()) {
                taken.notes[id] = "not taken, " + refusal + "; graded with its stub";
                continue;
            }
            replace_region(file, id, body);
            taken.notes[id] = "taken from the submission";
            taken.regions[id] = {
                file, std::vector<std::string>(
                          kit_lines.begin() + static_cast<std::ptrdiff_t>(at.first + 1),
                          kit_lines.begin() + static_cast<std::ptrdiff_t>(at.second))};
        }
    }
    return taken;
}

/// The taken regions that a build log's errors point into ("FILE:LINE:COLUMN: error:"
/// or "FILE:LINE: error:", a relative FILE being relative to `build_dir`), each with the
/// first of those error lines.
std::map<std::string, std::string> regions_with_errors(const std::string& log,
                                                       const Taken& taken,
                                                       const fs::path& build_dir) {
    std::map<std::string, std::string> found;
    for (const auto& line : lines_of(log)) {
        if (line.find(": error:") == std::string::npos &&
            line.find(": fatal error:") == std::string::npos) {
            continue;
        }
        const auto colon = line.find(':');
        const auto second =
            colon == std::string::npos ? colon : line.find(':', colon + 1);
        if (second == std::string::npos) {
            continue;
        }
        fs::path file = line.substr(0, colon);
        const std::string number = line.substr(colon + 1, second - colon - 1);
        if (number.empty() ||
            number.find_first_not_of("0123456789") != std::string::npos) {
            continue;
        }
        if (file.is_relative()) {
            file = build_dir / file;
        }
        std::error_code ignored;
        file = fs::weakly_canonical(file, ignored);
        const std::size_t at_line = std::stoul(number);
        for (const auto& [id, region] : taken.regions) {
            if (found.count(id) != 0 ||
                fs::weakly_canonical(region.file, ignored) != file) {
                continue;
            }
            // Line numbers are 1-based: the body lies between the two comments.
            const auto [begin, end] =
                exercise_regions(lines_of(read_text(region.file))).at(id);
            if (at_line > begin + 1 && at_line <= end) {
                found[id] = line;
            }
        }
    }
    return found;
}

std::string json_string(const std::string& text) {
    std::string out = "\"";
    for (const char c : text) {
        switch (c) {
        case '"':
            out += "\\\"";
            break;
        case '\\':
            out += "\\\\";
            break;
        case '\n':
            out += "\\n";
            break;
        case '\r':
            out += "\\r";
            break;
        case '\t':
            out += "\\t";
            break;
        default:
            if (static_cast<unsigned char>(c) < 0x20) {
                char buffer[8];
                std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
                out += buffer;
            } else {
                out += c;
            }
        }
    }
    return out + "\"";
}

std::string join(const std::vector<std::string>& lines) {
    std::string text;
    for (const auto& line : lines) {
        text += (text.empty() ? "" : "\n") + line;
    }
    return text;
}

#ifndef EXACTPIXELS_KIT_STAMP
#define EXACTPIXELS_KIT_STAMP "no kit (the book's own build)"
#endif
/// The kit this grader came with, "chapter NN kit, version V, commit C" (make-kit stamps
/// it into the kit's CMakeLists.txt): printed first, and the first line of results.json's
/// "output", so that a grade always says which kit gave it.
const std::string kit_stamp = "Graded by the " EXACTPIXELS_KIT_STAMP;

/// The grade: the grade reporter's lines and Gradescope's results.json.
struct Report {
    std::string lines, json;
};

/// An exercise of the kit: its kind and difficulty from the chapter's tag.
struct Exercise {
    std::string id, kind;
    int marks = 0;
};

/// The lines of exercises.txt, "ID KIND MARKS".
std::vector<Exercise> read_exercises(const fs::path& file) {
    if (!fs::exists(file)) {
        throw GradeError("cannot read " + file.string());
    }
    std::vector<Exercise> exercises;
    for (const auto& line : lines_of(read_text(file))) {
        std::istringstream in(line);
        Exercise exercise;
        if (in >> exercise.id >> exercise.kind >> exercise.marks) {
            exercises.push_back(exercise);
        }
    }
    return exercises;
}

Report report(const std::vector<Case>& cases, const std::string& summary_note,
              const std::vector<Exercise>& exercises = {}) {
    int earned = 0, declared = 0, passed = 0, counted = 0;
    // The same sums over the visible test cases only, for the summary students see
    // before the hidden test cases are published.
    int shown_earned = 0, shown_declared = 0, hidden = 0;
    std::string lines, tests;
    for (const auto& exercise : exercises) {
        int got = 0, of = 0;
        for (const auto& test : cases) {
            if (test.exercise == exercise.id && !test.skip) {
                got += test.passed ? test.points : 0;
                of += test.points;
            }
        }
        lines += "# " + exercise.id + " [" + exercise.kind + ", " +
                 std::to_string(exercise.marks) +
                 (exercise.marks == 1 ? " mark" : " marks") +
                 "]: " + std::to_string(got) + "/" + std::to_string(of) + " points\n";
    }
    for (const auto& test : cases) {
        const int score = test.passed ? test.points : 0;
        if (test.skip) {
            lines += "SKIP 0/" + std::to_string(test.points) + " " + test.exercise + " " +
                     test.name + "\n";
            continue;
        }
        earned += score;
        declared += test.points;
        passed += test.passed ? 1 : 0;
        ++counted;
        if (test.visibility == "visible") {
            shown_earned += score;
            shown_declared += test.points;
        } else {
            ++hidden;
        }
        lines += std::string(test.passed ? "PASS " : "FAIL ") + std::to_string(score) +
                 "/" + std::to_string(test.points) + " " + test.exercise + " " +
                 test.name + "\n";
        for (const auto& reason : test.reasons) {
            lines += "  " + reason + "\n";
        }
        std::string tags = test.exercise == "-" ? "" : json_string(test.exercise);
        for (const auto& exercise : exercises) {
            if (exercise.id == test.exercise) {
                tags += ", " + json_string(exercise.kind) + ", " +
                        json_string("difficulty " + std::to_string(exercise.marks));
            }
        }
        tests += std::string(tests.empty() ? "" : ",\n") +
                 "    {\"name\": " + json_string(test.name) +
                 ", \"score\": " + std::to_string(score) +
                 ", \"max_score\": " + std::to_string(test.points) + ", \"status\": \"" +
                 (test.passed ? "passed" : "failed") +
                 "\", \"output\": " + json_string(join(test.reasons)) + ", \"tags\": [" +
                 tags + "], \"visibility\": " + json_string(test.visibility) + "}";
    }
    const std::string total =
        "TOTAL " + std::to_string(earned) + "/" + std::to_string(declared) + " points; " +
        std::to_string(passed) + "/" + std::to_string(counted) + " test cases passed";
    lines += total + "\n";
    // With hidden test cases, the summary counts the visible ones, and the grader's
    // printed lines (which name every test case) are hidden from students.
    const std::string shown =
        hidden == 0 ? total
                    : "TOTAL " + std::to_string(shown_earned) + "/" +
                          std::to_string(shown_declared) +
                          " points of the visible test cases; " + std::to_string(hidden) +
                          " more test case" + (hidden == 1 ? " is" : "s are") +
                          " shown when the grades are published";
    const std::string output =
        kit_stamp + "\n" + (summary_note.empty() ? shown : summary_note + "\n" + shown);
    Report result;
    result.lines = lines;
    result.json =
        "{\n  \"score\": " + std::to_string(earned) +
        ",\n  \"output\": " + json_string(output) +
        ",\n  \"stdout_visibility\": " + json_string(hidden == 0 ? "visible" : "hidden") +
        ",\n  \"tests\": [\n" + tests + (tests.empty() ? "" : "\n") + "  ]\n}\n";
    return result;
}

struct Options {
    fs::path tests, grade_file, results_json, build_dir, source_dir, submission;
    std::string target;
    int time_limit = test_time_limit_seconds;
    int total_points = 0;
    fs::path exercises, time_limits, measure, hidden_tests;
    Identity run_as;
};

int to_int(const std::string& flag, const std::string& value) {
    std::size_t used = 0;
    int number = -1;
    try {
        number = std::stoi(value, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != value.size() || number < 0) {
        throw GradeError(flag + " wants a whole number, got '" + value + "'");
    }
    return number;
}

Options parse(int argc, char** argv) {
    Options options;
    for (int i = 1; i < argc; ++i) {
        const std::string flag = argv[i];
        if (i + 1 >= argc) {
            throw GradeError(flag + " wants a value");
        }
        const std::string value = argv[++i];
        if (flag == "--tests") {
            options.tests = value;
        } else if (flag == "--grade-file") {
            options.grade_file = value;
        } else if (flag == "--results-json") {
            options.results_json = value;
        } else if (flag == "--build-dir") {
            options.build_dir = value;
        } else if (flag == "--source-dir") {
            options.source_dir = value;
        } else if (flag == "--submission") {
            options.submission = value;
        } else if (flag == "--target") {
            options.target = value;
        } else if (flag == "--time-limit") {
            options.time_limit = to_int(flag, value);
        } else if (flag == "--exercises") {
            options.exercises = value;
        } else if (flag == "--total-points") {
            options.total_points = to_int(flag, value);
        } else if (flag == "--time-limits") {
            options.time_limits = value;
        } else if (flag == "--measure") {
            options.measure = value;
        } else if (flag == "--hidden-tests") {
            options.hidden_tests = value;
        } else if (flag == "--run-as") {
            const auto colon = value.find(':');
            if (colon == std::string::npos) {
                throw GradeError("--run-as wants UID:GID, got '" + value + "'");
            }
            options.run_as.set = true;
            options.run_as.uid = static_cast<uid_t>(to_int(flag, value.substr(0, colon)));
            options.run_as.gid =
                static_cast<gid_t>(to_int(flag, value.substr(colon + 1)));
        } else {
            throw GradeError("unknown option " + flag +
                             " (see the top of grade_runner.cpp)");
        }
    }
    if (options.tests.empty() ||
        (options.grade_file.empty() && options.measure.empty())) {
        throw GradeError(
            "usage: grade-runner --tests PROGRAM (--grade-file FILE | --measure "
            "FILE) (see the top of grade_runner.cpp for the other options)");
    }
    if (options.time_limit < 1) {
        throw GradeError("--time-limit wants at least 1 second");
    }
    if (!options.submission.empty() && options.source_dir.empty()) {
        throw GradeError("--submission wants --source-dir (the kit) too");
    }
    if (!options.build_dir.empty() && options.target.empty()) {
        throw GradeError("--build-dir wants --target too");
    }
    return options;
}

/// The first line of a build log that reports an error, with `source_dir`'s prefix gone.
std::string first_error(const std::string& log, const fs::path& source_dir) {
    const auto lines = lines_of(log);
    std::string found;
    for (const char* mark : {": error:", ": fatal error:", "error:", "Error"}) {
        const auto at =
            std::find_if(lines.begin(), lines.end(), [&](const std::string& l) {
                return l.find(mark) != std::string::npos;
            });
        if (at != lines.end()) {
            found = *at;
            break;
        }
    }
    if (found.empty()) {
        found = lines.empty() ? "(the build printed nothing)" : lines.back();
    }
    if (!source_dir.empty()) {
        std::string prefix = fs::absolute(source_dir).lexically_normal().string();
        if (!prefix.empty() && prefix.back() != '/') {
            prefix += '/';
        }
        for (auto at = found.find(prefix); at != std::string::npos;
             at = found.find(prefix)) {
            found.erase(at, prefix.size());
        }
    }
    return found.substr(0, 2 * output_line_chars);
}

void write_report(const Options& options, const Report& grade) {
    write_text(options.grade_file, grade.lines);
    if (!options.results_json.empty()) {
        write_text(options.results_json, grade.json);
    }
    std::cout << grade.lines << std::flush;
}

/// The time limits of time_limits.txt (written by --measure): per test case, in
/// seconds, and a budget for all test cases together.
struct TimeLimits {
    std::map<std::string, int> per_case;
    int budget = default_budget_seconds;
};

/// Reads "budget SECONDS" and "LIMIT MEASURED NAME" lines ('#' starts a comment line);
/// no file means no per-case limits and the default budget.
TimeLimits read_time_limits(const fs::path& file) {
    TimeLimits limits;
    if (file.empty() || !fs::exists(file)) {
        return limits;
    }
    const auto lines = lines_of(read_text(file));
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (lines[i].empty() || lines[i][0] == '#') {
            continue;
        }
        std::istringstream in(lines[i]);
        std::string first, second, name;
        in >> first >> second;
        in.get();
        std::getline(in, name);
        const bool budget = first == "budget";
        const std::string where = file.string() + ":" + std::to_string(i + 1);
        if (second.empty() || (budget ? !name.empty() : name.empty())) {
            throw GradeError(where +
                             ": not 'budget SECONDS' or 'LIMIT MEASURED NAME': '" +
                             lines[i] + "'");
        }
        const int seconds = to_int(where, budget ? second : first);
        if (seconds < 1) {
            throw GradeError(where +
                             ": a time limit of at least 1 second is wanted, got '" +
                             lines[i] + "'");
        }
        if (budget) {
            limits.budget = seconds;
        } else {
            limits.per_case[name] = seconds;
        }
    }
    return limits;
}

/// This process's scratch folder, removed when it ends; only the grader can enter it.
struct Scratch {
    fs::path path =
        fs::temp_directory_path() / ("exactpixels-grade-" + std::to_string(::getpid()));
    Scratch() {
        fs::create_directories(path);
        fs::permissions(path, fs::perms::owner_all);
    }
    ~Scratch() {
        std::error_code ignored;
        fs::remove_all(path, ignored);
    }
};

/// After the build, when the code under test runs as another user: the kit and the
/// build become root's and read-only to that user (a test case cannot change what a
/// later one runs or reads, such as the test program or the command-line program),
/// and the test program can be run but not read.
void lock_down(const Options& options) {
    for (const auto& top : {options.source_dir, options.build_dir}) {
        if (top.empty()) {
            continue;
        }
        std::vector<fs::path> paths{top};
        for (const auto& entry : fs::recursive_directory_iterator(top)) {
            paths.push_back(entry.path());
        }
        for (const auto& path : paths) {
            struct stat info {};
            if (::lstat(path.c_str(), &info) != 0 || ::lchown(path.c_str(), 0, 0) != 0) {
                throw GradeError("cannot make " + path.string() +
                                 " root's: " + std::strerror(errno));
            }
            // No set-user-ID bit survives: a file the user made must not run as root.
            if (!S_ISLNK(info.st_mode)) {
                ::chmod(path.c_str(), info.st_mode & 0755);
            }
        }
    }
    ::chmod(options.tests.c_str(), 0711);
}

/// The folder the code under test runs in (its home and TMPDIR too): its own, empty.
void prepare_home(const fs::path& home, const Identity& as) {
    fs::create_directories(home);
    if (as.set && ::chown(home.c_str(), as.uid, as.gid) != 0) {
        throw GradeError("cannot give " + home.string() +
                         " to the grading user: " + std::strerror(errno));
    }
    ::setenv("HOME", home.c_str(), 1);
    ::setenv("TMPDIR", home.c_str(), 1);
}

/// Runs every test case of the solution once and writes its time limits (the rule at
/// limit_multiple above) to options.measure.
int measure(const Options& options) {
    const Scratch scratch;
    auto cases = list_cases(options.tests, scratch.path, options.run_as);
    std::string lines;
    double total = 0;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        auto& test = cases[i];
        if (test.skip) {
            continue;
        }
        const auto started = std::chrono::steady_clock::now();
        run_case(options.tests, i + 1, test, scratch.path,
                 std::chrono::seconds(test_time_limit_seconds),
                 "still running after " + std::to_string(test_time_limit_seconds) + " s",
                 options.run_as);
        const std::chrono::duration<double> took =
            std::chrono::steady_clock::now() - started;
        if (!test.passed) {
            throw GradeError("the solution fails test case \"" + test.name +
                             "\", so its time cannot be measured: " + join(test.reasons));
        }
        total += took.count();
        const int limit = static_cast<int>(
            std::ceil(limit_multiple * took.count() + limit_floor_seconds));
        char seconds[32];
        std::snprintf(seconds, sizeof seconds, "%.3f", took.count());
        lines += std::to_string(limit) + " " + seconds + " " + test.name + "\n";
    }
    const int budget =
        static_cast<int>(std::ceil(budget_multiple * total + budget_floor_seconds));
    write_text(
        options.measure,
        "# Time limits in seconds, measured on the book's solution by grade-runner "
        "--measure:\n# a test case's limit is " +
            std::to_string(limit_multiple) + " times the solution's time plus " +
            std::to_string(limit_floor_seconds) + " s; all test cases together get " +
            std::to_string(budget_multiple) + " times the solution's total plus " +
            std::to_string(budget_floor_seconds) +
            " s (rounded up).\n# LIMIT MEASURED NAME\nbudget " + std::to_string(budget) +
            "\n" + lines);
    std::cout << "grade-runner: wrote " << options.measure.string() << ": "
              << cases.size() << " test cases, " << total << " s in all, budget "
              << budget << " s\n";
    return 0;
}

int grade(Options options) {
    const Scratch scratch_folder;
    const fs::path& scratch = scratch_folder.path;
    const TimeLimits limits = read_time_limits(options.time_limits);

    std::cout << kit_stamp << "\n" << std::flush;
    // An earlier grade must not stand for this one if this one cannot be written.
    fs::remove(options.grade_file);
    if (!options.results_json.empty()) {
        fs::remove(options.results_json);
    }
    if (options.run_as.set) {
        options.run_as.home = scratch / "home";
        prepare_home(options.run_as.home, options.run_as);
        fs::permissions(scratch, fs::perms::owner_all | fs::perms::group_exec |
                                     fs::perms::others_exec);
    }
    // Of a submission, only the text of its exercise regions: the rest is the kit's.
    Taken taken;
    if (!options.submission.empty()) {
        taken = take_regions(options.submission, options.source_dir);
        std::cout << taken.text() << "\n" << std::flush;
    }

    // A region whose text does not compile gets its stub back, so that it costs its own
    // exercise only; when the errors point into no taken region, every taken region does.
    while (!options.build_dir.empty()) {
        const Ended built =
            run({EXACTPIXELS_GRADE_CMAKE, "--build", options.build_dir.string(),
                 "--target", options.target},
                scratch / "build.txt", std::chrono::seconds(build_time_limit_seconds),
                options.run_as);
        const bool failed = built.timed_out || built.signal != 0 || built.exit_code != 0;
        if (failed && !built.timed_out && built.signal == 0 && !taken.regions.empty()) {
            const std::string log = read_text(scratch / "build.txt");
            auto guilty = regions_with_errors(log, taken, options.build_dir);
            if (guilty.empty()) {
                for (const auto& [id, region] : taken.regions) {
                    guilty[id] = first_error(log, options.source_dir);
                }
            }
            for (const auto& [id, error] : guilty) {
                replace_region(taken.regions.at(id).file, id, taken.regions.at(id).stub);
                taken.regions.erase(id);
                taken.notes[id] =
                    "does not compile, graded with its stub; the compiler's "
                    "first error: " +
                    first_error(error, options.source_dir);
            }
            continue;
        }
        if (failed) {
            const std::string log = read_text(scratch / "build.txt");
            Case build;
            build.name = "the submission compiles";
            build.points = options.total_points;
            build.reasons = {built.timed_out
                                 ? "the build took longer than " +
                                       std::to_string(build_time_limit_seconds) + " s"
                                 : "the submission does not compile, so no test ran; "
                                   "the compiler's first error:",
                             "| " + first_error(log, options.source_dir)};
            write_report(options,
                         report({build}, taken.text() +
                                             (taken.notes.empty() ? "" : "\n") +
                                             "The submission does not compile: "
                                             "fix the first error and submit again."));
            return 0;
        }
        break;
    }
    // The hidden tests are compiled in; their text is not left for the code under test.
    if (!options.hidden_tests.empty()) {
        fs::remove_all(options.hidden_tests);
    }
    if (options.run_as.set) {
        lock_down(options);
    }
    auto cases = list_cases(options.tests, scratch, options.run_as);
    if (cases.empty()) {
        throw GradeError(options.tests.string() + " lists no test cases");
    }
    // Each test case's line as soon as it ended, with its time, so that a slow or hung
    // case shows which; the whole grade follows at the end. Each test case stops at its
    // own limit, and all together at the budget: past it, the rest are not run.
    const std::string budget = std::to_string(limits.budget) + " s";
    const auto budget_end =
        std::chrono::steady_clock::now() + std::chrono::seconds(limits.budget);
    for (std::size_t i = 0; i < cases.size(); ++i) {
        auto& test = cases[i];
        const auto started = std::chrono::steady_clock::now();
        const auto left = std::chrono::duration_cast<Milliseconds>(budget_end - started);
        const auto own = limits.per_case.find(test.name);
        const int limit = own != limits.per_case.end() ? own->second : options.time_limit;
        const bool not_run = !test.skip && left.count() <= 0;
        if (not_run) {
            test.reasons.push_back("not run: the " + budget +
                                   " that all test cases may take together were used up "
                                   "by the test cases before it");
        } else if (!test.skip && left < std::chrono::seconds(limit)) {
            run_case(options.tests, i + 1, test, scratch, left,
                     "stopped: the " + budget +
                         " that all test cases may take together ran out while it ran",
                     options.run_as);
        } else if (!test.skip) {
            const std::string seconds = std::to_string(limit) + " s";
            run_case(options.tests, i + 1, test, scratch, std::chrono::seconds(limit),
                     "time limit " + seconds + " exceeded: still running after " +
                         seconds + ", so it was stopped (an endless loop?)",
                     options.run_as);
        }
        const std::chrono::duration<double> took =
            std::chrono::steady_clock::now() - started;
        char seconds[32];
        std::snprintf(seconds, sizeof seconds, "%.2f", took.count());
        std::cout << "[" << i + 1 << "/" << cases.size() << "] "
                  << (test.skip     ? "SKIP"
                      : not_run     ? "NOT RUN"
                      : test.passed ? "PASS"
                                    : "FAIL")
                  << ' ' << (test.passed ? test.points : 0) << '/' << test.points << ' '
                  << test.exercise << ' ' << test.name << " (" << seconds << " s)\n"
                  << std::flush;
    }
    const auto exercises = options.exercises.empty() ? std::vector<Exercise>{}
                                                     : read_exercises(options.exercises);
    write_report(options, report(cases, taken.text(), exercises));
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    // A test program that ends before it reads its key (it could not start, or crashed
    // first) must not take the grader with it: the key's write then fails with EPIPE.
    std::signal(SIGPIPE, SIG_IGN);
    try {
        const Options options = parse(argc, argv);
        return options.measure.empty() ? grade(options) : measure(options);
    } catch (const std::exception& error) {
        std::cerr << "grade-runner: " << error.what() << "\n";
        return 2;
    }
}
