// make-kit: a chapter's course-assignment kit, generated from the book's own tested code.
//
// Usage:
//   make-kit kit --source ROOT --template DIR --chapter NN --out DIR [--version V]
//                [--commit C] [--time-limits FILE]
//   make-kit restore --source ROOT --kit DIR [--later restore|stub]
//   make-kit list --source ROOT
//   make-kit check --source ROOT [--chapter NN]
//   make-kit stub --source ROOT --file FILE
//
// `kit` writes DIR as a self-contained CMake project: of src/, the library layers that
// chapter NN's code includes and those beneath them (src/exactpixels/layers.txt), the
// command-line program and the CMakeLists.txt files (minus the line that adds src/kits),
// chapter NN's example folder, its tests (tests/chNN_*, tests/fixtures/chNN*), the test
// headers they include (tests/*.hpp) and the support files (tests/support/). Every
// exercise region of chapter NN (see book/AUTHORING.md, "Exercise regions") is replaced
// by its stub between two plain comments,
//     // EXERCISE ch02-edge-bias: one-line hint
//     ...stub...
//     // END EXERCISE ch02-edge-bias
// while every earlier chapter keeps its solution. Every region of a later chapter, and
// every gives-away block of one (`//> gives-away ID` ... `//< gives-away ID`: code
// outside a region that states its answer), is its stub between `// LATER EXERCISE ID:`
// and `// END LATER EXERCISE ID`, so that no kit holds an answer its students have not
// been set yet; the grader never takes those from a submission. Only the later exercises
// that `kit-keeps-later` (book/metadata.yaml) lists for chapter NN, because its own code
// runs them, keep their solution. Every marker line (`//>`, `//<`, `//|`) is removed. The template folder supplies the kit's CMakeLists.txt, README.md, its
// grader (grade_runner.cpp) and Gradescope's two scripts, setup.sh and run_autograder
// (NAME.in with @CHAPTER@-style placeholders, or NAME copied as it is). --time-limits
// FILE (written by grade-runner --measure from the solution) becomes the kit's
// time_limits.txt. The teacher's hidden tests (tests/hidden/) never go into a kit (the
// assignment script adds them to the autograder's zip only). DIR is deleted first if it
// holds an earlier kit.
//
// `restore` puts the solution of every exercise back between those comments (and the
// later chapters' code between the LATER ones, unless `--later stub`: the kit as a
// student who solved every exercise has it, which must reach full marks) in a kit
// (the teacher's copy; the kit tests use it to prove the stubs are the only difference).
// `list` prints every exercise region and the tests that declare points for it.
// `check` proves that the book's marks and the kits' points agree, for every chapter (or
// chapter NN): an exercise with a region is worth `kit-points-per-mark`
// (book/metadata.yaml) points per mark of its tag in the chapter, summed over the tests
// that name it; every region has a tag and every tag's region exists; a test that names
// no exercise declares no points (it would give points for nothing). It prints every
// disagreement, with file and line, and exits 1 if there is one.
// `stub` prints FILE (a path under ROOT) with every exercise region, of any chapter,
// replaced by its stub as a kit has it, and every gives-away block by its stub: the
// course edition's API reference reads the library through it (Doxygen's INPUT_FILTER),
// so it shows no solution.
//
// The kit is checked while it is made: every exercise region of chapter NN must be named
// by a test of chapter NN with points > 0, and every exercise a test names must exist.
// Errors name file and line and make the program exit with status 1.
#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/base/error.hpp"
#include "support/declared_points.hpp" // tests/support: the grade reporter reads it too

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace fs = std::filesystem;

using exactpixels::testing::DeclaredPoints;
using exactpixels::testing::parse_declared_points;

namespace {

struct KitError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// ---------------------------------------------------------------------------------------
// Text helpers

std::string read_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw KitError("cannot read " + path.string());
    }
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

void write_text(const fs::path& path, const std::string& text) {
    fs::create_directories(path.parent_path());
    try { // all or nothing, every write checked (chapter 0's atomic_file.hpp)
        exactpixels::write_file_atomically(path, "kit", text);
    } catch (const exactpixels::Error& error) {
        throw KitError(error.what());
    }
}

std::vector<std::string> split_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::string::size_type start = 0;
    while (start < text.size()) {
        const auto end = text.find('\n', start);
        if (end == std::string::npos) {
            lines.push_back(text.substr(start));
            break;
        }
        lines.push_back(text.substr(start, end - start));
        start = end + 1;
    }
    return lines;
}

std::string join_lines(const std::vector<std::string>& lines) {
    std::string text;
    for (const auto& line : lines) {
        text += line;
        text += '\n';
    }
    return text;
}

std::string_view trim(std::string_view text) {
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) {
        text.remove_prefix(1);
    }
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) {
        text.remove_suffix(1);
    }
    return text;
}

bool starts_with(std::string_view text, std::string_view prefix) {
    return text.substr(0, prefix.size()) == prefix;
}

std::string replace_all(std::string text, const std::string& from,
                        const std::string& to) {
    std::string::size_type at = 0;
    while ((at = text.find(from, at)) != std::string::npos) {
        text.replace(at, from.size(), to);
        at += to.size();
    }
    return text;
}

std::string where(const fs::path& file, std::size_t line) {
    return file.generic_string() + ":" + std::to_string(line);
}

/// "chNN-name": the prefix ch, two digits, a dash, then lower-case letters, digits,
/// dashes.
bool valid_exercise_id(std::string_view id) {
    if (id.size() < 6 || !starts_with(id, "ch") || !std::isdigit(id[2]) ||
        !std::isdigit(id[3]) || id[4] != '-') {
        return false;
    }
    return std::all_of(id.begin() + 5, id.end(), [](char c) {
        return std::islower(static_cast<unsigned char>(c)) ||
               std::isdigit(static_cast<unsigned char>(c)) || c == '-';
    });
}

bool is_code_file(const fs::path& path) {
    static const std::set<std::string> extensions = {".cpp", ".hpp", ".h",
                                                     ".cc",  ".inl", ".ipp"};
    return extensions.count(path.extension().string()) != 0;
}

// ---------------------------------------------------------------------------------------
// Exercise regions

/// One `//> exercise ID: hint` ... `//< exercise ID` region of solution code, or one
/// `//> gives-away ID` ... `//< gives-away ID` block: code outside the region that states
/// exercise ID's answer (a second use of the same formula), shown wherever the region is
/// shown as its stub: as its own stub lines (`//|`), which must compile.
struct Region {
    std::string id;                    // e.g. "ch02-edge-bias"
    std::string hint;                  // the one-line hint after the colon
    fs::path file;                     // relative to the source root
    std::size_t line = 0;              // of the opening marker, 1-based
    std::vector<std::string> solution; // the code lines, markers removed
    std::vector<std::string> stub;     // the uncommented stub lines
    std::size_t kit_line = 0;          // of the EXERCISE comment in the kit, if stubbed
    bool gives_away = false;           // a gives-away block, not the exercise's region
    std::string chapter() const { return id.substr(0, 4); }
};

const std::string kit_begin = "// EXERCISE ";
const std::string kit_end = "// END EXERCISE ";
// A region or gives-away block of a later chapter's exercise, shipped as its stub: the
// grader never takes it from a submission (it is not an EXERCISE region) and `restore`
// puts its solution back.
const std::string later_begin = "// LATER EXERCISE ";
const std::string later_end = "// END LATER EXERCISE ";
// A gives-away block as the course edition's API reference shows it.
const std::string course_hidden_begin =
    "// NOT IN THE COURSE EDITION (it would give exercise ";
