// Assignment kits (src/kits/): make-kit turns the book's own tested code into a chapter's
// starter project; these tests prove that the kits are what the issue asks for.
//
// - make-kit reads exercise regions exactly as book/AUTHORING.md defines them and refuses
//   malformed ones (naming file and line), and refuses a region no test checks;
// - on a fixture tree (tests/fixtures/kits/tree): the kit holds the chapter's stubs,
//   an earlier chapter's solutions and a later chapter's stubs, no marker line, the
//   example, tests and fixture data; the zip holds the same files; the grade is exactly
//   the expected lines, twice the same;
// - no kit of the book holds the answer lines of an exercise of its own chapter or a
//   later one (a search written here, tried on the fixture tree);
// - for every chapter of the book: its kit configures and builds on its own, outside the
//   source tree; fresh, every test of an exercise fails and every other test passes;
//   with the chapter's own exercises solved (a later chapter's left as stubs), every
//   test passes and the grade reaches full marks; restored, the kit's code is the book's
//   code with the markers removed.
//
// Time: the chapter kits share one kit folder and one build folder. Each kit is made into
// the same folder in turn; make-kit rewrites only files whose content changes, so the
// build recompiles only what differs between two kits (the stubbed files and the tests).
// Every build is still a correct build of that kit: make sees every changed file.
#include "support/process.hpp"
#include "support/text_lines.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using exactpixels::testing::CommandResult;
using exactpixels::testing::run_command;

