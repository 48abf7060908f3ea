// grade_runner.cpp: the assignment kit's grader, which holds up when the code it grades
// does not. Every kit builds it as `build/bin/grade-runner` (it uses nothing of the
// library, so it builds even when the student's code does not compile).
//
//   grade-runner --tests PROGRAM --grade-file FILE [--results-json FILE]
//                [--time-limit SECONDS] [--build-dir DIR --target NAME]
//                [--total-points N] [--source-dir DIR] [--exercises FILE]
//
// With --build-dir, it first builds NAME there (`cmake --build DIR --target NAME`); if
// that fails, the grade says so, with the compiler's first error (paths shown relative to
// --source-dir), and scores 0 of --total-points. Then it asks PROGRAM (a doctest test
// program linking tests/support/grade_reporter.cpp) for its test cases and runs each in
// a process of its own, stopped after the time limit (test_time_limit_seconds below,
// unless --time-limit says otherwise). A test case that crashes (a signal such as a
// segmentation fault or an abort), hangs past the limit, exits early or throws scores 0
// with a line saying what happened, and every other test case still runs and scores.
//
// FILE gets the grade reporter's lines (STATUS EARNED/DECLARED EXERCISE NAME, then the
// reasons of a failure indented by two spaces, then TOTAL); they are printed as well.
// --results-json writes the same grade in Gradescope's results.json format
// (https://gradescope-autograders.readthedocs.io/en/latest/specs/): the total "score",
// an "output" summary, and per test case "name", "score", "max_score", "status" (passed
// or failed), "output" (the reasons) and "tags" (the exercise, see --exercises). Skipped
// test cases are left out of both totals, as in the grade reporter.
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
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string.h>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace {

/// Seconds one test case may run before it is stopped and scores 0.
constexpr int test_time_limit_seconds = 60;
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

/// Runs `argv` with standard output and error going to `output`, in a process group of
/// its own that is killed whole after `seconds`.
Ended run(const std::vector<std::string>& argv, const fs::path& output, int seconds) {
    const pid_t pid = ::fork();
    if (pid < 0) {
        throw GradeError(std::string("cannot start a process: ") + std::strerror(errno));
    }
    if (pid == 0) {
        ::setpgid(0, 0);
        std::FILE* out = std::freopen(output.c_str(), "w", stdout);
        if (out == nullptr || ::dup2(::fileno(stdout), 2) < 0) {
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
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
    Ended ended;
    int status = 0;
    for (;;) {
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
            return ended;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    if (WIFSIGNALED(status)) {
        ended.signal = WTERMSIG(status);
    } else if (WIFEXITED(status)) {
        ended.exit_code = WEXITSTATUS(status);
    }
    ::kill(-pid, SIGKILL); // anything the test left running in its group
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
    bool passed = false;
    std::vector<std::string> reasons;
};

/// "TEST RUN|SKIP POINTS EXERCISE NAME" lines, from `--list-test-cases
/// --reporters=grade`.
std::vector<Case> list_cases(const fs::path& program, const fs::path& scratch,
                             int seconds) {
    const fs::path listing = scratch / "list.txt";
    const Ended ended = run({program.string(), "--list-test-cases", "--no-skip",
                             "--reporters=grade", "--out=" + listing.string()},
                            scratch / "list-output.txt", seconds);
    if (ended.timed_out || ended.signal != 0 || ended.exit_code != 0) {
        throw GradeError(program.string() + " could not list its test cases" +
                         (ended.timed_out ? " (it timed out)" : "") + "; its output:\n" +
                         read_text(scratch / "list-output.txt"));
    }
    std::vector<Case> cases;
    for (const auto& line : lines_of(read_text(listing))) {
        std::istringstream in(line);
        std::string word, mode;
        Case test;
        in >> word >> mode >> test.points >> test.exercise;
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

/// Runs test case number `index` (1-based, in listing order) in a process of its own.
void run_case(const fs::path& program, std::size_t index, Case& test,
              const fs::path& scratch, int seconds) {
    const fs::path report = scratch / "case.txt";
    const fs::path output = scratch / "case-output.txt";
    fs::remove(report);
    const std::string n = std::to_string(index);
    const Ended ended =
        run({program.string(), "--reporters=grade", "--no-skip", "--no-exitcode",
             "--first=" + n, "--last=" + n, "--out=" + report.string()},
            output, seconds);
    // The reporter's line for this test case and the reasons below it.
    bool found = false, reported_pass = false;
    std::vector<std::string> reported;
    for (const auto& line : lines_of(read_text(report))) {
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
        test.reasons.push_back("timed out: still running after " +
                               std::to_string(seconds) +
                               " s, the time limit of one test case, so it was stopped "
                               "(an endless loop?)");
    } else if (ended.signal != 0) {
        test.reasons.push_back("crashed: the test program died of " +
                               signal_name(ended.signal));
    } else if (ended.exit_code != 0) {
        test.reasons.push_back("the test program stopped early with exit status " +
                               std::to_string(ended.exit_code) +
                               " (exit() or std::terminate in the code under test?)");
    } else if (!found) {
        test.reasons.push_back("the test program reported no result for this test case");
    } else {
        test.passed = reported_pass;
    }
    test.reasons.insert(test.reasons.end(), reported.begin(), reported.end());
    if (!test.passed && (ended.timed_out || ended.signal != 0 || ended.exit_code != 0)) {
        const auto tail = output_tail(output);
        test.reasons.insert(test.reasons.end(), tail.begin(), tail.end());
    }
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
                 tags + "]}";
    }
    const std::string total =
        "TOTAL " + std::to_string(earned) + "/" + std::to_string(declared) + " points; " +
        std::to_string(passed) + "/" + std::to_string(counted) + " test cases passed";
    lines += total + "\n";
    const std::string output = summary_note.empty() ? total : summary_note + "\n" + total;
    Report result;
    result.lines = lines;
    result.json = "{\n  \"score\": " + std::to_string(earned) +
                  ",\n  \"output\": " + json_string(output) + ",\n  \"tests\": [\n" +
                  tests + (tests.empty() ? "" : "\n") + "  ]\n}\n";
    return result;
}

struct Options {
    fs::path tests, grade_file, results_json, build_dir, source_dir;
    std::string target;
    int time_limit = test_time_limit_seconds;
    int total_points = 0;
    fs::path exercises;
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
        } else if (flag == "--target") {
            options.target = value;
        } else if (flag == "--time-limit") {
            options.time_limit = to_int(flag, value);
        } else if (flag == "--exercises") {
            options.exercises = value;
        } else if (flag == "--total-points") {
            options.total_points = to_int(flag, value);
        } else {
            throw GradeError("unknown option " + flag +
                             " (see the top of grade_runner.cpp)");
        }
    }
    if (options.tests.empty() || options.grade_file.empty()) {
        throw GradeError("usage: grade-runner --tests PROGRAM --grade-file FILE "
                         "[--results-json FILE] [--time-limit SECONDS] [--build-dir DIR "
                         "--target NAME] [--total-points N] [--source-dir DIR]");
    }
    if (options.time_limit < 1) {
        throw GradeError("--time-limit wants at least 1 second");
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

int grade(const Options& options) {
    const fs::path scratch =
        fs::temp_directory_path() / ("exactpixels-grade-" + std::to_string(::getpid()));
    fs::create_directories(scratch);
    struct Cleanup {
        fs::path path;
        ~Cleanup() {
            std::error_code ignored;
            fs::remove_all(path, ignored);
        }
    } cleanup{scratch};

    if (!options.build_dir.empty()) {
        const Ended built = run({EXACTPIXELS_GRADE_CMAKE, "--build",
                                 options.build_dir.string(), "--target", options.target},
                                scratch / "build.txt", build_time_limit_seconds);
        if (built.timed_out || built.signal != 0 || built.exit_code != 0) {
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
                         report({build}, "The submission does not compile: "
                                         "fix the first error and submit again."));
            return 0;
        }
    }
    auto cases = list_cases(options.tests, scratch, options.time_limit);
    if (cases.empty()) {
        throw GradeError(options.tests.string() + " lists no test cases");
    }
    for (std::size_t i = 0; i < cases.size(); ++i) {
        if (!cases[i].skip) {
            run_case(options.tests, i + 1, cases[i], scratch, options.time_limit);
        }
    }
    const auto exercises = options.exercises.empty() ? std::vector<Exercise>{}
                                                     : read_exercises(options.exercises);
    write_report(options, report(cases, "", exercises));
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    try {
        return grade(parse(argc, argv));
    } catch (const std::exception& error) {
        std::cerr << "grade-runner: " << error.what() << "\n";
        return 2;
    }
}
