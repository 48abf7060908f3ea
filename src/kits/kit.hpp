// kit.hpp: the parts of make-kit (make_kit.cpp) shared by its files: text helpers
// (kit_text.cpp), exercise regions and the tests' declared points (kit_regions.cpp), the
// files a chapter's kit takes from the source tree (kit_tree.cpp), and what a kit reads
// from the book's chapter text and metadata (kit_book.cpp). Every function throws
// KitError, naming file and line, on input it cannot use.
#pragma once

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

namespace kits {

namespace fs = std::filesystem;

using exactpixels::testing::DeclaredPoints;
using exactpixels::testing::parse_declared_points;

struct KitError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// The whole file at `path`; KitError naming it when it cannot be read.
std::string read_text(const fs::path& path);

/// Writes `text` as the file at `path` (its folders made first); KitError on failure.
void write_text(const fs::path& path, const std::string& text);

/// The lines of `text`, without their line breaks.
std::vector<std::string> split_lines(const std::string& text);

/// The lines, each followed by a line break.
std::string join_lines(const std::vector<std::string>& lines);

/// `text` without leading and trailing blanks.
std::string_view trim(std::string_view text);

/// Whether `text` begins with `prefix`.
bool starts_with(std::string_view text, std::string_view prefix);

/// `text` with every `from` replaced by `to`.
std::string replace_all(std::string text, const std::string& from, const std::string& to);

/// "FILE:LINE", the start of a message about that line.
std::string where(const fs::path& file, std::size_t line);

/// "chNN-name": the prefix ch, two digits, a dash, then lower-case letters, digits,
/// dashes.
bool valid_exercise_id(std::string_view id);

/// Whether `path` is C++ source or a header, by its extension.
bool is_code_file(const fs::path& path);

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

inline const std::string kit_begin = "// EXERCISE ";

inline const std::string kit_end = "// END EXERCISE ";

// A region or gives-away block of a later chapter's exercise, shipped as its stub: the
// grader never takes it from a submission (it is not an EXERCISE region) and `restore`
// puts its solution back.
inline const std::string later_begin = "// LATER EXERCISE ";

inline const std::string later_end = "// END LATER EXERCISE ";

// A gives-away block as the course edition's API reference shows it.
inline const std::string course_hidden_begin =
    "// NOT IN THE COURSE EDITION (it would give exercise ";
inline const std::string course_hidden_end =
    "// END OF WHAT THE COURSE EDITION LEAVES OUT";

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
                       const std::set<std::string>& keep_later = {});

/// Every code file under src/, chapters/ and tests/ (test fixtures excluded), relative to
/// the root, sorted so that the output never depends on directory order.
std::vector<fs::path> code_files(const fs::path& root);

/// Every exercise region in the tree, by ID (IDs are unique across the tree).
std::map<std::string, Region> all_regions(const fs::path& root);

/// A TEST_CASE with the points and exercise its description declares.
struct TestDecl {
    std::string name;
    fs::path file;
    std::size_t line = 0;
    int points = 0;
    std::string exercise; // empty for none
    bool skipped = false; // doctest::skip: counts in no total
};

/// The line (from 1) of `text` that holds the character at `offset`.
std::size_t line_of(const std::string& text, std::size_t offset);

/// Finds every TEST_CASE* in a test file and reads `doctest::description("points: N;
/// exercise: ID")` among its decorators (between the name and the opening brace).
std::vector<TestDecl> test_declarations(const fs::path& root, const fs::path& rel);

/// "2", "02" or "ch02" -> "02".
std::string chapter_number(std::string text);

/// chapters/NN-slug, if the chapter has a folder.
std::optional<fs::path> chapter_folder(const fs::path& root, const std::string& number);

/// The relative paths of every file the kit of chapter NN takes from the source tree:
/// the chapter's folder, its tests and the test headers they include, the test support
/// files, and of the library only the layers that this code reaches (with the layers
/// beneath them), so that a chapter's kit needs only its own chapters' packages.
std::vector<fs::path> kit_files(const fs::path& root, const std::string& number);

/// Chapter text without its worked solutions: every `::: solution` fenced div, with
/// whatever it nests, is dropped, so that no kit carries the teacher's edition.
std::string without_solutions(const std::string& text);

/// Chapter text as the course edition has it (book/AUTHORING.md, "Exercise regions"):
/// a `::: not-in-course` fenced div, with whatever it nests, and a
/// `[...]{.not-in-course}` span are dropped; a `::: course-only` div and a
/// `[...]{.course-only}` span are kept without their markup. A kit goes to the students
/// of a course, so its chapter text and its README say no more than the course edition
/// does.
std::string course_text(const std::string& text);

/// The kind and difficulty of each exercise region the chapter's exercise tags name.
std::map<std::string, std::string> region_tags(const fs::path& chapter_md);

/// The text of `chapter.md` between `## Exercises` and the next `## ` heading, without
/// solutions, with the book-only span attributes reduced to plain text and each
/// exercise's tag to "**[kind, N marks]**".
std::string book_exercises(const fs::path& chapter_md);

/// The chapter's title (its `# ` heading without attributes), or "chapter".
std::string chapter_title(const fs::path& chapter_md);

/// The kit's template files (NAME.in or NAME in the template folder).
inline const char* const template_files[] = {
    "CMakeLists.txt", "README.md", "grade_runner.cpp", "run_autograder", "setup.sh"};

/// A number the grade runner states as a named constant (`constexpr int NAME = N;`), for
/// the README: the time limits and the rule that derives them.
std::string runner_constant(const fs::path& template_dir, const std::string& constant);

/// `kit-points-per-mark: N` from book/metadata.yaml: what one mark of the book is worth
/// in a kit.
int points_per_mark(const fs::path& root);

/// The later chapters' exercises that chapter NN's kit keeps solved, from
/// `kit-keeps-later: "chNN: ID ID; chMM: ID"` in book/metadata.yaml (none without it).
std::set<std::string> kept_later(const fs::path& root, const std::string& number);

/// Every disagreement between chapter NN's exercise tags and its tests' points (see
/// `check` at the top of the file), one message each.
std::vector<std::string>
points_disagreements(const fs::path& root, const std::string& number,
                     const std::map<std::string, Region>& regions, int per_mark);

} // namespace kits