const std::string course_hidden_end = "// END OF WHAT THE COURSE EDITION LEAVES OUT";

/// A file after the region markers have been interpreted.
struct Processed {
    std::vector<std::string> lines; // the kit's text of the file
    std::vector<Region> regions;    // every exercise region found in it
    std::vector<Region> blocks;     // every region and gives-away block, in file order
};

/// How a kit shows a region or block.
enum class Shown { solution, exercise, later };

/// Reads the markers of one file. `stub_chapter` is "chNN" for chapter NN's kit: its
/// regions become their stubs between the kit's EXERCISE comments, every region and
/// gives-away block of a later chapter its stub between LATER EXERCISE comments (a kit
/// holds no answer of a chapter after its own) unless `keep_later` names its exercise
/// (`kit-keeps-later`, book/metadata.yaml), and an earlier chapter's keep their
/// solution. "*" (the course edition's API reference) shows every region as its EXERCISE
/// stub and every gives-away block as its stub; "" keeps every solution.
Processed process_file(const fs::path& rel, const std::string& text,
                       const std::string& stub_chapter,
                       const std::set<std::string>& keep_later = {}) {
    Processed result;
    std::optional<Region> open;
    const auto lines = split_lines(text);
    const auto shown = [&](const Region& region) {
        if (stub_chapter.empty()) {
            return Shown::solution;
        }
        if (stub_chapter == "*") {
            return region.gives_away ? Shown::later : Shown::exercise;
        }
        if (region.chapter() == stub_chapter) {
            return region.gives_away ? Shown::solution : Shown::exercise;
        }
        return region.chapter() > stub_chapter && keep_later.count(region.id) == 0
                   ? Shown::later
                   : Shown::solution;
    };
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const std::string& line = lines[i];
        const auto first = line.find_first_not_of(" \t");
        const std::string indent = line.substr(0, first == std::string::npos ? 0 : first);
        const std::string_view rest = first == std::string::npos
                                          ? std::string_view{}
                                          : std::string_view(line).substr(first);
        const bool stubbing = open && shown(*open) != Shown::solution;
        if (starts_with(rest, "//>") || starts_with(rest, "//<")) {
            const std::string_view body = trim(rest.substr(3));
            const bool exercise = starts_with(body, "exercise ") || body == "exercise";
            const bool gives_away = starts_with(body, "gives-away ");
            if (!exercise && !gives_away) {
                continue; // a snippet marker: never part of a kit
            }
            const std::string kind = exercise ? "exercise" : "gives-away";
            const std::string_view spec = trim(body.substr(kind.size()));
            if (rest[2] == '>') {
                if (open) {
                    throw KitError(where(rel, i + 1) + ": " + kind + " region inside region " +
                                   open->id + " (opened at line " +
                                   std::to_string(open->line) + ")");
                }
                const auto colon = spec.find(':');
                const std::string id(trim(spec.substr(0, colon)));
                std::string hint(colon == std::string_view::npos
                                     ? std::string_view{}
                                     : trim(spec.substr(colon + 1)));
                const std::size_t open_line = i + 1;
                // A hint too long for one line, as clang-format reflows it: the next
                // lines at the same indent read "//word" (no space after the slashes).
                while (exercise && i + 1 < lines.size() &&
                       starts_with(lines[i + 1], indent + "//") &&
                       lines[i + 1].size() > indent.size() + 2 &&
                       std::string_view(" /<>|!").find(lines[i + 1][indent.size() + 2]) ==
                           std::string_view::npos) {
                    hint += " " +
                            std::string(trim(
                                std::string_view(lines[++i]).substr(indent.size() + 2)));
                }
                if (!valid_exercise_id(id)) {
                    throw KitError(where(rel, open_line) + ": exercise ID '" + id +
                                   "' is not of the form chNN-name");
                }
                if (exercise && hint.empty()) {
                    throw KitError(where(rel, open_line) + ": exercise " + id +
                                   " has no hint ('//> exercise " + id + ": hint')");
                }
                open = Region{id, hint, rel, open_line, {}, {}, 0, gives_away};
                switch (shown(*open)) {
                case Shown::exercise:
                    result.lines.push_back(indent + kit_begin + id + ": " + hint);
                    open->kit_line = result.lines.size();
                    break;
                case Shown::later:
                    result.lines.push_back(
                        indent + (stub_chapter == "*"
                                      ? course_hidden_begin + id + " away); a stub:"
                                      : later_begin + id + ": chapter " + id.substr(2, 2) +
                                            "'s, not graded here; its stub until then"));
                    open->kit_line = result.lines.size();
                    break;
                case Shown::solution:
                    break;
                }
            } else {
                const std::string id(trim(spec));
                if (!open || open->id != id || open->gives_away != gives_away) {
                    throw KitError(where(rel, i + 1) + ": '//< " + kind + " " + id +
                                   "' closes no open region" +
                                   (open ? " (open: " + open->id + ")" : std::string{}));
                }
                if (gives_away && open->stub.empty()) {
                    throw KitError(where(rel, open->line) + ": gives-away block of " + id +
                                   " has no stub ('//|' lines that compile)");
                }
                if (stubbing) {
                    result.lines.push_back(indent + (shown(*open) == Shown::exercise
                                                         ? kit_end + id
                                                     : stub_chapter == "*"
                                                         ? course_hidden_end
                                                         : later_end + id));
                }
                result.blocks.push_back(*open);
                if (!gives_away) {
                    result.regions.push_back(std::move(*open));
                }
                open.reset();
            }
        } else if (starts_with(rest, "//|")) {
            if (!open) {
                throw KitError(where(rel, i + 1) +
                               ": stub line '//|' outside any exercise region");
            }
            std::string_view stub = rest.substr(3);
            if (starts_with(stub, " ")) {
                stub.remove_prefix(1);
            }
            open->stub.push_back(indent + std::string(stub));
            if (stubbing) {
                result.lines.push_back(open->stub.back());
            }
        } else {
            if (open) {
                open->solution.push_back(line);
            }
            if (!stubbing) {
                result.lines.push_back(line);
            }
        }
    }
    if (open) {
        throw KitError(where(rel, open->line) + ": exercise region " + open->id +
                       " is never closed ('//< exercise " + open->id + "')");
    }
    return result;
}