namespace {

const fs::path source_root = EXACTPIXELS_SOURCE_DIR;

/// The path in single quotes for /bin/sh (built by appending: GCC 12 warns falsely,
/// -Wrestrict, about "'" + std::string + "'").
std::string quoted(const fs::path& path) {
    std::string text(1, '\'');
    text.append(path.string());
    text.push_back('\'');
    return text;
}

std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

void write_file(const fs::path& path, const std::string& text) {
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

using exactpixels::testing::lines_of;

std::string trimmed(const std::string& line) {
    const auto first = line.find_first_not_of(" \t");
    const auto last = line.find_last_not_of(" \t\r");
    return first == std::string::npos ? "" : line.substr(first, last - first + 1);
}

bool starts_with(const std::string& text, const std::string& prefix) {
    return text.rfind(prefix, 0) == 0;
}

/// This process's folder for kits and their builds, deleted when the tests end.
const fs::path& scratch_root() {
    struct Root {
        fs::path path = fs::temp_directory_path() /
                        ("exactpixels-kits-" + std::to_string(::getpid()));
        ~Root() {
            std::error_code ignored;
            fs::remove_all(path, ignored);
        }
    };
    static const Root root;
    return root.path;
}

/// A fresh folder under scratch_root().
fs::path scratch(const std::string& name) {
    const fs::path folder = scratch_root() / name;
    fs::remove_all(folder);
    fs::create_directories(folder);
    return folder;
}

/// Every regular file under `root`, relative, sorted.
std::vector<fs::path> files_under(const fs::path& root) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        if (entry.is_regular_file()) {
            files.push_back(fs::relative(entry.path(), root));
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

bool is_code(const fs::path& path) {
    const auto e = path.extension();
    return e == ".cpp" || e == ".hpp" || e == ".h";
}

CommandResult make_kit(const fs::path& source, const std::string& chapter,
                       const fs::path& out) {
    return run_command(
        std::string("'") + EXACTPIXELS_MAKE_KIT + "' kit --source " + quoted(source) +
        " --template " +
        quoted(fs::path(EXACTPIXELS_KIT_SCRIPT).parent_path() / "template") +
        " --chapter " + chapter + " --out " + quoted(out));
}

/// `later`: "restore" puts every solution back, "stub" only the kit's own exercises'
/// (a later chapter's stubs stay, as in a student's solved kit).
CommandResult restore_kit(const fs::path& source, const fs::path& kit,
                          const std::string& later = "restore") {
    return run_command(std::string("'") + EXACTPIXELS_MAKE_KIT + "' restore --source " +
                       quoted(source) + " --kit " + quoted(kit) + " --later " + later);
}

std::string cmake() {
    return std::string("'") + EXACTPIXELS_CMAKE + "'";
}

/// Configures `kit` into `build` with the compiler and generator of this build, Release.
CommandResult configure(const fs::path& kit, const fs::path& build) {
    return run_command(cmake() + " -S " + quoted(kit) + " -B " + quoted(build) + " -G '" +
                       EXACTPIXELS_GENERATOR + "' -DCMAKE_BUILD_TYPE=Release" +
                       " -DCMAKE_CXX_COMPILER='" + EXACTPIXELS_CXX_COMPILER + "'");
}

CommandResult build(const fs::path& build_dir) {
    return run_command(cmake() + " --build " + quoted(build_dir) + " -j2");
}

/// One line of the grade: STATUS EARNED/DECLARED EXERCISE NAME.
struct GradeLine {
    std::string status, exercise, name;
    int earned = -1, declared = -1;
    std::vector<std::string> reasons; ///< the indented lines below a FAIL line
};

/// The grade file, parsed strictly: every line but the last is a test case line or (two
/// spaces first) a reason below a FAIL line, the last is "TOTAL E/D points; P/N test
/// cases passed" and agrees with the lines above it.
struct Grade {
    std::vector<std::string> exercises; ///< "ID [KIND, N marks]: E/D points" lines
    std::vector<GradeLine> cases;
    bool well_formed = false;
    int earned = 0, declared = 0, passed = 0, counted = 0;
};

Grade parse_grade(const std::string& text) {
    Grade grade;
    const auto lines = lines_of(text);
    if (lines.empty()) {
        return grade;
    }
    int earned = 0, declared = 0, passed = 0, counted = 0;
    for (std::size_t i = 0; i + 1 < lines.size(); ++i) {
        if (starts_with(lines[i], "# ")) {
            // An exercise's summary line, before every test case line.
            if (!grade.cases.empty()) {
                return grade;
            }
            grade.exercises.push_back(lines[i].substr(2));
            continue;
        }
        if (starts_with(lines[i], "  ")) {
            // A reason below a FAIL line.
            if (grade.cases.empty() || grade.cases.back().status != "FAIL") {
                return grade;
            }
            grade.cases.back().reasons.push_back(lines[i].substr(2));
            continue;
        }
        std::istringstream in(lines[i]);
        GradeLine line;
        char slash = 0;
        in >> line.status >> line.earned >> slash >> line.declared >> line.exercise;
        in.get(); // the single space before the name
        std::getline(in, line.name);
        const bool status_ok =
            line.status == "PASS" || line.status == "FAIL" || line.status == "SKIP";
        if (!in.eof() && in.fail()) {
            return grade;
        }
        if (!status_ok || slash != '/' || line.name.empty() ||
            line.earned != (line.status == "PASS" ? line.declared : 0)) {
            return grade;
        }
        if (line.status != "SKIP") {
            earned += line.earned;
            declared += line.declared;
            passed += line.status == "PASS";
            ++counted;
        }
        grade.cases.push_back(line);
    }
    std::istringstream total(lines.back());
    std::string word, points, tests, cases, passed_word;
    char slash1 = 0, slash2 = 0;
    total >> word >> grade.earned >> slash1 >> grade.declared >> points >> grade.passed >>
        slash2 >> grade.counted >> tests >> cases >> passed_word;
    grade.well_formed = word == "TOTAL" && points == "points;" && tests == "test" &&
                        cases == "cases" && passed_word == "passed" && slash1 == '/' &&
                        slash2 == '/' && grade.earned == earned &&
                        grade.declared == declared && grade.passed == passed &&
                        grade.counted == counted;
    return grade;
}

/// Runs the kit's `grade` target; returns the grade file (also checked to be printed).
std::string run_grade(const fs::path& build_dir, std::string* printed = nullptr) {
    const auto result =
        run_command(cmake() + " --build " + quoted(build_dir) + " --target grade");
    INFO(result.out << result.err);
    CHECK(result.exit_code == 0);
    const std::string text = read_file(build_dir / "grade.txt");
    CHECK(result.out.find(text) != std::string::npos);
    if (printed != nullptr) {
        *printed = result.out;
    }
    return text;
}

/// A named constant of the kit's grade runner, `constexpr int NAME = N;`: the time limit
/// of a test case time_limits.txt does not list, and the rule that derives the others.
int runner_constant(const fs::path& kit, const std::string& name) {
    std::smatch match;
    const std::string runner = read_file(kit / "grade_runner.cpp");
    std::regex_search(runner, match,
                      std::regex("constexpr int " + name + " = ([0-9]+);"));
    REQUIRE(match.size() == 2);
    return std::stoi(match[1].str());
}

/// The seconds of the slowest test case in the grade runner's progress lines,
/// "[I/N] STATUS E/D EXERCISE NAME (S s)", and its line; the count of such lines.
struct Slowest {
    double seconds = 0, total = 0; ///< the slowest case's, all cases'

    std::string line;
    std::size_t lines = 0;
};

Slowest slowest_case(const std::string& printed) {
    Slowest slowest;
    const std::regex progress(R"(^\[[0-9]+/[0-9]+\] .* \(([0-9]+\.[0-9]+) s\)$)");
    for (const auto& line : lines_of(printed)) {
        std::smatch match;
        if (std::regex_match(line, match, progress)) {
            ++slowest.lines;
            const double seconds = std::stod(match[1].str());
            slowest.total += seconds;
            if (seconds >= slowest.seconds) {
                slowest = {seconds, slowest.total, line, slowest.lines};
            }
        }
    }
    return slowest;
}

/// The lines of a source file as the book's readers see the code: every marker line,
/// stub line and (clang-format-wrapped) hint continuation removed. Written here
/// independently of make-kit, as the oracle for a restored kit.
std::string without_markers(const std::string& text) {
    std::string out;
    bool after_exercise_open = false;
    for (const auto& line : lines_of(text)) {
        const std::string t = trimmed(line);
        const bool marker =
            starts_with(t, "//>") || starts_with(t, "//<") || starts_with(t, "//|");
        const bool continuation = after_exercise_open && t.size() > 2 &&
                                  starts_with(t, "//") &&
                                  std::string(" /<>|!").find(t[2]) == std::string::npos;
        if (marker || continuation) {
            after_exercise_open =
                starts_with(t, "//> exercise ") || (continuation && after_exercise_open);
            continue;
        }
        after_exercise_open = false;
        out += line + "\n";
    }
    return out;
}

/// The kit's comments around a stub: "// EXERCISE chNN-name: hint" and
/// "// END EXERCISE chNN-name".
const std::regex kit_begin(R"(^\s*// EXERCISE (ch[0-9][0-9]-[a-z0-9-]+): .*$)");
const std::regex kit_end(R"(^\s*// END EXERCISE ch[0-9][0-9]-[a-z0-9-]+$)");

/// A later chapter's region or gives-away block: "// LATER EXERCISE chNN-name: ..." and
/// "// END LATER EXERCISE chNN-name".
const std::regex later_begin(R"(^\s*// LATER EXERCISE (ch[0-9][0-9]-[a-z0-9-]+): .*$)");
const std::regex later_end(R"(^\s*// END LATER EXERCISE ch[0-9][0-9]-[a-z0-9-]+$)");

/// The kit's text minus its EXERCISE / END EXERCISE (and LATER EXERCISE) comment lines.
std::string without_kit_comments(const std::string& text) {
    std::string out;
    for (const auto& line : lines_of(text)) {
        if (!std::regex_match(line, kit_begin) && !std::regex_match(line, kit_end) &&
            !std::regex_match(line, later_begin) && !std::regex_match(line, later_end)) {
            out += line + "\n";
        }
    }
    return out;
}

/// The exercise IDs a kit stubs, from its EXERCISE comments.
std::set<std::string> kit_exercises(const fs::path& kit) {
    std::set<std::string> ids;
    for (const auto& rel : files_under(kit)) {
        if (!is_code(rel)) {
            continue;
        }
        for (const auto& line : lines_of(read_file(kit / rel))) {
            std::smatch match;
            if (std::regex_match(line, match, kit_begin)) {
                ids.insert(match[1]);
            }
        }
    }
    return ids;
}

/// No kit code file holds a book marker line; no kit file names the source tree.
void check_clean(const fs::path& kit, const fs::path& source) {
    for (const auto& rel : files_under(kit)) {
        const std::string text = read_file(kit / rel);
        INFO("kit file " << rel.string());
        CHECK(text.find(source.string()) == std::string::npos);
        if (!is_code(rel)) {
            continue;
        }
        for (const auto& line : lines_of(text)) {
            const std::string t = trimmed(line);
            CHECK_FALSE((starts_with(t, "//>") || starts_with(t, "//<") ||
                         starts_with(t, "//|")));
        }
    }
}

/// The fixture tree plus the real test support files (main, reporter), copied once.
fs::path fixture_tree() {
    static const fs::path tree = [] {
        const fs::path copy = scratch("fixture-tree");
        fs::copy(source_root / "tests/fixtures/kits/tree", copy,
                 fs::copy_options::recursive);
        fs::copy(source_root / "tests/support", copy / "tests/support",
                 fs::copy_options::recursive);
        return copy;
    }();
    return tree;
}

/// The chapters that get an assignment-chNN target: a folder chapters/NN-slug or a test
/// file tests/chNN_*.cpp (the rule of src/kits/CMakeLists.txt).
std::vector<std::string> book_chapters() {
    std::set<std::string> numbers;
    for (const auto& entry : fs::directory_iterator(source_root / "chapters")) {
        const std::string name = entry.path().filename().string();
        if (entry.is_directory() && name.size() > 3 && std::isdigit(name[0]) &&
            std::isdigit(name[1]) && name[2] == '-') {
            numbers.insert(name.substr(0, 2));
        }
    }
    for (const auto& entry : fs::directory_iterator(source_root / "tests")) {
        const std::string name = entry.path().filename().string();
        if (name.size() > 5 && starts_with(name, "ch") && std::isdigit(name[2]) &&
            std::isdigit(name[3]) && name[4] == '_' &&
            entry.path().extension() == ".cpp") {
            numbers.insert(name.substr(2, 2));
        }
    }
    return {numbers.begin(), numbers.end()};
}

} // namespace

TEST_CASE("make-kit refuses malformed exercise regions, naming the file and line") {
    struct Case {
        const char* what;
        const char* code;  // src/exactpixels/bad.hpp
        const char* tests; // tests/ch07_bad.cpp
        const char* message;
    };
    const char* ok_test =
        "TEST_CASE(\"t\" * doctest::description(\"points: 1; exercise: ch07-x\")) {}\n";
    const Case cases[] = {
        {"never closed", "int f() {\n    //> exercise ch07-x: hint\n    return 1;\n}\n",
         ok_test, "bad.hpp:2: exercise region ch07-x is never closed"},
        {"closed under another name",
         "//> exercise ch07-x: hint\nint a;\n//< exercise ch07-y\n", ok_test,
         "bad.hpp:3: '//< exercise ch07-y' closes no open region (open: ch07-x)"},
        {"nested", "//> exercise ch07-x: h\n//> exercise ch07-y: h\n", ok_test,
         "bad.hpp:2: exercise region inside region ch07-x"},
        {"stub outside", "int a;\n//| int b;\n", ok_test,
         "bad.hpp:2: stub line '//|' outside any exercise region"},
        {"bad ID", "//> exercise chapter7: h\n//< exercise chapter7\n", ok_test,
         "bad.hpp:1: exercise ID 'chapter7' is not of the form chNN-name"},
        {"no hint", "//> exercise ch07-x\n//< exercise ch07-x\n", ok_test,
         "bad.hpp:1: exercise ch07-x has no hint"},
        {"untested", "//> exercise ch07-x: h\n//< exercise ch07-x\n",
         "TEST_CASE(\"t\") {}\n", "bad.hpp:1: exercise ch07-x is checked by no test"},
        {"unknown exercise in a test", "int a;\n", ok_test,
         "ch07_bad.cpp:1: test \"t\" names exercise ch07-x, but no region"},
        {"no points", "//> exercise ch07-x: h\n//< exercise ch07-x\n",
         "TEST_CASE(\"t\" * doctest::description(\"exercise: ch07-x\")) {}\n",
         "ch07_bad.cpp:1: test \"t\" checks exercise ch07-x but declares no points"},
        {"points not a number", "//> exercise ch07-x: h\n//< exercise ch07-x\n",
         "TEST_CASE(\"t\" * doctest::description(\"points: two; exercise: ch07-x\")) "
         "{}\n",
         "points 'two' is not a whole number"},
    };
    for (const auto& c : cases) {
        CAPTURE(c.what);
        const fs::path tree = scratch("bad-tree");
        write_file(tree / "src/exactpixels/bad.hpp", c.code);
        write_file(tree / "tests/ch07_bad.cpp", c.tests);
        const auto result = make_kit(tree, "07", scratch("bad-kit"));
        INFO(result.err);
        CHECK(result.exit_code == 1);
        CHECK(result.err.find(c.message) != std::string::npos);
    }
    // The same ID twice in the tree.
    const fs::path tree = scratch("bad-tree");
    write_file(tree / "src/exactpixels/a.hpp",
               "//> exercise ch07-x: h\n//< exercise ch07-x\n");
    write_file(tree / "src/exactpixels/b.hpp",
               "\n//> exercise ch07-x: h\n//< exercise ch07-x\n");
    write_file(tree / "tests/ch07_bad.cpp", ok_test);
    const auto result = make_kit(tree, "07", scratch("bad-kit"));
    CHECK(result.exit_code == 1);
    CHECK(result.err.find("b.hpp:2: exercise ch07-x is also defined at "
                          "src/exactpixels/a.hpp:1") != std::string::npos);
    // A folder make-kit did not write is never deleted or written into.
    const fs::path precious = scratch("precious");
    write_file(precious / "thesis.tex", "years of work");
    const auto refused = make_kit(fixture_tree(), "07", precious);
    CHECK(refused.exit_code == 1);
    CHECK(read_file(precious / "thesis.tex") == "years of work");
}

namespace {

/// One code line of an exercise's answer: a solution line of its region, or a line of a
/// gives-away block (code elsewhere that states the same answer).
struct AnswerLine {
    std::string exercise;  // e.g. "ch04-modifier"
    bool gives_away;       // from a gives-away block, not the region
    std::string where;     // file:line in the source tree
};

/// Every answer line of every exercise in the code of `tree` (src/, chapters/, tests/,
/// test fixtures aside), by its trimmed text, read here independently of make-kit. A line
/// that the tree also holds outside every region and block, or as a stub line, is left
/// out ("break;", "}", a common loop head): a kit holds it anyway. So are blank lines,
/// comments and lines of braces alone.
std::map<std::string, std::vector<AnswerLine>> answer_lines(const fs::path& tree) {
    std::map<std::string, std::vector<AnswerLine>> answers;
    std::set<std::string> elsewhere;
    for (const char* top : {"src", "chapters", "tests"}) {
        for (const auto& rel : files_under(tree / top)) {
            if (!is_code(rel) || starts_with(rel.generic_string(), "fixtures/")) {
                continue;
            }
            std::string exercise;
            bool gives_away = false;
            int number = 0;
            for (const auto& line : lines_of(read_file(tree / top / rel))) {
                ++number;
                const std::string t = trimmed(line);
                std::smatch match;
                static const std::regex open(R"(^//> (exercise|gives-away) (ch[0-9][0-9]-[a-z0-9-]+)\b.*$)");
                static const std::regex close(R"(^//< (exercise|gives-away) .*$)");
                if (std::regex_match(t, match, open)) {
                    exercise = match[2];
                    gives_away = match[1] == "gives-away";
                } else if (std::regex_match(t, close)) {
                    exercise.clear();
                } else if (starts_with(t, "//|")) {
                    elsewhere.insert(trimmed(t.substr(3)));
                } else if (exercise.empty()) {
                    elsewhere.insert(t);
                } else if (!t.empty() && !starts_with(t, "//") &&
                           t.find_first_not_of("{}();, ") != std::string::npos) {
                    answers[t].push_back(
                        {exercise, gives_away,
                         (fs::path(top) / rel).generic_string() + ":" +
                             std::to_string(number)});
                }
            }
        }
    }
    for (const auto& line : elsewhere) {
        answers.erase(line);
    }
    return answers;
}

/// The answer lines that chapter `number`'s kit must not hold, found in `kit`: a region's
/// lines of its own chapter or a later one (they are the students' to write), a
/// gives-away block's of a later chapter (its own chapter's kit needs them to run).
std::vector<std::string> answers_in_kit(const fs::path& kit, const std::string& number,
                                        const std::map<std::string, std::vector<AnswerLine>>&
                                            answers,
                                        const std::set<std::string>& kept = {}) {
    std::vector<std::string> found;
    for (const auto& rel : files_under(kit)) {
        if (!is_code(rel)) {
            continue;
        }
        int n = 0;
        for (const auto& line : lines_of(read_file(kit / rel))) {
            ++n;
            const auto hit = answers.find(trimmed(line));
            if (hit == answers.end()) {
                continue;
            }
            for (const auto& answer : hit->second) {
                const std::string chapter = answer.exercise.substr(2, 2);
                if ((chapter > number && kept.count(answer.exercise) == 0) ||
                    (chapter == number && !answer.gives_away)) {
                    found.push_back("ch" + number + " kit, " + rel.generic_string() + ":" +
                                    std::to_string(n) + " holds the answer of " +
                                    answer.exercise + " (" + answer.where + "): " +
                                    trimmed(line));
                }
            }
        }
    }
    return found;
}

} // namespace

TEST_CASE(
    "a fixture kit holds its chapter's stubs, other chapters' solutions, no markers") {
    const fs::path tree = fixture_tree();
    const fs::path kits = scratch("fixture-kit");
    const fs::path kit = kits / "ch07";
    const auto made = make_kit(tree, "07", kit);
    INFO(made.out << made.err);
    REQUIRE(made.exit_code == 0);
    CHECK(made.out.find("(chapter 07, 2 exercises, 5 test cases, 6 points)") !=
          std::string::npos);

    // Exactly these files: library, the chapter folder (example and text), the chapter's
    // tests and fixture data, the test support files, the template files; nothing of
    // ch08.
    std::vector<std::string> files;
    for (const auto& rel : files_under(kit)) {
        if (!starts_with(rel.generic_string(), "tests/support/")) {
            files.push_back(rel.generic_string());
        }
    }
    const std::vector<std::string> expected = {".exactpixels-kit",
                                               "CMakeLists.txt",
                                               "README.md",
                                               "chapters/07-fake/chapter.md",
                                               "chapters/07-fake/example.cpp",
                                               "exercises.txt",
                                               "grade_runner.cpp",
                                               "run_autograder",
                                               "setup.sh",
                                               "src/CMakeLists.txt",
                                               "src/exactpixels/answer.cpp",
                                               "src/exactpixels/answer.hpp",
                                               "tests/ch07_fake.cpp",
                                               "tests/fixtures/ch07/numbers.txt"};
    CHECK(files == expected);
    // src/CMakeLists.txt is the tree's, without the line that adds the kit maker.
    const std::string src_cmake = read_file(tree / "src/CMakeLists.txt");
    CHECK(read_file(kit / "src/CMakeLists.txt") ==
          src_cmake.substr(0, src_cmake.find("add_subdirectory(kits)")));
    for (const auto& rel : files_under(tree / "tests/support")) {
        CHECK(read_file(kit / "tests/support" / rel) ==
              read_file(tree / "tests/support" / rel));
    }
    check_clean(kit, tree);

    // Chapter 07's regions are stubs between the kit's comments, with the (wrapped) hint;
    // chapter 06's region keeps its solution and loses its stub; chapter 08's region and
    // its gives-away block are their stubs between LATER comments (no answer of a later
    // chapter in a kit); the snippet markers go.
    CHECK(read_file(kit / "src/exactpixels/answer.hpp") ==
          "// answer.hpp: a tiny fake library for the assignment-kit tests "
          "(tests/assignments_kits.cpp).\n"
          "// Chapter 07 (\"fake\") has two exercise regions, chapter 06 one; a snippet "
          "region encloses\n"
          "// an exercise region, as the book allows. Chapter 08's exercise, and the block "
          "that gives\n"
          "// it away, are stubs in chapter 07's kit.\n"
          "#pragma once\n\nnamespace fake {\n\n"
          "/// The answer, computed.\n"
          "inline int answer() {\n"
          "    // EXERCISE ch07-answer: six times seven.\n"
          "    return 0; // stub: a neutral value\n"
          "    // END EXERCISE ch07-answer\n"
          "}\n\n"
          "/// 1 + 2 + ... + n.\n"
          "int triangle_number(int n);\n\n"
          "/// 2 x, chapter 06's exercise (keeps its solution in chapter 07's kit).\n"
          "inline int twice(int x) {\n"
          "    return x + x;\n"
          "}\n\n"
          "/// 3 x, chapter 08's exercise (its stub in chapter 07's kit).\n"
          "inline int thrice(int x) {\n"
          "    // LATER EXERCISE ch08-thrice: chapter 08's, not graded here; its stub until "
          "then\n"
          "    (void)x;\n"
          "    return 0;\n"
          "    // END LATER EXERCISE ch08-thrice\n"
          "}\n\n"
          "/// 6 x, written the way chapter 08's exercise wants (its stub in chapter 07's "
          "kit).\n"
          "inline int six_times(int x) {\n"
          "    // LATER EXERCISE ch08-thrice: chapter 08's, not graded here; its stub until "
          "then\n"
          "    return 6 * x; // stub: the same value, another way\n"
          "    // END LATER EXERCISE ch08-thrice\n"
          "}\n\n"
          "} // namespace fake\n");
    const std::string cpp = read_file(kit / "src/exactpixels/answer.cpp");
    CHECK(cpp.find("    // EXERCISE ch07-triangle: add 1, 2, ..., n.\n"
                   "    (void)n; // stub: the sum of nothing\n"
                   "    // END EXERCISE ch07-triangle\n") != std::string::npos);
    CHECK(cpp.find("sum += k") == std::string::npos);

    // The README lists the exercises with where, points and hint, the tests that check
    // them, the chapter's own exercise section and the commands.
    const std::string readme = read_file(kit / "README.md");
    CHECK(readme.find("chapter 07: A fake chapter\n") != std::string::npos);
    CHECK(
        readme.find("| `ch07-answer` | `src/exactpixels/answer.hpp:11` | 3 | [implement, "
                    "2 marks] | six times seven. |") != std::string::npos);
    CHECK(
        readme.find("| `ch07-triangle` | `src/exactpixels/answer.cpp:9` | 2 | - | add 1, "
                    "2, ..., n. |") != std::string::npos);
    CHECK(readme.find("- `ch07-triangle`: \"triangle numbers\"") != std::string::npos);
    CHECK(readme.find("1. **[implement, 2 marks]** Implement `answer` (\"the answer is "
                      "42\").\n") != std::string::npos);
    CHECK(readme.find("2. **[derive, 3 marks]** Derive") != std::string::npos);
    CHECK(readme.find("3. **[measure, 1 mark]** Measure") != std::string::npos);
    // No worked solution reaches a kit: not in the README, not in the chapter's text.
    for (const auto& rel : files_under(kit)) {
        INFO("kit file " << rel.string());
        const std::string text = read_file(kit / rel);
        CHECK(text.find("ANSWER-SOLUTION") == std::string::npos);
        CHECK(text.find("TRIANGLE-SOLUTION") == std::string::npos);
        CHECK(text.find("nested div inside a solution") == std::string::npos);
    }
    CHECK(read_file(kit / "chapters/07-fake/chapter.md").find("3. []{.exercise") !=
          std::string::npos);
    // The kit says no more than the course edition: text marked `.not-in-course` (span
    // or div, nested markup and all) is gone, `.course-only` text stays, unwrapped.
    const std::string chapter_md = read_file(kit / "chapters/07-fake/chapter.md");
    for (const std::string& text : {chapter_md, readme}) {
        CHECK(text.find("PUBLIC-") == std::string::npos);
        CHECK(text.find("not-in-course") == std::string::npos);
        CHECK(text.find("course-only") == std::string::npos);
        CHECK(text.find("Derive the triangle number, COURSE-SPAN") != std::string::npos);
        CHECK(text.find("COURSE-DIV text.") != std::string::npos);
    }
    CHECK(readme.find("Not part of the README") == std::string::npos);
    CHECK(readme.find("worth 6 points") != std::string::npos);
    CHECK(readme.find("cmake --build build --target grade") != std::string::npos);
    CHECK(readme.find("@") == std::string::npos); // every placeholder filled

    // `make-kit stub` (the course edition's API reference reads the library through it)
    // stubs the regions of every chapter, 06's, 07's and 08's alike, and every gives-away
    // block.
    const auto stubbed = run_command(std::string("'") + EXACTPIXELS_MAKE_KIT +
                                     "' stub --source " + quoted(tree) + " --file " +
                                     quoted(tree / "src/exactpixels/answer.hpp"));
    REQUIRE(stubbed.exit_code == 0);
    CHECK(stubbed.out.find("    // EXERCISE ch07-answer: six times seven.\n"
                           "    return 0; // stub: a neutral value\n") !=
          std::string::npos);
    CHECK(stubbed.out.find("    // EXERCISE ch06-twice: add x to itself; this hint is "
                           "long enough that clang-format wraps it.\n    (void)x;\n") !=
          std::string::npos);
    CHECK(stubbed.out.find("    // NOT IN THE COURSE EDITION (it would give exercise "
                           "ch08-thrice away); a stub:\n"
                           "    return 6 * x; // stub: the same value, another way\n"
                           "    // END OF WHAT THE COURSE EDITION LEAVES OUT\n") !=
          std::string::npos);
    CHECK(stubbed.out.find("six * 7") == std::string::npos);
    CHECK(stubbed.out.find("x + x") == std::string::npos);

    // Chapter 06's kit takes the wrapped hint whole; chapter 08's keeps the gives-away
    // block of its own exercise (its tests need it) and stubs the exercise.
    const fs::path kit06 = kits / "ch06";
    REQUIRE(make_kit(tree, "06", kit06).exit_code == 0);
    CHECK(
        read_file(kit06 / "src/exactpixels/answer.hpp")
            .find("    // EXERCISE ch06-twice: add x to itself; this hint is long enough "
                  "that clang-format wraps it.\n    (void)x;\n    return 0;\n"
                  "    // END EXERCISE ch06-twice\n") != std::string::npos);
    const fs::path kit08 = kits / "ch08";
    REQUIRE(make_kit(tree, "08", kit08).exit_code == 0);
    const std::string header08 = read_file(kit08 / "src/exactpixels/answer.hpp");
    CHECK(header08.find("    // EXERCISE ch08-thrice: add x three times.\n") !=
          std::string::npos);
    CHECK(header08.find("    return 2 * (x + x + x);\n") != std::string::npos);
    CHECK(header08.find("x + x;") != std::string::npos); // chapter 06's, kept

    // Made again into the same folder, the kit is the same and unchanged files keep their
    // time stamps (so a build in the kit's place recompiles only what changed).
    const auto stamp = fs::last_write_time(kit / "src/exactpixels/answer.cpp");
    write_file(kit / "src/exactpixels/answer.cpp",
               read_file(kit / "src/exactpixels/answer.cpp"));
    const auto touched = fs::last_write_time(kit / "src/exactpixels/answer.cpp");
    REQUIRE(make_kit(tree, "07", kit).exit_code == 0);
    CHECK(fs::last_write_time(kit / "src/exactpixels/answer.cpp") == touched);
    CHECK(touched >= stamp);

    // The search of the test below, tried on the fixture tree: chapter 08's exercise and gives-away block are both
    // found by the search (in chapter 08's kit) and absent from chapter 07's.
    const auto fixture_answers = answer_lines(fixture_tree());
    REQUIRE(fixture_answers.count("return x + x + x;") == 1);
    REQUIRE(fixture_answers.count("return 2 * (x + x + x);") == 1);
    const fs::path fixture_kit = scratch("answers-fixture") / "kit";
    REQUIRE(make_kit(fixture_tree(), "07", fixture_kit).exit_code == 0);
    CHECK(answers_in_kit(fixture_kit, "07", fixture_answers).empty());
    // Restored (every answer back, as the old make-kit left chapter 08's), the search
    // finds chapter 07's region lines and chapter 08's region and gives-away lines.
    REQUIRE(restore_kit(fixture_tree(), fixture_kit).exit_code == 0);
    const auto restored = answers_in_kit(fixture_kit, "07", fixture_answers);
    const auto naming = [&](const std::string& id) {
        return std::count_if(restored.begin(), restored.end(), [&](const std::string& f) {
            return f.find("answer of " + id + " ") != std::string::npos;
        });
    };
    CHECK(naming("ch08-thrice") == 2);
    CHECK(naming("ch07-answer") == 2);
    CHECK(naming("ch06-twice") == 0);

}

TEST_CASE("no kit holds the answer of an exercise of its own chapter or a later one") {
    // The later exercises a chapter's code runs, which its kit keeps solved
    // (`kit-keeps-later: "ch07: ID ID; ..."` in book/metadata.yaml), read here too.
    std::map<std::string, std::set<std::string>> kept;
    for (const auto& line : lines_of(read_file(source_root / "book/metadata.yaml"))) {
        if (!starts_with(line, "kit-keeps-later:")) {
            continue;
        }
        std::string value = line.substr(16);
        value.erase(std::remove(value.begin(), value.end(), '"'), value.end());
        std::istringstream entries(value);
        for (std::string entry; std::getline(entries, entry, ';');) {
            const auto colon = entry.find(':');
            REQUIRE(colon != std::string::npos);
            std::istringstream ids(entry.substr(colon + 1));
            for (std::string id; ids >> id;) {
                kept[trimmed(entry.substr(0, colon)).substr(2)].insert(id);
                MESSAGE("chapter " << trimmed(entry.substr(0, colon)) << "'s kit keeps "
                                   << id << " solved (book/metadata.yaml)");
            }
        }
    }
    // Every chapter of the book (the search itself is tried on the fixture tree, in
    // "a fixture kit holds its chapter's stubs...").
    const auto answers = answer_lines(source_root);
    REQUIRE(answers.size() > 30);
    const fs::path kit = scratch("answers-book") / "kit";
    for (const auto& number : book_chapters()) {
        CAPTURE(number);
        const auto made = make_kit(source_root, number, kit);
        INFO(made.out << made.err);
        REQUIRE(made.exit_code == 0);
        for (const auto& found : answers_in_kit(kit, number, answers, kept[number])) {
            FAIL_CHECK(found);
        }
    }
}

TEST_CASE("the assignment script writes the kit and a zip holding the same files") {
    const fs::path out = scratch("fixture-assignments");
    const auto result = run_command(cmake() + " -DMAKE_KIT='" + EXACTPIXELS_MAKE_KIT +
                                    "' -DSOURCE=" + quoted(fixture_tree()) +
                                    " -DCHAPTER=07 -DOUTPUT=" + quoted(out) + " -P '" +
                                    EXACTPIXELS_KIT_SCRIPT + "'");
    INFO(result.out << result.err);
    REQUIRE(result.exit_code == 0);
    REQUIRE(fs::exists(out / "ch07.zip"));
    const fs::path unpacked = scratch("fixture-unzipped");
    REQUIRE(run_command("cd " + quoted(unpacked) + " && " + cmake() + " -E tar xf " +
                        quoted(out / "ch07.zip"))
                .exit_code == 0);
    const auto files = files_under(out / "ch07");
    CHECK(files == files_under(unpacked / "ch07"));
    for (const auto& rel : files) {
        CHECK(read_file(out / "ch07" / rel) == read_file(unpacked / "ch07" / rel));
    }
}

TEST_CASE("the fixture kit builds on its own; fresh it fails its exercises, restored it "
          "gets full marks") {
    const fs::path tree = fixture_tree();
    const fs::path kit = scratch("fixture-build-kit") / "ch07";
    const fs::path build_dir = scratch("fixture-build");
    REQUIRE(make_kit(tree, "07", kit).exit_code == 0);
    const auto configured = configure(kit, build_dir);
    INFO(configured.out << configured.err);
    REQUIRE(configured.exit_code == 0);
    const auto built = build(build_dir);
    INFO(built.out << built.err);
    REQUIRE(built.exit_code == 0);

    // Fresh: exactly these lines, and the same lines again on a second run.
    const std::string fresh = run_grade(build_dir);
    CHECK(fresh ==
          "# ch07-answer [implement, 2 marks]: 0/3 points\n"
          "FAIL 0/3 ch07-answer the answer is 42\n"
          "  ch07_fake.cpp:10: CHECK( fake::answer() == 42 ) is false; values: "
          "0 == 42\n"
          "FAIL 0/2 ch07-triangle triangle numbers\n"
          "  ch07_fake.cpp:14: CHECK( fake::triangle_number(4) == 10 ) is false; "
          "values: 0 == 10\n"
          "PASS 1/1 - twice is kept from chapter 06\n"
          "PASS 0/0 - the fixture data travels with the kit\n"
          "SKIP 0/5 - a skipped test\n"
          "TOTAL 1/6 points; 2/4 test cases passed\n");
    CHECK(parse_grade(fresh).well_formed);
    CHECK(run_grade(build_dir) == fresh);
    // One process per test case (the runner) and one for all (the reporter alone) agree.
    const auto in_one = run_command(quoted(build_dir / "bin/test_ch07") +
                                    " --reporters=grade --no-exitcode");
    CHECK("# ch07-answer [implement, 2 marks]: 0/3 points\n" + in_one.out == fresh);
    // The test program itself fails while exercises are open; the example runs.
    CHECK(run_command(quoted(build_dir / "bin/test_ch07")).exit_code != 0);
    CHECK(run_command(quoted(build_dir / "bin/ch07-example")).out == "0 0\n");

    // Restored: full marks, and the code is the tree's code without markers.
    const auto restored = restore_kit(tree, kit);
    INFO(restored.out << restored.err);
    REQUIRE(restored.exit_code == 0);
    CHECK(restored.out.find("restored 2 exercise solutions") != std::string::npos);
    for (const char* file :
         {"src/exactpixels/answer.hpp", "src/exactpixels/answer.cpp"}) {
        CHECK(without_kit_comments(read_file(kit / file)) ==
              without_markers(read_file(tree / file)));
    }
    REQUIRE(build(build_dir).exit_code == 0);
    const std::string full = run_grade(build_dir);
    CHECK(full == "# ch07-answer [implement, 2 marks]: 3/3 points\n"
                  "PASS 3/3 ch07-answer the answer is 42\n"
                  "PASS 2/2 ch07-triangle triangle numbers\n"
                  "PASS 1/1 - twice is kept from chapter 06\n"
                  "PASS 0/0 - the fixture data travels with the kit\n"
                  "SKIP 0/5 - a skipped test\n"
                  "TOTAL 6/6 points; 4/4 test cases passed\n");
    CHECK(run_command(quoted(build_dir / "bin/test_ch07")).exit_code == 0);
    CHECK(run_command(quoted(build_dir / "bin/ch07-example")).out == "42 10\n");
}

TEST_CASE("every chapter's kit builds on its own; fresh it fails exactly its exercise "
          "tests, restored it gets full marks") {
    const auto chapters = book_chapters();
    REQUIRE_FALSE(chapters.empty());
    std::string list;
    for (const auto& number : chapters) {
        list += " ch" + number;
    }
    MESSAGE("assignment kits tested for:" << list);

    // One kit folder and one build folder, reused kit after kit (see the top of the
    // file).
    const fs::path kit = scratch("book-kit") / "kit";
    const fs::path build_dir = scratch("book-build");
    const fs::path figures = scratch("book-example-out");
    for (const auto& number : chapters) {
        CAPTURE(number);
        const auto made = make_kit(source_root, number, kit);
        INFO(made.out << made.err);
        CHECK(made.exit_code == 0);
        if (made.exit_code != 0) {
            continue;
        }
        check_clean(kit, source_root);
        const auto exercises = kit_exercises(kit);

        const auto configured = configure(kit, build_dir);
        INFO(configured.out << configured.err);
        REQUIRE(configured.exit_code == 0);
        const auto built = build(build_dir);
        INFO(built.out.substr(built.out.size() > 4000 ? built.out.size() - 4000 : 0)
             << built.err);
        REQUIRE(built.exit_code == 0);

        // Fresh: every test of an exercise fails, every other test passes, and every
        // exercise is checked by at least one test.
        const std::string fresh_text = run_grade(build_dir);
        const Grade fresh = parse_grade(fresh_text);
        CHECK(fresh.well_formed);
        // Every failed check shows the values it compared (tests/support/printing.hpp).
        CHECK(fresh_text.find("{?}") == std::string::npos);
        std::set<std::string> checked;
        for (const auto& line : fresh.cases) {
            INFO("fresh ch" << number << ": " << line.status << " " << line.exercise
                            << " " << line.name);
            if (line.exercise != "-") {
                CHECK(line.status == "FAIL");
                CHECK(exercises.count(line.exercise) == 1);
                checked.insert(line.exercise);
            } else {
                CHECK(line.status != "FAIL");
            }
        }
        CHECK(checked == exercises);
        const fs::path example = build_dir / ("bin/ch" + number + "-example");
        if (fs::exists(kit / "chapters") && fs::exists(example)) {
            const auto ran = run_command("cd " + quoted(figures) + " && " +
                                         quoted(example) + " " + quoted(figures));
            INFO("the example with stubs: " << ran.out << ran.err);
            CHECK(ran.exit_code == 0);
        }

        // Solved, as a student who wrote every exercise of the chapter has the kit (a
        // later chapter's stubs stay: those are not theirs to write): every test passes,
        // full marks. So no test of the chapter needs a later chapter's exercise.
        const auto solved = restore_kit(source_root, kit, "stub");
        INFO(solved.out << solved.err);
        REQUIRE(solved.exit_code == 0);
        const auto rebuilt = build(build_dir);
        INFO(rebuilt.out << rebuilt.err);
        REQUIRE(rebuilt.exit_code == 0);
        std::string printed;
        const Grade full = parse_grade(run_grade(build_dir, &printed));
        CHECK(full.well_formed);
        CHECK(full.earned == full.declared);
        // Each test case's line was printed as it ended; the solution's slowest case
        // takes at most a third of the time limit, so the limit stops only code that is
        // far slower than the solution (an endless loop) and not a slow machine.
        const Slowest slowest = slowest_case(printed);
        CHECK(slowest.lines == full.cases.size());
        MESSAGE("ch" << number << " solved: the test cases took " << slowest.total
                     << " s in all, the slowest " << slowest.line);
        CHECK(slowest.seconds * 3 <= runner_constant(kit, "test_time_limit_seconds"));
        CHECK(full.passed == full.counted);
        // Stable: the same test cases, in the same order, declaring the same points.
        REQUIRE(full.cases.size() == fresh.cases.size());
        for (std::size_t i = 0; i < full.cases.size(); ++i) {
            CHECK(full.cases[i].name == fresh.cases[i].name);
            CHECK(full.cases[i].exercise == fresh.cases[i].exercise);
            CHECK(full.cases[i].declared == fresh.cases[i].declared);
        }
        // Restored, the later chapters' code too: the code is the book's.
        const auto restored = restore_kit(source_root, kit);
        INFO(restored.out << restored.err);
        REQUIRE(restored.exit_code == 0);
        for (const auto& rel : files_under(kit)) {
            // The kit's own files at its root (the grader, from src/kits/template) are
            // not book code.
            if (is_code(rel) && rel.has_parent_path() &&
                !starts_with(rel.generic_string(), "tests/support/")) {
                INFO("restored file " << rel.string());
                CHECK(without_kit_comments(read_file(kit / rel)) ==
                      without_markers(read_file(source_root / rel)));
            }
        }
    }
}

namespace {

/// The fixture kit, made and built once (fresh) for the grader tests below.
struct BuiltFixtureKit {
    fs::path kit, build;
};

const BuiltFixtureKit& built_fixture_kit() {
    static const BuiltFixtureKit built = [] {
        BuiltFixtureKit made{scratch("grader-kit") / "ch07", scratch("grader-build")};
        REQUIRE(make_kit(fixture_tree(), "07", made.kit).exit_code == 0);
        REQUIRE(configure(made.kit, made.build).exit_code == 0);
        return made;
    }();
    return built;
}

/// Replaces the kit's library with `header` and `source`, builds, and runs the grade
/// runner with a time limit of `seconds` (and `options`); returns the parsed grade.
Grade grade_broken(const std::string& header, const std::string& source, int seconds,
                   const std::string& options = "") {
    const auto& fixture = built_fixture_kit();
    write_file(fixture.kit / "src/exactpixels/answer.hpp", header);
    write_file(fixture.kit / "src/exactpixels/answer.cpp", source);
    const auto built = build(fixture.build);
    INFO(built.out << built.err);
    REQUIRE(built.exit_code == 0);
    const fs::path grade_file = fixture.build / "broken-grade.txt";
    const auto ran = run_command(quoted(fixture.build / "bin/grade-runner") +
                                 " --tests " + quoted(fixture.build / "bin/test_ch07") +
                                 " --grade-file " + quoted(grade_file) +
                                 " --time-limit " + std::to_string(seconds) + options);
    INFO(ran.out << ran.err);
    CHECK(ran.exit_code == 0);
    const std::string text = read_file(grade_file);
    // A line per test case as it ended, then the grade.
    CHECK(slowest_case(ran.out).lines == 5);
    REQUIRE(ran.out.size() >= text.size());
    CHECK(ran.out.substr(ran.out.size() - text.size()) == text);
    return parse_grade(text);
}

/// The first reason line of `line` that contains `needle`, or "".
std::string reason_with(const GradeLine& line, const std::string& needle) {
    for (const auto& reason : line.reasons) {
        if (reason.find(needle) != std::string::npos) {
            return reason;
        }
    }
    return "";
}

const char* const broken_header_start = "#pragma once\n#include <stdexcept>\n"
                                        "namespace fake {\n";
const char* const broken_header_end = "int triangle_number(int n);\n"
                                      "inline int twice(int x) { return x + x; }\n"
                                      "} // namespace fake\n";

} // namespace

TEST_CASE(
    "a test case that crashes, hangs, aborts or throws scores 0 and says why; every "
    "other test case still runs and scores") {
    // A time limit of 2 s instead of the kit's, so the hang costs 2 s here.
    {
        INFO(
            "round 1: answer() reads through a null pointer, triangle_number never ends");
        const Grade grade = grade_broken(
            std::string(broken_header_start) +
                "inline int answer() {\n"
                "    volatile int* volatile nowhere = nullptr;\n"
                "    return *nowhere;\n}\n" +
                broken_header_end,
            "#include \"exactpixels/answer.hpp\"\nnamespace fake {\n"
            "int triangle_number(int n) {\n    volatile int spin = 0;\n"
            "    while (spin == 0) {\n    }\n    return n;\n}\n} // namespace fake\n",
            2);
        REQUIRE(grade.well_formed);
        REQUIRE(grade.cases.size() == 5);
        CHECK(grade.cases[0].status == "FAIL");
        CHECK(reason_with(grade.cases[0], "crashed: the test program died of SIGSEGV") !=
              "");
        // The command that reruns that one case (the first listed) and how to look
        // for the memory error.
        const std::string rerun =
            reason_with(grade.cases[0], "to run this test case alone: ");
        CHECK(rerun.find("bin/test_ch07 --first=1 --last=1") != std::string::npos);
        CHECK(rerun.find("-fsanitize=address") != std::string::npos);
        CHECK(reason_with(grade.cases[1], "--first=2 --last=2") != "");
        CHECK(grade.cases[1].status == "FAIL");
        CHECK(reason_with(grade.cases[1],
                          "time limit 2 s exceeded: still running after 2 s") != "");
        CHECK(grade.cases[2].status == "PASS"); // twice: still runs, still scores
        CHECK(grade.cases[2].earned == 1);
        CHECK(grade.cases[3].status == "PASS");
        CHECK(grade.cases[4].status == "SKIP");
        CHECK(grade.earned == 1);
        CHECK(grade.declared == 6);
    }
    {
        INFO("round 2: answer() throws, triangle_number aborts");
        const Grade grade = grade_broken(
            std::string(broken_header_start) +
                "inline int answer() { throw std::runtime_error(\"no answer yet\"); }\n" +
                broken_header_end,
            "#include \"exactpixels/answer.hpp\"\n#include <cstdlib>\nnamespace fake {\n"
            "int triangle_number(int) { std::abort(); }\n} // namespace fake\n",
            2);
        REQUIRE(grade.well_formed);
        REQUIRE(grade.cases.size() == 5);
        CHECK(grade.cases[0].status == "FAIL");
        CHECK(reason_with(grade.cases[0], "threw: \"no answer yet\"") != "");
        CHECK(grade.cases[1].status == "FAIL");
        CHECK(reason_with(grade.cases[1], "crashed: the test program died of SIGABRT") !=
              "");
        CHECK(grade.cases[2].status == "PASS");
        CHECK(grade.cases[3].status == "PASS");
        CHECK(grade.earned == 1);
    }
    {
        INFO("round 3: triangle_number calls exit(3) in the middle of a test");
        const Grade grade = grade_broken(
            std::string(broken_header_start) + "inline int answer() { return 42; }\n" +
                broken_header_end,
            "#include \"exactpixels/answer.hpp\"\n#include <cstdlib>\nnamespace fake {\n"
            "int triangle_number(int) { std::exit(3); }\n} // namespace fake\n",
            2);
        REQUIRE(grade.well_formed);
        REQUIRE(grade.cases.size() == 5);
        CHECK(grade.cases[0].status == "PASS");
        CHECK(grade.cases[1].status == "FAIL");
        CHECK(reason_with(grade.cases[1], "stopped early with exit status 3") != "");
        CHECK(grade.earned == 4);
    }
    {
        INFO("round 4: both exercises never end, and all test cases together may take 3 "
             "s");
        const auto& fixture = built_fixture_kit();
        write_file(fixture.build / "time_limits.txt", "# a budget only\nbudget 3\n");
        const Grade grade = grade_broken(
            std::string(broken_header_start) +
                "inline int answer() {\n    volatile int spin = 0;\n"
                "    while (spin == 0) {\n    }\n    return 42;\n}\n" +
                broken_header_end,
            "#include \"exactpixels/answer.hpp\"\nnamespace fake {\n"
            "int triangle_number(int n) {\n    volatile int spin = 0;\n"
            "    while (spin == 0) {\n    }\n    return n;\n}\n} // namespace fake\n",
            2, " --time-limits " + quoted(fixture.build / "time_limits.txt"));
        REQUIRE(grade.well_formed);
        REQUIRE(grade.cases.size() == 5);
        // Its own limit of 2 s, then the 1 s left of the budget, then nothing.
        CHECK(reason_with(grade.cases[0], "time limit 2 s exceeded") != "");
        CHECK(reason_with(grade.cases[1], "stopped: the 3 s that all test cases may take "
                                          "together ran out while it ran") != "");
        CHECK(reason_with(grade.cases[1], "--first=2 --last=2") != "");
        for (const std::size_t i : {2, 3}) {
            CHECK(grade.cases[i].status == "FAIL");
            CHECK(reason_with(grade.cases[i], "not run: the 3 s that all test cases may "
                                              "take together were used up") != "");
        }
        CHECK(grade.cases[4].status == "SKIP");
        CHECK(grade.earned == 0);
    }
    // The kit states its limits and the rule that derives them: the runner's named
    // constants, in the README.
    const auto& fixture = built_fixture_kit();
    const auto constant = [&](const std::string& name) {
        return std::to_string(runner_constant(fixture.kit, name));
    };
    std::string readme = read_file(fixture.kit / "README.md");
    std::replace(readme.begin(), readme.end(), '\n', ' ');
    CHECK(readme.find("allows **" + constant("test_time_limit_seconds") + " seconds**") !=
          std::string::npos);
    CHECK(readme.find(
              "**" + constant("limit_multiple") + " times the solution's time plus " +
              constant("limit_floor_seconds") + " seconds**") != std::string::npos);
    CHECK(readme.find(
              "**" + constant("budget_multiple") + " times the solution's total plus " +
              constant("budget_floor_seconds") + " seconds**") != std::string::npos);
}

namespace {

/// Checks results.json against the fields of Gradescope's specification
/// (gradescope-autograders.readthedocs.io, "Autograder Specifications"): only documented
/// keys, the required ones present with the right types, the total the sum of the tests.
/// Prints "score S of M, N tests".
const char* const results_check = R"(
import json, sys
r = json.load(open(sys.argv[1]))
top = {"score", "execution_time", "output", "output_format", "test_output_format",
       "test_name_format", "visibility", "stdout_visibility", "extra_data", "tests",
       "leaderboard"}
per_test = {"score", "max_score", "status", "name", "name_format", "number", "output",
            "output_format", "tags", "visibility", "extra_data"}
assert set(r) <= top, set(r) - top
assert isinstance(r["score"], (int, float)) and isinstance(r["output"], str)
assert isinstance(r["tests"], list)
for t in r["tests"]:
    assert set(t) <= per_test, set(t) - per_test
    for key, kind in (("name", str), ("score", (int, float)), ("max_score", (int, float)),
                      ("status", str), ("output", str)):
        assert isinstance(t[key], kind), (key, t)
    assert t["status"] in ("passed", "failed"), t
    assert 0 <= t["score"] <= t["max_score"], t
    assert (t["status"] == "passed") == (t["score"] == t["max_score"] and t["max_score"] > 0
                                         or t["status"] == "passed"), t
    assert all(isinstance(tag, str) for tag in t.get("tags", [])), t
assert r["score"] == sum(t["score"] for t in r["tests"])
print("score %g of %g, %d tests" % (r["score"], sum(t["max_score"] for t in r["tests"]),
                                      len(r["tests"])))
)";

/// Runs ROOT/source/run_autograder (ROOT named by AUTOGRADER_ROOT) on the files in
/// ROOT/submission; returns the check's summary line and the JSON text, and what the
/// autograder printed in `printed`.
std::pair<std::string, std::string> autograde(const fs::path& root,
                                              std::string* printed = nullptr) {
    fs::remove_all(root / "results");
    const auto ran = run_command(
        "AUTOGRADER_ROOT=" + quoted(root) +
        " AUTOGRADER_CMAKE_ARGS=-DCMAKE_CXX_COMPILER=" + EXACTPIXELS_CXX_COMPILER + " " +
        quoted(root / "source/run_autograder"));
    if (printed != nullptr) {
        *printed = ran.out;
    }
    INFO(ran.out << ran.err);
    CHECK(ran.exit_code == 0);
    const fs::path json = root / "results/results.json";
    REQUIRE(fs::exists(json));
    write_file(root / "check.py", results_check);
    const auto checked =
        run_command("python3 " + quoted(root / "check.py") + " " + quoted(json));
    INFO(checked.err << read_file(json));
    CHECK(checked.exit_code == 0);
    std::string summary = checked.out;
    while (!summary.empty() && summary.back() == '\n') {
        summary.pop_back();
    }
    return {summary, read_file(json)};
}

/// A fixture kit's assignment (made by the assignment script into NAME-assignments) and
/// a Gradescope-like ROOT (NAME-root) whose source/ is its autograder zip, unpacked.
struct GradescopeRoot {
    fs::path out, root;
};

GradescopeRoot gradescope_root(const std::string& name,
                               const std::string& extra_options = "") {
    const fs::path out = scratch(name + "-assignments");
    const auto made = run_command(cmake() + " -DMAKE_KIT='" + EXACTPIXELS_MAKE_KIT +
                                  "' -DSOURCE=" + quoted(fixture_tree()) +
                                  " -DCHAPTER=07 -DOUTPUT=" + quoted(out) +
                                  extra_options + " -P '" + EXACTPIXELS_KIT_SCRIPT + "'");
    INFO(made.out << made.err);
    REQUIRE(made.exit_code == 0);
    const fs::path root = scratch(name + "-root");
    REQUIRE(run_command("mkdir -p " + quoted(root / "source") + " && cd " +
                        quoted(root / "source") + " && " + cmake() + " -E tar xf " +
                        quoted(out / "ch07-gradescope.zip"))
                .exit_code == 0);
    return {out, root};
}

} // namespace

TEST_CASE("the Gradescope autograder: fresh kit scores the non-exercise points, solved "
          "full marks, a region that does not compile its stub's with the first error; "
          "results.json as specified") {
    const auto [out, root] = gradescope_root("gradescope");
    // Gradescope's layout: setup.sh and an executable run_autograder at the zip's root.
    for (const char* script : {"setup.sh", "run_autograder"}) {
        CAPTURE(script);
        REQUIRE(fs::exists(root / "source" / script));
        CHECK((fs::status(root / "source" / script).permissions() &
               fs::perms::owner_exec) != fs::perms::none);
    }
    CHECK(read_file(root / "source/setup.sh").find("apt-get install") !=
          std::string::npos);

    // Fresh: the kit's own src/, plus a tampered test file that the grader must ignore.
    fs::create_directories(root / "submission");
    fs::copy(out / "ch07/src", root / "submission/src", fs::copy_options::recursive);
    write_file(root / "submission/tests/ch07_fake.cpp",
               "#include <doctest/doctest.h>\nTEST_CASE(\"free points\" * "
               "doctest::description(\"points: 100\")) {}\n");
    const auto [fresh, fresh_json] = autograde(root);
    CHECK(fresh == "score 1 of 7, 5 tests");
    // The hidden test: in the autograder's zip, not in the students' kit or zip, and in
    // results.json shown only after the grades are published, with the printed lines
    // (which name it) hidden.
    const std::string hidden_file = "tests/hidden/ch07_hidden.cpp";
    CHECK_FALSE(fs::exists(out / "ch07" / hidden_file));
    CHECK(fs::exists(root / "source" / hidden_file));
    const auto zipped = [&](const fs::path& zip) {
        const auto listed = run_command(cmake() + " -E tar tf " + quoted(zip));
        REQUIRE(listed.exit_code == 0);
        return lines_of(listed.out);
    };
    const auto student_zip = zipped(out / "ch07.zip");
    CHECK(std::count(student_zip.begin(), student_zip.end(),
                     "ch07/tests/ch07_fake.cpp") == 1);
    CHECK(std::count(student_zip.begin(), student_zip.end(), "ch07/" + hidden_file) == 0);
    const auto autograder_zip = zipped(out / "ch07-gradescope.zip");
    CHECK(std::count(autograder_zip.begin(), autograder_zip.end(), hidden_file) == 1);
    write_file(root / "visibility.py",
               "import json, sys\n"
               "r = json.load(open(sys.argv[1]))\n"
               "print(r['stdout_visibility'], sorted((t['visibility'], t['name']) "
               "for t in r['tests'] if t['visibility'] != 'visible'),\n"
               "      sum(t['visibility'] == 'visible' for t in r['tests']))\n");
    const auto visibility = run_command("python3 " + quoted(root / "visibility.py") +
                                        " " + quoted(root / "results/results.json"));
    CHECK(visibility.out ==
          "hidden [('after_published', 'a hidden triangle number')] 4\n");
    // The summary students see counts the visible test cases only.
    CHECK(fresh_json.find("TOTAL 1/6 points of the visible test cases; 1 more test case "
                          "is shown when the grades are published") != std::string::npos);
    CHECK(
        fresh_json.find("\"tags\": [\"ch07-answer\", \"implement\", \"difficulty 2\"]") !=
        std::string::npos);
    CHECK(fresh_json.find("CHECK( fake::answer() == 42 ) is false") != std::string::npos);
    // The grade names the kit that gave it (make-kit's --version and --commit).
    CHECK(fresh_json.find("\"output\": \"Graded by the chapter 07 kit, version 0.0.0, "
                          "commit ") != std::string::npos);

    // Solved, submitted as the kit's folder (the solution restored by make-kit).
    REQUIRE(restore_kit(fixture_tree(), out / "ch07").exit_code == 0);
    fs::remove_all(root / "submission");
    fs::create_directories(root / "submission/ch07");
    fs::copy(out / "ch07/src", root / "submission/ch07/src", fs::copy_options::recursive);
    const auto [solved, solved_json] = autograde(root);
    CHECK(solved == "score 7 of 7, 5 tests");

    // A region that does not compile costs its own exercise only: it is graded with its
    // stub, with the compiler's first error on the kit's line of the region's text (the
    // rest of the file is the kit's); the other exercise still scores.
    write_file(root / "submission/ch07/src/exactpixels/answer.cpp",
               "int triangle_number(int n) {\n"
               "    // EXERCISE ch07-triangle: add 1, 2, ..., n.\n"
               "    return n +;\n"
               "    // END EXERCISE ch07-triangle\n");
    const auto [broken, broken_json] = autograde(root);
    CHECK(broken == "score 4 of 7, 5 tests");
    CHECK(broken_json.find("ch07-triangle: does not compile, graded with its stub; the "
                           "compiler's first error: src/exactpixels/answer.cpp:10:") !=
          std::string::npos);
    CHECK(broken_json.find("ch07-answer: taken from the submission") !=
          std::string::npos);
    const std::string grade = read_file(root / "results/grade.txt");
    CHECK(grade.find("PASS 3/3 ch07-answer the answer is 42\n") != std::string::npos);
    CHECK(grade.find("FAIL 0/2 ch07-triangle triangle numbers\n") != std::string::npos);
}

TEST_CASE("a submission cannot give itself marks: only its exercise regions are taken, "
          "and the grader alone decides each test case") {
    const auto root = gradescope_root("forging").root;

    // The forgery of issue 31 (tests/fixtures/kits/forging): an unsolved kit whose
    // answer.hpp includes a header that rewrites the test program's report as it exits,
    // and whose ch07-triangle region tries to include it as well.
    fs::copy(source_root / "tests/fixtures/kits/forging", root / "submission",
             fs::copy_options::recursive);
    const auto [forged, forged_json] = autograde(root);
    // Only the point of the test that checks no exercise: 0 for both exercises.
    CHECK(forged == "score 1 of 7, 5 tests");
    CHECK(forged_json.find("ch07-answer: taken from the submission") !=
          std::string::npos);
    CHECK(forged_json.find("ch07-triangle: not taken, it holds a preprocessor line; "
                           "graded with its stub") != std::string::npos);
    const std::string grade = read_file(root / "results/grade.txt");
    CHECK(grade.find("FAIL 0/3 ch07-answer the answer is 42\n") != std::string::npos);
    CHECK(grade.find("FAIL 0/2 ch07-triangle triangle numbers\n") != std::string::npos);
    CHECK(grade.find("TOTAL 1/7 points") != std::string::npos);
}

TEST_CASE("a submitted region is refused when it could reach outside its region") {
    // Each region below is written into the fixture kit's ch07-answer region; the
    // grader takes the good ones and keeps the stub for the others.
    const auto& fixture = built_fixture_kit();
    const auto runner_built = run_command(cmake() + " --build " + quoted(fixture.build) +
                                          " --target grade-runner");
    INFO(runner_built.out << runner_built.err);
    REQUIRE(runner_built.exit_code == 0);
    const fs::path fresh_kit = scratch("region-fresh") / "ch07";
    REQUIRE(make_kit(fixture_tree(), "07", fresh_kit).exit_code == 0);
    const fs::path submission = scratch("region-submission");
    const std::string kit_header = read_file(fresh_kit / "src/exactpixels/answer.hpp");
    const std::string stub = "    return 0; // stub: a neutral value\n";
    REQUIRE(kit_header.find(stub) != std::string::npos);
    struct Example {
        std::string region, note;
    };
    const Example examples[] = {
        {"    const int six = 6'0 / 1'0; // {\n    return six * 7; /* } */\n", "taken"},
        {"    return std::string(\"}\").size() == 1 ? R\"x(})x\"[0] : '}';\n", "taken"},
        {"#define CHECK(x) (void)0\n    return 42;\n", "it holds a preprocessor line"},
        {"    %:include <cstdio>\n    return 42;\n", "it holds a preprocessor line"},
        {"    return 42;\n}\nint cheat = 0;\ninline int more() {\n    return 1;\n",
         "it closes a brace that it did not open"},
        {"    return 42; /*\n", "it leaves a comment or a literal open"},
        {"    asm(\"nop\");\n    return 42;\n", "it uses asm"},
        {"    return 42; \\\n", "it holds a line continuation"},
        {"    if (true) {\n        return 42;\n", "it leaves a brace open"},
    };
    for (const auto& example : examples) {
        CAPTURE(example.region);
        std::string header = kit_header;
        header.replace(header.find(stub), stub.size(), example.region);
        write_file(submission / "src/exactpixels/answer.hpp", header);
        const fs::path kit = scratch("region-kit");
        fs::copy(fresh_kit, kit, fs::copy_options::recursive);
        // A grade from an earlier run: gone even though this run cannot grade.
        write_file(kit / "grade.txt", "TOTAL 6/6 points; 4/4 test cases passed\n");
        const auto ran = run_command(quoted(fixture.build / "bin/grade-runner") +
                                     " --tests /nonexistent" + " --grade-file " +
                                     quoted(kit / "grade.txt") + " --source-dir " +
                                     quoted(kit) + " --submission " + quoted(submission));
        CHECK(ran.exit_code == 2); // the test program /nonexistent cannot list its tests
        CHECK_FALSE(fs::exists(kit / "grade.txt"));
        const std::string taken = read_file(kit / "src/exactpixels/answer.hpp");
        if (example.note == "taken") {
            CHECK(ran.out.find("ch07-answer: taken from the submission") !=
                  std::string::npos);
            CHECK(taken == header);
        } else {
            CHECK(ran.out.find("ch07-answer: not taken, " + example.note) !=
                  std::string::npos);
            CHECK(taken == kit_header);
        }
        // The other region was not in this submission: its stub stays.
        CHECK(ran.out.find("ch07-triangle: not found in the submission's "
                           "src/exactpixels/answer.cpp, graded with its stub") !=
              std::string::npos);
    }
}

TEST_CASE("code under test cannot speak for the grade reporter: no report file to "
          "rewrite, and lines without the grader's key are not the reporter's") {
    // The forging files whole, as if they had reached the test program (the grader
    // takes only regions, so they cannot): the header rewrites the --out= file at exit
    // and prints PASS lines of its own.
    const auto& fixture = built_fixture_kit();
    const fs::path forging = source_root / "tests/fixtures/kits/forging/src/exactpixels";
    write_file(fixture.kit / "src/exactpixels/forge.hpp",
               read_file(forging / "forge.hpp"));
    const Grade grade = grade_broken(read_file(forging / "answer.hpp"),
                                     read_file(forging / "answer.cpp"), 10);
    fs::remove(fixture.kit / "src/exactpixels/forge.hpp");
    REQUIRE(grade.well_formed);
    REQUIRE(grade.cases.size() == 5);
    CHECK(grade.cases[0].status == "FAIL");
    CHECK(grade.cases[1].status == "FAIL");
    CHECK(grade.earned == 1);
}

namespace {

/// The fixture kit with its solutions restored and the hidden test added, built once: the
/// program whose test cases give a kit its time limits, as the book's own test_chNN does
/// for a chapter's kit.
const fs::path& solved_fixture_build() {
    static const fs::path solved = [] {
        const fs::path kit = scratch("solved-kit") / "ch07";
        const fs::path build_dir = scratch("solved-build");
        REQUIRE(make_kit(fixture_tree(), "07", kit).exit_code == 0);
        REQUIRE(restore_kit(fixture_tree(), kit).exit_code == 0);
        fs::create_directories(kit / "tests/hidden");
        fs::copy_file(fixture_tree() / "tests/hidden/ch07_hidden.cpp",
                      kit / "tests/hidden/ch07_hidden.cpp");
        REQUIRE(configure(kit, build_dir).exit_code == 0);
        const auto built = build(build_dir);
        INFO(built.out << built.err);
        REQUIRE(built.exit_code == 0);
        return build_dir;
    }();
    return solved;
}

/// A submission for the fixture kit `kit` (fresh): its src/ with the ch07-answer region
/// solved and the ch07-triangle region's stub replaced by `triangle`.
void submit(const fs::path& kit, const fs::path& root, const std::string& triangle) {
    fs::remove_all(root / "submission");
    fs::create_directories(root / "submission");
    fs::copy(kit / "src", root / "submission/src", fs::copy_options::recursive);
    const auto replace = [&](const std::string& file, const std::string& stub,
                             const std::string& text) {
        std::string code = read_file(root / "submission" / file);
        REQUIRE(code.find(stub) != std::string::npos);
        code.replace(code.find(stub), stub.size(), text);
        write_file(root / "submission" / file, code);
    };
    replace("src/exactpixels/answer.hpp", "    return 0; // stub: a neutral value\n",
            "    return 42;\n");
    replace("src/exactpixels/answer.cpp", "    (void)n; // stub: the sum of nothing\n",
            triangle);
}

} // namespace

TEST_CASE("each test case's time limit comes from the solution's own time; a region that "
          "never ends is stopped in seconds and the other exercises still score") {
    const fs::path solved = solved_fixture_build();
    const auto [out, root] = gradescope_root(
        "timed", " -DGRADE_RUNNER=" + quoted(solved / "bin/grade-runner") +
                     " -DTIMING_PROGRAM=" + quoted(solved / "bin/test_ch07"));
    // time_limits.txt, in the students' kit and the autograder: per test case (the hidden
    // one too, the skipped one not) MULTIPLE x the solution's time + FLOOR s, rounded up,
    // and a budget of BUDGET_MULTIPLE x the total + BUDGET_FLOOR s.
    const std::string limits = read_file(out / "ch07/time_limits.txt");
    CHECK(read_file(root / "source/time_limits.txt") == limits);
    const fs::path kit = out / "ch07";
    std::map<std::string, int> limit_of;
    double total = 0;
    int budget = 0;
    for (const auto& line : lines_of(limits)) {
        if (line.empty() || line[0] == '#') {
            continue;
        }
        std::istringstream in(line);
        std::string first, name;
        double measured = -1;
        in >> first;
        if (first == "budget") {
            in >> budget;
            continue;
        }
        in >> measured;
        in.get();
        std::getline(in, name);
        CAPTURE(line);
        REQUIRE(measured >= 0);
        CHECK(std::stoi(first) == static_cast<int>(std::ceil(
                                      runner_constant(kit, "limit_multiple") * measured +
                                      runner_constant(kit, "limit_floor_seconds"))));
        limit_of[name] = std::stoi(first);
        total += measured;
    }
    CHECK(limit_of.size() == 5);
    CHECK(limit_of.count("a hidden triangle number") == 1);
    CHECK(budget ==
          static_cast<int>(std::ceil(runner_constant(kit, "budget_multiple") * total +
                                     runner_constant(kit, "budget_floor_seconds"))));

    // ch07-triangle never ends: its two test cases stop at their limits, a few seconds
    // each, with the rerun command; ch07-answer and the rest score as before.
    submit(kit, root,
           "    volatile int spin = 0;\n    while (spin == 0) {\n    }\n    (void)n;\n");
    std::string printed;
    const auto [summary, json] = autograde(root, &printed);
    CHECK(summary == "score 4 of 7, 5 tests");
    const Grade grade = parse_grade(read_file(root / "results/grade.txt"));
    REQUIRE(grade.well_formed);
    int stopped = 0;
    for (const auto& line : grade.cases) {
        CAPTURE(line.name);
        if (line.exercise != "ch07-triangle") {
            CHECK(line.status != "FAIL");
            continue;
        }
        ++stopped;
        const std::string seconds = std::to_string(limit_of.at(line.name)) + " s";
        CHECK(reason_with(line, "time limit " + seconds +
                                    " exceeded: still running after " + seconds) != "");
        CHECK(reason_with(line, "to run this test case alone: ") != "");
    }
    CHECK(stopped == 2);
    // The grade arrived in seconds: the stopped cases took about their limits, and all
    // test cases together little more.
    const Slowest slowest = slowest_case(printed);
    INFO(printed);
    CHECK(slowest.lines == 6); // the skipped test case's line too
    CHECK(slowest.seconds < limit_of.at("triangle numbers") + 3);
    CHECK(slowest.total <
          limit_of.at("triangle numbers") + limit_of.at("a hidden triangle number") + 5);
    MESSAGE("an endless region: the test cases took " << slowest.total << " s in all");
}

TEST_CASE("run as root, the autograder builds and runs a submission as an unprivileged "
          "user that can read neither the autograder's files nor write its results") {
    const auto [out, root] = gradescope_root("isolated");
    // The ch07-triangle region reads the autograder's script and overwrites results.json
    // when it can, and then returns a wrong sum; when both fail, the right one.
    const std::string at = root.string();
    submit(
        out / "ch07", root,
        "    std::FILE* source = std::fopen(\"" + at +
            "/source/run_autograder\", \"r\");\n"
            "    std::FILE* results = std::fopen(\"" +
            at + "/results/results.json\", \"w\");\n" +
            "    const bool reached = source != nullptr || results != nullptr;\n"
            "    if (source != nullptr) {\n        std::fclose(source);\n    }\n"
            "    if (results != nullptr) {\n"
            "        std::fputs(\"{\\\"score\\\": 100, \\\"tests\\\": []}\\n\", "
            "results);\n"
            "        std::fclose(results);\n    }\n"
            "    for (int k = 1; k <= n && !reached; ++k) {\n        sum += k;\n    }\n");
    std::string printed;
    const auto [summary, json] = autograde(root, &printed);
    CHECK(json.find("ch07-triangle: taken from the submission") != std::string::npos);
    if (::geteuid() != 0) {
        // At a desk: no isolation, and the autograder says so.
        CHECK(
            printed.find("not run as root, so the submission is built and run as you") !=
            std::string::npos);
        MESSAGE("not root: the isolation of the autograder was not tested");
        return;
    }
    CHECK(printed.find("building and running the submission as ") != std::string::npos);
    // Both attempts failed: every test case passes, and results.json is the grader's.
    CHECK(summary == "score 7 of 7, 5 tests");
}
