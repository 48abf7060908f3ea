// kit_regions.cpp: make-kit's exercise regions (`//> exercise ID` ... `//< exercise ID`)
// and gives-away blocks, read from the source and shown as a kit shows them, and the
// points each test declares for an exercise.
#include "kit.hpp"

#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/base/error.hpp"

namespace kits {

Processed process_file(const fs::path& rel, const std::string& text,
                       const std::string& stub_chapter,
                       const std::set<std::string>& keep_later) {
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
                    throw KitError(where(rel, i + 1) + ": " + kind +
                                   " region inside region " + open->id +
                                   " (opened at line " + std::to_string(open->line) +
                                   ")");
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
                    // Appended in two steps: GCC 12 reports a false -Wrestrict overlap
                    // on " " + std::string(...) once trim is in another file.
                    hint += ' ';
                    hint += trim(std::string_view(lines[++i]).substr(indent.size() + 2));
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
                        indent +
                        (stub_chapter == "*"
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
                    throw KitError(where(rel, open->line) + ": gives-away block of " +
                                   id + " has no stub ('//|' lines that compile)");
                }
                if (stubbing) {
                    result.lines.push_back(indent +
                                           (shown(*open) == Shown::exercise ? kit_end + id
                                            : stub_chapter == "*" ? course_hidden_end
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

std::size_t line_of(const std::string& text, std::size_t offset) {
    return 1 + static_cast<std::size_t>(std::count(
                   text.begin(), text.begin() + static_cast<long>(offset), '\n'));
}

namespace {

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

} // namespace

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

} // namespace kits
