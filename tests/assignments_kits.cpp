// Assignment kits (src/kits/): make-kit turns the book's own tested code into a chapter's
// starter project; these tests prove that the kits are what the issue asks for.
//
// - make-kit reads exercise regions exactly as book/AUTHORING.md defines them and refuses
//   malformed ones (naming file and line), and refuses a region no test checks;
// - on a fixture tree (tests/fixtures/kits/tree): the kit holds the chapter's stubs and
//   every other chapter's solutions, no marker line, the example, tests and fixture data;
//   the zip holds the same files; the grade is exactly the expected lines, twice the
//   same;
// - for every chapter of the book: its kit configures and builds on its own, outside the
//   source tree; fresh, every test of an exercise fails and every other test passes;
//   restored, every test passes and the grade reaches full marks; the restored kit's code
//   is the book's code with the markers removed.
//
// Time: the chapter kits share one kit folder and one build folder. Each kit is made into
// the same folder in turn; make-kit rewrites only files whose content changes, so the
// build recompiles only what differs between two kits (the stubbed files and the tests).
// Every build is still a correct build of that kit: make sees every changed file.
#include "support/process.hpp"

#include <doctest/doctest.h>

#include <algorithm>
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

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        lines.push_back(line);
    }
    return lines;
}

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

CommandResult restore_kit(const fs::path& source, const fs::path& kit) {
    return run_command(std::string("'") + EXACTPIXELS_MAKE_KIT + "' restore --source " +
                       quoted(source) + " --kit " + quoted(kit));
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
};

/// The grade file, parsed strictly: every line but the last is a test case line, the last
/// is "TOTAL E/D points; P/N test cases passed" and agrees with the lines above it.
struct Grade {
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
std::string run_grade(const fs::path& build_dir) {
    const auto result =
        run_command(cmake() + " --build " + quoted(build_dir) + " --target grade");
    INFO(result.out << result.err);
    CHECK(result.exit_code == 0);
    const std::string text = read_file(build_dir / "grade.txt");
    CHECK(result.out.find(text) != std::string::npos);
    return text;
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

/// The kit's text minus its EXERCISE / END EXERCISE comment lines.
std::string without_kit_comments(const std::string& text) {
    std::string out;
    for (const auto& line : lines_of(text)) {
        if (!std::regex_match(line, kit_begin) && !std::regex_match(line, kit_end)) {
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
                                               "grade.cmake",
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
    // chapter 08's region keeps its solution and loses its stub; the snippet markers go.
    CHECK(read_file(kit / "src/exactpixels/answer.hpp") ==
          "// answer.hpp: a tiny fake library for the assignment-kit tests "
          "(tests/assignments_kits.cpp).\n"
          "// Chapter 07 (\"fake\") has two exercise regions, chapter 08 one; a snippet "
          "region encloses\n"
          "// an exercise region, as the book allows.\n"
          "#pragma once\n\nnamespace fake {\n\n"
          "/// The answer, computed.\n"
          "inline int answer() {\n"
          "    // EXERCISE ch07-answer: six times seven.\n"
          "    return 0; // stub: a neutral value\n"
          "    // END EXERCISE ch07-answer\n"
          "}\n\n"
          "/// 1 + 2 + ... + n.\n"
          "int triangle_number(int n);\n\n"
          "/// 2 x, chapter 08's exercise (keeps its solution in chapter 07's kit).\n"
          "inline int twice(int x) {\n"
          "    return x + x;\n"
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
    CHECK(readme.find("| `ch07-answer` | `src/exactpixels/answer.hpp:10` | 3 | six times "
                      "seven. |") != std::string::npos);
    CHECK(
        readme.find("| `ch07-triangle` | `src/exactpixels/answer.cpp:7` | 2 | add 1, 2, "
                    "..., n. |") != std::string::npos);
    CHECK(readme.find("- `ch07-triangle`: \"triangle numbers\"") != std::string::npos);
    CHECK(readme.find("1. Implement `answer` (\"the answer is 42\").\n2. Derive") !=
          std::string::npos);
    CHECK(readme.find("Not part of the README") == std::string::npos);
    CHECK(readme.find("worth 6 points") != std::string::npos);
    CHECK(readme.find("cmake --build build --target grade") != std::string::npos);
    CHECK(readme.find("@") == std::string::npos); // every placeholder filled

    // Chapter 08's kit takes the wrapped hint whole.
    const fs::path kit08 = kits / "ch08";
    REQUIRE(make_kit(tree, "08", kit08).exit_code == 0);
    CHECK(
        read_file(kit08 / "src/exactpixels/answer.hpp")
            .find("    // EXERCISE ch08-twice: add x to itself; this hint is long enough "
                  "that clang-format wraps it.\n    (void)x;\n    return 0;\n"
                  "    // END EXERCISE ch08-twice\n") != std::string::npos);

    // Made again into the same folder, the kit is the same and unchanged files keep their
    // time stamps (so a build in the kit's place recompiles only what changed).
    const auto stamp = fs::last_write_time(kit / "src/exactpixels/answer.cpp");
    write_file(kit / "src/exactpixels/answer.cpp",
               read_file(kit / "src/exactpixels/answer.cpp"));
    const auto touched = fs::last_write_time(kit / "src/exactpixels/answer.cpp");
    REQUIRE(make_kit(tree, "07", kit).exit_code == 0);
    CHECK(fs::last_write_time(kit / "src/exactpixels/answer.cpp") == touched);
    CHECK(touched >= stamp);
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
    CHECK(fresh == "FAIL 0/3 ch07-answer the answer is 42\n"
                   "FAIL 0/2 ch07-triangle triangle numbers\n"
                   "PASS 1/1 - twice is kept from chapter 08\n"
                   "PASS 0/0 - the fixture data travels with the kit\n"
                   "SKIP 0/5 - a skipped test\n"
                   "TOTAL 1/6 points; 2/4 test cases passed\n");
    CHECK(parse_grade(fresh).well_formed);
    CHECK(run_grade(build_dir) == fresh);
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
    CHECK(full == "PASS 3/3 ch07-answer the answer is 42\n"
                  "PASS 2/2 ch07-triangle triangle numbers\n"
                  "PASS 1/1 - twice is kept from chapter 08\n"
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
        const Grade fresh = parse_grade(run_grade(build_dir));
        CHECK(fresh.well_formed);
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

        // Restored: the code is the book's, every test passes, full marks.
        const auto restored = restore_kit(source_root, kit);
        INFO(restored.out << restored.err);
        REQUIRE(restored.exit_code == 0);
        for (const auto& rel : files_under(kit)) {
            if (is_code(rel) && !starts_with(rel.generic_string(), "tests/support/")) {
                INFO("restored file " << rel.string());
                CHECK(without_kit_comments(read_file(kit / rel)) ==
                      without_markers(read_file(source_root / rel)));
            }
        }
        const auto rebuilt = build(build_dir);
        INFO(rebuilt.out << rebuilt.err);
        REQUIRE(rebuilt.exit_code == 0);
        const Grade full = parse_grade(run_grade(build_dir));
        CHECK(full.well_formed);
        CHECK(full.earned == full.declared);
        CHECK(full.passed == full.counted);
        // Stable: the same test cases, in the same order, declaring the same points.
        REQUIRE(full.cases.size() == fresh.cases.size());
        for (std::size_t i = 0; i < full.cases.size(); ++i) {
            CHECK(full.cases[i].name == fresh.cases[i].name);
            CHECK(full.cases[i].exercise == fresh.cases[i].exercise);
            CHECK(full.cases[i].declared == fresh.cases[i].declared);
        }
    }
}