/// Every code file under src/, chapters/ and tests/ (test fixtures excluded), relative to
/// the root, sorted so that the output never depends on directory order.
std::vector<fs::path> code_files(const fs::path& root) {
    std::vector<fs::path> files;
    for (const char* top : {"src", "chapters", "tests"}) {
        if (!fs::is_directory(root / top)) {
            continue;
        }
        for (const auto& entry : fs::recursive_directory_iterator(root / top)) {
            const fs::path rel = fs::relative(entry.path(), root);
            if (entry.is_regular_file() && is_code_file(rel) &&
                !starts_with(rel.generic_string(), "tests/fixtures/")) {
                files.push_back(rel);
            }
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

/// Every exercise region in the tree, by ID (IDs are unique across the tree).
std::map<std::string, Region> all_regions(const fs::path& root) {
    std::map<std::string, Region> regions;
    std::vector<Region> gives_away;
    for (const auto& rel : code_files(root)) {
        for (auto& block : process_file(rel, read_text(root / rel), "").blocks) {
            if (block.gives_away) {
                gives_away.push_back(std::move(block));
                continue;
            }
            const auto [it, fresh] = regions.emplace(block.id, block);
            if (!fresh) {
                throw KitError(where(rel, block.line) + ": exercise " + block.id +
                               " is also defined at " +
                               where(it->second.file, it->second.line));
            }
        }
    }
    for (const auto& block : gives_away) {
        if (regions.count(block.id) == 0) {
            throw KitError(where(block.file, block.line) + ": gives-away block of " +
                           block.id + ", which is no exercise region");
        }
    }
    return regions;
}

// ---------------------------------------------------------------------------------------
// Tests and their declared points

/// A TEST_CASE with the points and exercise its description declares.
struct TestDecl {
    std::string name;
    fs::path file;
    std::size_t line = 0;
    int points = 0;
    std::string exercise; // empty for none
    bool skipped = false; // doctest::skip: counts in no total
};

std::size_t line_of(const std::string& text, std::size_t offset) {
    return 1 + static_cast<std::size_t>(std::count(
                   text.begin(), text.begin() + static_cast<long>(offset), '\n'));
}

/// The string literal starting at text[at] == '"' (escapes kept as written).
std::string literal_at(const std::string& text, std::size_t at, std::size_t* end) {
    std::string value;
    std::size_t i = at + 1;
    for (; i < text.size() && text[i] != '"'; ++i) {
        if (text[i] == '\\' && i + 1 < text.size()) {
            value += text[i++];
        }
        value += text[i];
    }
    *end = i + 1;
    return value;
}

/// Finds every TEST_CASE* in a test file and reads `doctest::description("points: N;
/// exercise: ID")` among its decorators (between the name and the opening brace).
std::vector<TestDecl> test_declarations(const fs::path& root, const fs::path& rel) {
    const std::string text = read_text(root / rel);
    std::vector<TestDecl> tests;
    std::size_t at = 0;
    while ((at = text.find("TEST_CASE", at)) != std::string::npos) {
        const std::size_t start = at;
        at += 9;
        // Skip mentions inside identifiers and the DOCTEST_ prefixed forms' definitions.
        if (start > 0 && (std::isalnum(static_cast<unsigned char>(text[start - 1])) ||
                          text[start - 1] == '_')) {
            continue;
        }
        // TEST_CASE, TEST_CASE_FIXTURE, TEST_CASE_TEMPLATE, ... then "(" and the name.
        while (at < text.size() && (std::isupper(static_cast<unsigned char>(text[at])) ||
                                    text[at] == '_' || text[at] == ' ')) {
            ++at;
        }
        if (at >= text.size() || text[at] != '(') {
            continue;
        }
        const auto quote = text.find('"', at);
        if (quote == std::string::npos || text.find_first_of(");", at) < quote) {
            continue;
        }
        TestDecl test;
        std::size_t after = 0;
        test.name = literal_at(text, quote, &after);
        const auto brace = std::min(text.find('{', after), text.size());
        test.file = rel;
        test.line = line_of(text, start);
        const std::string decorators = text.substr(after, brace - after);
        test.skipped = decorators.find("doctest::skip") != std::string::npos;
        const auto desc = decorators.find("description");
        if (desc != std::string::npos) {
            const auto q = decorators.find('"', desc);
            std::size_t unused = 0;
            const std::string description =
                q == std::string::npos ? "" : literal_at(decorators, q, &unused);
            const DeclaredPoints declared = parse_declared_points(description);
            if (!declared.bad_points.empty()) {
                throw KitError(where(rel, test.line) + ": test \"" + test.name +
                               "\": points '" + declared.bad_points +
                               "' is not a whole number");
            }
            test.points = declared.points;
            test.exercise = declared.exercise;
        }
        tests.push_back(test);
        at = after;
    }
    return tests;
}

// ---------------------------------------------------------------------------------------
// The kit

/// "2", "02" or "ch02" -> "02".
std::string chapter_number(std::string text) {
    if (starts_with(text, "ch")) {
        text = text.substr(2);
    }
    if (text.size() == 1) {
        text = "0" + text;
    }
    if (text.size() != 2 || !std::isdigit(static_cast<unsigned char>(text[0])) ||
        !std::isdigit(static_cast<unsigned char>(text[1]))) {
        throw KitError("--chapter wants a chapter number such as 02, got '" + text + "'");
    }
    return text;
}

/// chapters/NN-slug, if the chapter has a folder.
std::optional<fs::path> chapter_folder(const fs::path& root, const std::string& number) {
    if (!fs::is_directory(root / "chapters")) {
        return std::nullopt;
    }
    std::vector<fs::path> found;
    for (const auto& entry : fs::directory_iterator(root / "chapters")) {
        if (entry.is_directory() &&
            starts_with(entry.path().filename().string(), number + "-")) {
            found.push_back(fs::relative(entry.path(), root));
        }
    }
    if (found.size() > 1) {
        throw KitError("chapters/ has more than one folder for chapter " + number);
    }
    return found.empty() ? std::nullopt : std::optional<fs::path>(found.front());
}

/// The library's layers (src/exactpixels/layers.txt): for each layer, itself and the
/// layers beneath it that its code may include.
std::map<std::string, std::vector<std::string>> read_layers(const fs::path& root) {
    std::map<std::string, std::vector<std::string>> layers;
    const fs::path file = root / "src/exactpixels/layers.txt";
    if (!fs::exists(file)) {
        return layers;
    }
    for (const auto& line : split_lines(read_text(file))) {
        std::istringstream words(line);
        std::string layer, beneath;
        if (line.empty() || line[0] == '#' || !(words >> layer)) {
            continue;
        }
        layers[layer] = {layer};
        while (words >> beneath) {
            layers[layer].push_back(beneath);
        }
    }
    return layers;
}

/// The layers `text` includes ("exactpixels/LAYER/file.hpp") with those beneath them.
void add_included_layers(const std::string& text,
                         const std::map<std::string, std::vector<std::string>>& layers,
                         std::set<std::string>& used) {
    const std::string marker = "#include \"exactpixels/";
    for (auto at = text.find(marker); at != std::string::npos;
         at = text.find(marker, at + 1)) {
        const auto begin = at + marker.size();
        const auto slash = text.find('/', begin);
        if (slash == std::string::npos) {
            break;
        }
        const auto found = layers.find(text.substr(begin, slash - begin));
        if (found != layers.end()) {
            used.insert(found->second.begin(), found->second.end());
        }
    }
}

/// The relative paths of every file the kit of chapter NN takes from the source tree:
/// the chapter's folder, its tests and the test headers they include, the test support
/// files, and of the library only the layers that this code reaches (with the layers
/// beneath them), so that a chapter's kit needs only its own chapters' packages.
std::vector<fs::path> kit_files(const fs::path& root, const std::string& number) {
    std::vector<fs::path> files;
    auto add_tree = [&](const fs::path& rel, auto&& keep) {
        if (!fs::exists(root / rel)) {
            return;
        }
        if (fs::is_regular_file(root / rel)) {
            files.push_back(rel);
            return;
        }
        for (const auto& entry : fs::recursive_directory_iterator(root / rel)) {
            const fs::path file = fs::relative(entry.path(), root);
            if (entry.is_regular_file() && keep(file)) {
                files.push_back(file);
            }
        }
    };
    const auto everything = [](const fs::path&) { return true; };
    add_tree("tests/support", everything);
    add_tree(".clang-format", everything);
    if (const auto folder = chapter_folder(root, number)) {
        // The example, whatever it reads, and the chapter's text (its listings are named
        // regions, so it never shows a stub; some tests read the chapter's own examples).
        add_tree(*folder, everything);
    }
    const std::string prefix = "ch" + number;
    std::vector<fs::path> test_headers;
    for (const char* top : {"tests", "tests/fixtures"}) {
        if (!fs::is_directory(root / top)) {
            continue;
        }
        for (const auto& entry : fs::directory_iterator(root / top)) {
            const std::string name = entry.path().filename().string();
            if (std::string(top) == "tests" && entry.is_regular_file() &&
                (entry.path().extension() == ".hpp" ||
                 entry.path().extension() == ".h")) {
                test_headers.push_back(fs::relative(entry.path(), root));
            } else if (starts_with(name, prefix + "_") ||
                       starts_with(name, prefix + "-") || name == prefix ||
                       (starts_with(name, prefix + ".") && entry.is_regular_file())) {
                add_tree(fs::relative(entry.path(), root), everything);
            }
        }
    }
    // A header shared by the tests (e.g. a grid helper) comes along when a test of the
    // kit includes it.
    std::string code;
    for (const auto& rel : files) {
        if (is_code_file(rel)) {
            code += read_text(root / rel);
        }
    }
    for (const auto& header : test_headers) {
        if (code.find("#include \"" + header.filename().string() + "\"") !=
            std::string::npos) {
            files.push_back(header);
            code += read_text(root / header);
        }
    }
    // A fixture the chapter's code names by path ("tests/fixtures/NAME") comes along.
    if (fs::is_directory(root / "tests/fixtures")) {
        for (const auto& entry : fs::directory_iterator(root / "tests/fixtures")) {
            const std::string name = entry.path().filename().string();
            if (code.find("tests/fixtures/" + name + "/") != std::string::npos ||
                code.find("tests/fixtures/" + name + "\"") != std::string::npos) {
                add_tree(fs::relative(entry.path(), root), everything);
            }
        }
    }
    // The library: the layers the chapter's code includes, and those beneath them. The
    // base layer always comes (the command-line program needs it).
    const auto layers = read_layers(root);
    std::set<std::string> used = {"base"};
    add_included_layers(code, layers, used);
    add_tree("src", [&](const fs::path& file) {
        const std::string path = file.generic_string();
        if (starts_with(path, "src/kits/") || starts_with(path, "src/fuzz/") ||
            starts_with(path, "src/checks/")) {
            return false;
        }
        if (starts_with(path, "src/exactpixels/")) {
            const std::string rest = path.substr(std::string("src/exactpixels/").size());
            const auto slash = rest.find('/');
            return slash == std::string::npos || used.count(rest.substr(0, slash)) > 0;
        }
        return true;
    });
    std::sort(files.begin(), files.end());
    files.erase(std::unique(files.begin(), files.end()), files.end());
    return files;
}

/// Chapter text without its worked solutions: every `::: solution` fenced div, with
/// whatever it nests, is dropped, so that no kit carries the teacher's edition.
std::string without_solutions(const std::string& text) {
    std::vector<std::string> kept;
    int depth = 0; // fenced divs open inside a solution, the solution's own included
    for (const auto& line : split_lines(text)) {
        const std::string_view t = trim(line);
        const bool fence = starts_with(t, ":::");
        const auto colons = t.find_first_not_of(':');
        const std::string_view rest = colons == std::string_view::npos
                                          ? std::string_view{}
                                          : trim(t.substr(colons));
        if (depth > 0) {
            if (fence) {
                depth += rest.empty() ? -1 : 1;
            }
            continue;
        }
        if (fence && (starts_with(rest, "solution") || starts_with(rest, "{.solution"))) {
            depth = 1;
            continue;
        }
        kept.push_back(line);
    }
    return join_lines(kept);
}

/// Chapter text as the course edition has it (book/AUTHORING.md, "Exercise regions"):
/// a `::: not-in-course` fenced div, with whatever it nests, and a `[...]{.not-in-course}`
/// span are dropped; a `::: course-only` div and a `[...]{.course-only}` span are kept
/// without their markup. A kit goes to the students of a course, so its chapter text and
/// its README say no more than the course edition does.
std::string course_text(const std::string& text) {
    // Divs, line by line: a stack of the fenced divs open, each dropped, unwrapped or kept.
    enum class Div { keep, drop, unwrap };
    std::vector<Div> open;
    std::vector<std::string> kept;
    for (const auto& line : split_lines(text)) {
        const std::string_view t = trim(line);
        const auto colons = t.find_first_not_of(':');
        const bool fence = starts_with(t, ":::");
        const std::string_view rest =
            colons == std::string_view::npos ? std::string_view{} : trim(t.substr(colons));
        const bool dropping = std::find(open.begin(), open.end(), Div::drop) != open.end();
        if (fence && rest.empty() && !open.empty()) {
            const Div closed = open.back();
            open.pop_back();
            if (closed == Div::keep && !dropping) {
                kept.push_back(line);
            }
            continue;
        }
        if (fence && !rest.empty()) {
            const Div div = rest.find("not-in-course") != std::string_view::npos ? Div::drop
                            : rest.find("course-only") != std::string_view::npos
                                ? Div::unwrap
                                : Div::keep;
            open.push_back(div);
            if (div == Div::keep && !dropping) {
                kept.push_back(line);
            }
            continue;
        }
        if (!dropping) {
            kept.push_back(line);
        }
    }
    std::string out = join_lines(kept);
    // Spans, over the whole text (a span may run over lines): the '[' that opens each is
    // found by counting brackets back from its "]{.class}".
    for (const auto& [marker, keep] : {std::pair<std::string, bool>{"]{.not-in-course}", false},
                                       std::pair<std::string, bool>{"]{.course-only}", true}}) {
        for (auto at = out.find(marker); at != std::string::npos; at = out.find(marker)) {
            int depth = 0;
            std::size_t open_at = std::string::npos;
            for (std::size_t i = at; i-- > 0;) {
                if (out[i] == ']') {
                    ++depth;
                } else if (out[i] == '[' && depth-- == 0) {
                    open_at = i;
                    break;
                }
            }
            if (open_at == std::string::npos) {
                throw KitError("a '" + marker.substr(1) + "' span has no opening '['");
            }
            const std::string inner = out.substr(open_at + 1, at - open_at - 1);
            out = out.substr(0, open_at) + (keep ? inner : std::string{}) +
                  out.substr(at + marker.size());
        }
    }
    return out;
}

/// The attributes of a `[]{.exercise kind=K marks=N region=R}` tag that starts at `at`.
std::map<std::string, std::string> tag_attributes(const std::string& text, std::size_t at,
                                                  std::size_t* end) {
    std::map<std::string, std::string> attributes;
    const auto close = text.find('}', at);
    *end = close == std::string::npos ? text.size() : close + 1;
    std::istringstream words(text.substr(at, *end - at - 1));
    for (std::string word; words >> word;) {
        const auto equals = word.find('=');
        if (equals != std::string::npos) {
            std::string value = word.substr(equals + 1);
            value.erase(std::remove(value.begin(), value.end(), '"'), value.end());
            attributes[word.substr(0, equals)] = value;
        }
    }
    return attributes;
}

/// "[implement, 2 marks]" for a tag's attributes.
std::string tag_text(const std::map<std::string, std::string>& attributes) {
    const auto kind = attributes.find("kind");
    const auto marks = attributes.find("marks");
    if (kind == attributes.end() || marks == attributes.end()) {
        return "";
    }
    return "[" + kind->second + ", " + marks->second +
           (marks->second == "1" ? " mark]" : " marks]");
}

const std::string exercise_tag = "[]{.exercise";

/// The attributes of every exercise tag of a chapter that names a region, by region,
/// with the line of the tag (for messages).
struct RegionTag {
    std::map<std::string, std::string> attributes;
    std::size_t line = 0;
};
std::map<std::string, RegionTag> region_tag_attributes(const fs::path& chapter_md) {
    std::map<std::string, RegionTag> tags;
    if (!fs::exists(chapter_md)) {
        return tags;
    }
    const std::string text = read_text(chapter_md);
    for (auto at = text.find(exercise_tag); at != std::string::npos;
         at = text.find(exercise_tag, at + 1)) {
        std::size_t end = 0;
        const auto attributes = tag_attributes(text, at + exercise_tag.size(), &end);
        const auto region = attributes.find("region");
        if (region != attributes.end()) {
            tags[region->second] = {attributes, line_of(text, at)};
        }
    }
    return tags;
}

/// The kind and difficulty of each exercise region the chapter's exercise tags name.
std::map<std::string, std::string> region_tags(const fs::path& chapter_md) {
    std::map<std::string, std::string> tags;
    for (const auto& [region, tag] : region_tag_attributes(chapter_md)) {
        tags[region] = tag_text(tag.attributes);
    }
    return tags;
}

/// The text of `chapter.md` between `## Exercises` and the next `## ` heading, without
/// solutions, with the book-only span attributes reduced to plain text and each
/// exercise's tag to "**[kind, N marks]**".
std::string book_exercises(const fs::path& chapter_md) {
    if (!fs::exists(chapter_md)) {
        return "";
    }
    std::vector<std::string> kept;
    bool inside = false;
    for (const auto& line :
         split_lines(without_solutions(course_text(read_text(chapter_md))))) {
        if (starts_with(line, "## ")) {
            inside = starts_with(line, "## Exercises");
            continue;
        }
        if (inside) {
            std::string text = line;
            const auto tag = text.find(exercise_tag);
            if (tag != std::string::npos) {
                std::size_t end = 0;
                const auto attributes =
                    tag_attributes(text, tag + exercise_tag.size(), &end);
                text = text.substr(0, tag) + "**" + tag_text(attributes) + "**" +
                       text.substr(end);
            }
            // [name]{.test file="..."} -> "name"
            for (auto at = text.find("]{.test"); at != std::string::npos;
                 at = text.find("]{.test")) {
                const auto open = text.rfind('[', at);
                const auto close = text.find('}', at);
                if (open == std::string::npos || close == std::string::npos) {
                    break;
                }
                text = text.substr(0, open) + "\"" +
                       text.substr(open + 1, at - open - 1) + "\"" +
                       text.substr(close + 1);
            }
            kept.push_back(text);
        }
    }
    while (!kept.empty() && trim(kept.back()).empty()) {
        kept.pop_back();
    }
    while (!kept.empty() && trim(kept.front()).empty()) {
        kept.erase(kept.begin());
    }
    return join_lines(kept);
}

std::string chapter_title(const fs::path& chapter_md) {
    if (fs::exists(chapter_md)) {
        for (const auto& line : split_lines(read_text(chapter_md))) {
            if (starts_with(line, "# ")) {
                std::string title(trim(std::string_view(line).substr(2)));
                const auto attributes = title.find(" {");
                return attributes == std::string::npos ? title
                                                       : title.substr(0, attributes);
            }
        }
    }
    return "chapter";
}

/// The kit's template files (NAME.in or NAME in the template folder).
const char* const template_files[] = {"CMakeLists.txt", "README.md", "grade_runner.cpp",
                                      "run_autograder", "setup.sh"};

/// A number the grade runner states as a named constant (`constexpr int NAME = N;`), for
/// the README: the time limits and the rule that derives them.
std::string runner_constant(const fs::path& template_dir, const std::string& constant) {
    const std::string name = "constexpr int " + constant + " = ";
    const std::string text = read_text(template_dir / "grade_runner.cpp");
    const auto at = text.find(name);
    const auto end = at == std::string::npos ? at : text.find(';', at);
    if (end == std::string::npos) {
        throw KitError((template_dir / "grade_runner.cpp").string() + ": no '" + name +
                       "N;'");
    }
    return text.substr(at + name.size(), end - at - name.size());
}

/// The marks of each exercise region the chapter's exercise tags name, with the line of
/// the tag (for messages).
struct TagMarks {
    int marks = 0;
    std::size_t line = 0;
};
std::map<std::string, TagMarks> region_marks(const fs::path& chapter_md) {
    std::map<std::string, TagMarks> marks;
    for (const auto& [region, tag] : region_tag_attributes(chapter_md)) {
        const auto value = tag.attributes.find("marks");
        const std::string m = value == tag.attributes.end() ? "" : value->second;
        const bool whole =
            !m.empty() && m.size() <= 2 && std::all_of(m.begin(), m.end(), [](char c) {
                return std::isdigit(static_cast<unsigned char>(c));
            });
        marks[region] = {whole ? std::stoi(m) : 0, tag.line};
    }
    return marks;
}

/// `kit-points-per-mark: N` from book/metadata.yaml: what one mark of the book is worth
/// in a kit.
int points_per_mark(const fs::path& root) {
    const fs::path file = root / "book/metadata.yaml";
    const std::string key = "kit-points-per-mark:";
    for (const auto& line : split_lines(read_text(file))) {
        if (starts_with(line, key)) {
            const std::string value(trim(std::string_view(line).substr(key.size())));
            if (!value.empty() && value.size() <= 3 &&
                std::all_of(
                    value.begin(), value.end(),
                    [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }) &&
                std::stoi(value) > 0) {
                return std::stoi(value);
            }
            throw KitError(file.string() + ": " + key + " '" + value +
                           "' is not a whole number above 0");
        }
    }
    throw KitError(file.string() + ": no line '" + key + " N'");
}

/// The later chapters' exercises that chapter NN's kit keeps solved, from
/// `kit-keeps-later: "chNN: ID ID; chMM: ID"` in book/metadata.yaml (none without it).
std::set<std::string> kept_later(const fs::path& root, const std::string& number) {
    const fs::path file = root / "book/metadata.yaml";
    const std::string key = "kit-keeps-later:";
    std::set<std::string> kept;
    if (!fs::exists(file)) {
        return kept;
    }
    for (const auto& line : split_lines(read_text(file))) {
        if (!starts_with(line, key)) {
            continue;
        }
        std::string value(trim(std::string_view(line).substr(key.size())));
        value.erase(std::remove(value.begin(), value.end(), '"'), value.end());
        std::istringstream entries(value);
        for (std::string entry; std::getline(entries, entry, ';');) {
            const auto colon = entry.find(':');
            const std::string chapter(trim(std::string_view(entry).substr(0, colon)));
            if (colon == std::string::npos || chapter.size() != 4 ||
                !starts_with(chapter, "ch")) {
                throw KitError(file.string() + ": " + key + " entry '" + entry +
                               "' is not 'chNN: ID ...'");
            }
            std::istringstream ids(entry.substr(colon + 1));
            for (std::string id; ids >> id;) {
                if (!valid_exercise_id(id) || id.substr(0, 4) <= chapter) {
                    throw KitError(file.string() + ": " + key + " '" + id +
                                   "' is no exercise of a chapter after " + chapter);
                }
                if (chapter == "ch" + number) {
                    kept.insert(id);
                }
            }
        }
    }
    return kept;
}

/// Every disagreement between chapter NN's exercise tags and its tests' points (see
/// `check` at the top of the file), one message each.
std::vector<std::string>
points_disagreements(const fs::path& root, const std::string& number,
                     const std::map<std::string, Region>& regions, int per_mark) {
    std::vector<std::string> problems;
    const std::string chapter = "ch" + number;
    const auto folder = chapter_folder(root, number);
    const fs::path chapter_md = folder ? *folder / "chapter.md" : fs::path{};
    const auto tags =
        folder ? region_marks(root / chapter_md) : std::map<std::string, TagMarks>{};
    std::map<std::string, int> points;
    for (const auto& entry : fs::directory_iterator(root / "tests")) {
        const std::string name = entry.path().filename().string();
        if (!starts_with(name, chapter + "_") || !is_code_file(entry.path())) {
            continue;
        }
        for (const auto& test :
             test_declarations(root, fs::relative(entry.path(), root))) {
            if (test.exercise.empty() && test.points > 0 && !test.skipped) {
                problems.push_back(where(test.file, test.line) + ": test \"" + test.name +
                                   "\" declares " + std::to_string(test.points) +
                                   " points but names no exercise: points belong to an "
                                   "exercise of the book");
            } else if (!test.skipped && !test.exercise.empty()) {
                points[test.exercise] += test.points;
            }
        }
    }
    for (const auto& [id, region] : regions) {
        if (region.chapter() != chapter) {
            continue;
        }
        const auto tag = tags.find(id);
        if (tag == tags.end()) {
            problems.push_back(where(region.file, region.line) + ": exercise " + id +
                               " has no tag []{.exercise ... region=" + id + "} in " +
                               (folder ? chapter_md.generic_string()
                                       : "a chapter folder of chapter " + number));
            continue;
        }
        const int want = per_mark * tag->second.marks;
        if (points[id] != want) {
            problems.push_back(
                where(chapter_md, tag->second.line) + ": exercise " + id + " is " +
                std::to_string(tag->second.marks) + " mark" +
                (tag->second.marks == 1 ? "" : "s") + " in the book, so " +
                std::to_string(want) + " points in the kit (" + std::to_string(per_mark) +
                " a mark, book/metadata.yaml), but the tests of " + chapter +
                " that name it declare " + std::to_string(points[id]));
        }
    }
    for (const auto& [id, tag] : tags) {
        const auto region = regions.find(id);
        if (region == regions.end() || region->second.chapter() != chapter) {
            problems.push_back(where(chapter_md, tag.line) + ": the tag names region " +
                               id + ", which is no exercise region of chapter " + number);
        }
    }
    return problems;
}

struct Options {
    std::string command;
    fs::path source, template_dir, out, kit, file, time_limits;
    std::string chapter, version = "0.0.0";
    std::string later = "restore"; ///< restore: "stub" leaves the LATER stubs as they are
    std::string commit = "unknown"; ///< of the source tree, stamped on the kit
};

/// The kit's manifest: the files make-kit wrote, one per line after a comment line.
const std::string kit_stamp = ".exactpixels-kit";

/// Makes folder `out` hold exactly `files` (relative path -> content). Only files whose
/// content changes are written, so a build of an earlier kit in the same place rebuilds
/// only what changed; only files an earlier make-kit wrote (listed in its manifest) are
/// ever deleted, and a non-empty folder without a manifest is refused.
void sync_folder(const fs::path& out, const std::map<fs::path, std::string>& files) {
    if (fs::exists(out) && !fs::is_empty(out)) {
        if (!fs::exists(out / kit_stamp)) {
            throw KitError(out.string() + " exists and is not a kit made by make-kit; "
                                          "refusing to write into it");
        }
        const auto old = split_lines(read_text(out / kit_stamp));
        for (std::size_t i = 1; i < old.size(); ++i) {
            const fs::path rel = old[i];
            if (!rel.empty() && files.count(rel) == 0 && rel.is_relative() &&
                !starts_with(rel.generic_string(), "..")) {
                fs::remove(out / rel);
                // Remove the folders this leaves empty, up to the kit's root.
                for (fs::path dir = (out / rel).parent_path();
                     dir != out && fs::exists(dir) && fs::is_empty(dir);
                     dir = dir.parent_path()) {
                    fs::remove(dir);
                }
            }
        }
    }
    std::string manifest = "# Files written by make-kit (safe to delete the folder).\n";
    for (const auto& [rel, text] : files) {
        const fs::path path = out / rel;
        if (!fs::exists(path) || read_text(path) != text) {
            write_text(path, text);
        }
        manifest += rel.generic_string() + "\n";
    }
    write_text(out / kit_stamp, manifest);
}

void make_kit(const Options& options) {
    const fs::path root = fs::canonical(options.source);
    const std::string number = chapter_number(options.chapter);
    const std::string chapter = "ch" + number;
    const auto regions = all_regions(root);

    // The tests of chapter NN and what they declare.
    std::vector<TestDecl> tests;
    const auto files = kit_files(root, number);
    for (const auto& rel : files) {
        if (rel.parent_path() == "tests" && is_code_file(rel)) {
            const auto found = test_declarations(root, rel);
            tests.insert(tests.end(), found.begin(), found.end());
        }
    }
    std::map<std::string, int> points_for;
    std::map<std::string, std::vector<std::string>> tests_for;
    for (const auto& test : tests) {
        if (test.exercise.empty()) {
            continue;
        }
        if (regions.count(test.exercise) == 0) {
            throw KitError(where(test.file, test.line) + ": test \"" + test.name +
                           "\" names exercise " + test.exercise +
                           ", but no region '//> exercise " + test.exercise +
                           ": ...' exists");
        }
        if (test.points <= 0) {
            throw KitError(where(test.file, test.line) + ": test \"" + test.name +
                           "\" checks exercise " + test.exercise +
                           " but declares no points");
        }
        points_for[test.exercise] += test.points;
        tests_for[test.exercise].push_back(test.name);
    }
    for (const auto& [id, region] : regions) {
        if (region.chapter() == chapter && points_for.count(id) == 0) {
            throw KitError(where(region.file, region.line) + ": exercise " + id +
                           " is checked by no test of chapter " + number +
                           " (add doctest::description(\"points: N; exercise: " + id +
                           "\") to one)");
        }
    }

    // Every file of the kit, by relative path.
    const auto keep_later = kept_later(root, number);
    for (const auto& id : keep_later) {
        if (regions.count(id) == 0) {
            throw KitError("book/metadata.yaml: kit-keeps-later names " + id +
                           ", which is no exercise region");
        }
    }
    std::map<fs::path, std::string> kit;
    std::vector<Region> stubbed;
    for (const auto& rel : files) {
        if (rel == "src/CMakeLists.txt") {
            // The book's own, minus the line that adds the kit maker (not in the kit).
            std::string text;
            for (const auto& line : split_lines(read_text(root / rel))) {
                if (trim(line) != "add_subdirectory(kits)") {
                    text += line + "\n";
                }
            }
            kit[rel] = text;
            continue;
        }
        if (!is_code_file(rel)) {
            const std::string text = read_text(root / rel);
            kit[rel] = rel.filename() == "chapter.md"
                           ? without_solutions(course_text(text))
                           : text;
            continue;
        }
        auto processed = process_file(rel, read_text(root / rel), chapter, keep_later);
        kit[rel] = join_lines(processed.lines);
        for (auto& region : processed.regions) {
            if (region.chapter() == chapter) {
                stubbed.push_back(std::move(region));
            }
        }
    }
    // A chapter-NN region outside the kit's files could not be stubbed: refuse.
    for (const auto& [id, region] : regions) {
        // The lambda captures a copy: Clang 14 cannot capture a structured binding.
        const bool in_kit =
            std::any_of(stubbed.begin(), stubbed.end(),
                        [&id = id](const Region& r) { return r.id == id; });
        if (region.chapter() == chapter && !in_kit) {
            throw KitError(where(region.file, region.line) + ": exercise " + id +
                           " lies in a file the kit does not contain");
        }
    }

    // Template files.
    const auto folder = chapter_folder(root, number);
    const fs::path chapter_md = folder ? root / *folder / "chapter.md" : fs::path{};
    // exercises.txt, "ID KIND MARKS" per tagged exercise, for the grade's summary lines.
    const auto tags = region_tags(chapter_md);
    std::string exercise_list;
    for (const auto& region : stubbed) {
        const auto tag = tags.find(region.id);
        if (tag != tags.end()) {
            // "[implement, 2 marks]" -> "implement 2"
            const auto comma = tag->second.find(", ");
            exercise_list += region.id + " " + tag->second.substr(1, comma - 1) + " " +
                             tag->second.substr(comma + 2, 1) + "\n";
        }
    }
    kit["exercises.txt"] = exercise_list;
    // The time limits measured on the solution (grade-runner --measure), when given.
    if (!options.time_limits.empty()) {
        kit["time_limits.txt"] = read_text(options.time_limits);
    }
    std::string table;
    if (stubbed.empty()) {
        table = "This chapter has no implementation exercises yet: the kit builds the "
                "chapter's code, example and tests as they are in the book.\n";
    } else {
        table = "| exercise | where | points | kind, difficulty | hint |\n"
                "|---|---|---|---|---|\n";
        for (const auto& region : stubbed) {
            const auto tag = tags.find(region.id);
            table += "| `" + region.id + "` | `" + where(region.file, region.kit_line) +
                     "` | " + std::to_string(points_for[region.id]) + " | " +
                     (tag == tags.end() ? std::string("-") : tag->second) + " | " +
                     replace_all(region.hint, "|", "\\|") + " |\n";
        }
        table += "\nThe tests that check them (each passes only when the exercise is "
                 "solved):\n\n";
        for (const auto& region : stubbed) {
            for (const auto& name : tests_for[region.id]) {
                table += "- `" + region.id + "`: \"" + name + "\"\n";
            }
        }
    }
    int total = 0;
    for (const auto& test : tests) {
        total += test.skipped ? 0 : test.points;
    }
    std::string book = book_exercises(chapter_md);
    if (book.empty()) {
        book = "(The chapter text has no exercise section yet.)\n";
    }
    const bool has_example = folder && fs::exists(root / *folder / "example.cpp");
    // The packages: the book's base list, plus toml++ and tinyobjloader if the kit has
    // the scene layer (the only one that reads TOML scenes and OBJ models). Debian's
    // names (Ubuntu's and WSL's too), and Homebrew's formulae for macOS (checked against
    // homebrew-core: it has no formula for stb or tinyobjloader).
    std::string packages = "cmake g++ make pkg-config doctest-dev libglm-dev libstb-dev "
                           "libpng-dev libfmt-dev libcli11-dev libboost-dev";
    std::string brew_packages = "cmake pkgconf doctest glm libpng fmt cli11 boost";
    const bool scene = std::any_of(kit.begin(), kit.end(), [](const auto& file) {
        return starts_with(file.first.generic_string(), "src/exactpixels/scene/");
    });
    if (scene) {
        packages += " libtomlplusplus-dev libtinyobjloader-dev";
        brew_packages += " tomlplusplus";
    }
    const std::string brew_missing =
        scene ? "Homebrew has no formula for two of them. For stb, put the single header "
                "`stb_image_write.h` (from the stb project) into a folder and configure "
                "with "
                "`-DSTB_INCLUDE_DIR=that/folder`. For tinyobjloader, build and install "
                "release 2.0 from its source with CMake and "
                "`-DTINYOBJLOADER_USE_DOUBLE=ON` "
                "(the kit links `tinyobjloader::tinyobjloader_double`)."
              : "Homebrew has no formula for stb: put the single header "
                "`stb_image_write.h` (from the stb project) into a folder and configure "
                "with "
                "`-DSTB_INCLUDE_DIR=that/folder`.";
    const std::map<std::string, std::string> values = {
        {"@TIME_LIMIT@",
         runner_constant(options.template_dir, "test_time_limit_seconds")},
        {"@LIMIT_MULTIPLE@", runner_constant(options.template_dir, "limit_multiple")},
        {"@LIMIT_FLOOR@", runner_constant(options.template_dir, "limit_floor_seconds")},
        {"@BUDGET_MULTIPLE@", runner_constant(options.template_dir, "budget_multiple")},
        {"@BUDGET_FLOOR@", runner_constant(options.template_dir, "budget_floor_seconds")},
        {"@DEFAULT_BUDGET@",
         runner_constant(options.template_dir, "default_budget_seconds")},
        {"@PACKAGES@", packages},
        {"@BREW_PACKAGES@", brew_packages},
        {"@BREW_MISSING@", brew_missing},
        {"@CHAPTER@", number},
        {"@TITLE@", chapter_title(chapter_md)},
        {"@VERSION@", options.version},
        {"@COMMIT@", options.commit},
        {"@EXERCISE_TABLE@", table},
        {"@BOOK_EXERCISES@", book},
        {"@TOTAL_POINTS@", std::to_string(total)},
        {"@EXAMPLE_NOTE@", has_example ? "mkdir -p out && build/bin/ch" + number +
                                             "-example out  # the example's figures"
                                       : "# (this chapter has no example program)"},
    };
    // NAME.in gets its placeholders filled; a template file without ".in" is copied.
    for (const std::string name : template_files) {
        const fs::path plain = options.template_dir / name;
        if (fs::exists(plain)) {
            kit[name] = read_text(plain);
            continue;
        }
        std::string text = read_text(options.template_dir / (name + ".in"));
        for (const auto& [key, value] : values) {
            text = replace_all(text, key, value);
        }
        kit[name] = text;
    }
    const fs::path out = fs::absolute(options.out);
    sync_folder(out, kit);
    for (const char* script : {"run_autograder", "setup.sh"}) {
        fs::permissions(out / script,
                        fs::perms::owner_exec | fs::perms::group_exec |
                            fs::perms::others_exec,
                        fs::perm_options::add);
    }

    std::cout << "make-kit: wrote " << out.string() << " (chapter " << number << ", "
              << stubbed.size() << " exercise" << (stubbed.size() == 1 ? "" : "s") << ", "
              << tests.size() << " test cases, " << total << " points)\n";
    for (const auto& region : stubbed) {
        std::cout << "  " << region.id << "  " << where(region.file, region.kit_line)
                  << "  " << points_for[region.id] << " points\n";
    }
}

/// Puts each region's solution back between the kit's EXERCISE comments, and each later
/// chapter's region or gives-away block back between its LATER EXERCISE comments (the
/// n-th such block of an exercise in a file is the n-th block of that exercise in the
/// source's file); rewrites only the files that change, so an existing build recompiles
/// only those.
void restore_kit(const Options& options) {
    const fs::path root = fs::canonical(options.source);
    const auto regions = all_regions(root);
    const fs::path kit = options.kit;
    if (!fs::exists(kit / kit_stamp)) {
        throw KitError(kit.string() + " is not a kit made by make-kit");
    }
    const bool keep_later_stubs = options.later == "stub";
    int restored = 0, later = 0;
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(kit)) {
        const fs::path rel = fs::relative(entry.path(), kit);
        if (entry.is_regular_file() && is_code_file(rel) &&
            (starts_with(rel.generic_string(), "src/") ||
             starts_with(rel.generic_string(), "chapters/") ||
             starts_with(rel.generic_string(), "tests/"))) {
            files.push_back(rel);
        }
    }
    std::sort(files.begin(), files.end());
    for (const auto& rel : files) {
        const std::string text = read_text(kit / rel);
        const auto lines = split_lines(text);
        std::vector<std::string> out;
        std::optional<std::vector<Region>> source_blocks; // read when first needed
        std::map<std::string, std::size_t> later_seen;    // id -> LATER blocks so far
        for (std::size_t i = 0; i < lines.size(); ++i) {
            out.push_back(lines[i]);
            const std::string_view body = trim(lines[i]);
            const bool is_later = starts_with(body, later_begin);
            if (!(starts_with(body, kit_begin) || (is_later && !keep_later_stubs)) ||
                body.find(':') == std::string_view::npos) {
                continue;
            }
            const std::string_view spec =
                body.substr((is_later ? later_begin : kit_begin).size());
            const std::string id(trim(spec.substr(0, spec.find(':'))));
            if (!valid_exercise_id(id)) {
                continue; // a comment that merely starts with the same words
            }
            const std::string closing = (is_later ? later_end : kit_end) + id;
            std::size_t end = i + 1;
            while (end < lines.size() && trim(lines[end]) != closing) {
                ++end;
            }
            if (end == lines.size()) {
                throw KitError(where(rel, i + 1) + ": no '" + closing + "' after it");
            }
            const std::vector<std::string>* solution = nullptr;
            if (!is_later) {
                const auto region = regions.find(id);
                if (region == regions.end()) {
                    throw KitError(where(rel, i + 1) +
                                   ": the source tree has no exercise " + id);
                }
                solution = &region->second.solution;
                ++restored;
            } else {
                if (!source_blocks) {
                    source_blocks = fs::exists(root / rel)
                                        ? process_file(rel, read_text(root / rel), "").blocks
                                        : std::vector<Region>{};
                }
                std::size_t n = later_seen[id]++;
                for (const auto& block : *source_blocks) {
                    if (block.id == id && n-- == 0) {
                        solution = &block.solution;
                        break;
                    }
                }
                if (!solution) {
                    throw KitError(where(rel, i + 1) + ": the source's " +
                                   rel.generic_string() + " has no such block of " + id);
                }
                ++later;
            }
            out.insert(out.end(), solution->begin(), solution->end());
            out.push_back(lines[end]);
            i = end;
        }
        const std::string restored_text = join_lines(out);
        if (restored_text != text) {
            write_text(kit / rel, restored_text);
        }
    }
    std::cout << "make-kit: restored " << restored << " exercise solution"
              << (restored == 1 ? "" : "s") << " in " << kit.string();
    if (later > 0) {
        std::cout << " (and " << later << " of later chapters)";
    }
    std::cout << "\n";
}

void print_stubbed(const Options& options) {
    const fs::path root = fs::canonical(options.source);
    const fs::path file = fs::canonical(options.file);
    std::cout << join_lines(
        process_file(fs::relative(file, root), read_text(file), "*").lines);
}

void list_regions(const Options& options) {
    const fs::path root = fs::canonical(options.source);
    const auto regions = all_regions(root);
    std::map<std::string, std::vector<TestDecl>> tests_for;
    for (const auto& rel : code_files(root)) {
        if (rel.parent_path() == "tests") {
            for (const auto& test : test_declarations(root, rel)) {
                tests_for[test.exercise].push_back(test);
            }
        }
    }
    for (const auto& [id, region] : regions) {
        std::cout << id << " " << where(region.file, region.line) << " " << region.hint
                  << "\n";
        for (const auto& test : tests_for[id]) {
            std::cout << "  " << test.points << " points: \"" << test.name << "\" ("
                      << where(test.file, test.line) << ")\n";
        }
    }
}

/// `check`: every chapter's marks and points agree (or chapter --chapter's).
int check_points(const Options& options) {
    const fs::path root = fs::canonical(options.source);
    const auto regions = all_regions(root);
    const int per_mark = points_per_mark(root);
    std::set<std::string> numbers;
    if (!options.chapter.empty()) {
        numbers.insert(chapter_number(options.chapter));
    } else {
        for (const auto& entry : fs::directory_iterator(root / "chapters")) {
            const std::string name = entry.path().filename().string();
            if (entry.is_directory() && name.size() > 3 && name[2] == '-' &&
                std::isdigit(static_cast<unsigned char>(name[0])) &&
                std::isdigit(static_cast<unsigned char>(name[1]))) {
                numbers.insert(name.substr(0, 2));
            }
        }
        for (const auto& [id, region] : regions) {
            numbers.insert(id.substr(2, 2));
        }
    }
    std::size_t count = 0;
    for (const auto& number : numbers) {
        for (const auto& problem :
             points_disagreements(root, number, regions, per_mark)) {
            std::cerr << problem << "\n";
            ++count;
        }
    }
    if (count > 0) {
        std::cerr << "make-kit: the book's marks and the kits' points disagree in "
                  << count << " place" << (count == 1 ? "" : "s") << "\n";
        return 1;
    }
    std::cout << "make-kit: marks and points agree in " << numbers.size() << " chapter"
              << (numbers.size() == 1 ? "" : "s") << " (" << per_mark
              << " points a mark)\n";
    return 0;
}

Options parse(int argc, char** argv) {
    if (argc < 2) {
        throw KitError(
            "usage: make-kit kit|restore|list|check|stub --source ROOT [options]; see the "
            "top of src/kits/make_kit.cpp");
    }
    Options options;
    options.command = argv[1];
    for (int i = 2; i < argc; ++i) {
        const std::string flag = argv[i];
        if (i + 1 >= argc) {
            throw KitError(flag + " wants a value");
        }
        const std::string value = argv[++i];
        if (flag == "--source") {
            options.source = value;
        } else if (flag == "--template") {
            options.template_dir = value;
        } else if (flag == "--chapter") {
            options.chapter = value;
        } else if (flag == "--out") {
            options.out = value;
        } else if (flag == "--kit") {
            options.kit = value;
        } else if (flag == "--version") {
            options.version = value;
        } else if (flag == "--commit") {
            options.commit = value;
        } else if (flag == "--file") {
            options.file = value;
        } else if (flag == "--time-limits") {
            options.time_limits = value;
        } else if (flag == "--later") {
            if (value != "restore" && value != "stub") {
                throw KitError("--later wants restore or stub, not '" + value + "'");
            }
            options.later = value;
        } else {
            throw KitError("unknown option " + flag);
        }
    }
    if (options.source.empty()) {
        throw KitError("--source ROOT is required");
    }
    if (options.command == "kit" && (options.template_dir.empty() ||
                                     options.chapter.empty() || options.out.empty())) {
        throw KitError("make-kit kit wants --template, --chapter and --out");
    }
    // Both go into the kit's CMakeLists.txt and a C++ string: plain words only.
    for (const std::string* stamp : {&options.version, &options.commit}) {
        if (stamp->empty() || !std::all_of(stamp->begin(), stamp->end(), [](char c) {
                return std::isalnum(static_cast<unsigned char>(c)) || c == '.' ||
                       c == '+' || c == '-';
            })) {
            throw KitError("--version and --commit want letters, digits, '.', '+' and "
                           "'-' only, not '" +
                           *stamp + "'");
        }
    }
    if (options.command == "restore" && options.kit.empty()) {
        throw KitError("make-kit restore wants --kit");
    }
    if (options.command == "stub" && options.file.empty()) {
        throw KitError("make-kit stub wants --file");
    }
    return options;
}

} // namespace

int main(int argc, char** argv) {
    try {
        const Options options = parse(argc, argv);
        if (options.command == "kit") {
            make_kit(options);
        } else if (options.command == "restore") {
            restore_kit(options);
        } else if (options.command == "list") {
            list_regions(options);
        } else if (options.command == "check") {
            return check_points(options);
        } else if (options.command == "stub") {
            print_stubbed(options);
        } else {
            throw KitError("unknown command '" + options.command +
                           "' (kit, restore, list, check, stub)");
        }
    } catch (const std::exception& error) {
        std::cerr << "make-kit: " << error.what() << "\n";
        return 1;
    }
    return 0;
}
