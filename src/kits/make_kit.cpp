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
// runs them, keep their solution. Every marker line (`//>`, `//<`, `//|`) is removed. The
// template folder supplies the kit's CMakeLists.txt, README.md, its grader
// (grade_runner.cpp) and Gradescope's two scripts, setup.sh and run_autograder (NAME.in
// with @CHAPTER@-style placeholders, or NAME copied as it is). --time-limits FILE
// (written by grade-runner --measure from the solution) becomes the kit's
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
#include "kit.hpp"

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

using namespace kits;

namespace {

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
                    source_blocks =
                        fs::exists(root / rel)
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
        throw KitError("usage: make-kit kit|restore|list|check|stub --source ROOT "
                       "[options]; see the "
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
