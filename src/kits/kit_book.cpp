// kit_book.cpp: what make-kit reads from the book: a chapter's text as a kit carries it
// (no worked solutions, the course edition's), its exercise tags and marks, and
// book/metadata.yaml's points per mark and kept later exercises.
#include "kit.hpp"

#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/base/error.hpp"

namespace kits {

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

std::string course_text(const std::string& text) {
    // Divs, line by line: a stack of the fenced divs open, each dropped, unwrapped or
    // kept.
    enum class Div { keep, drop, unwrap };
    std::vector<Div> open;
    std::vector<std::string> kept;
    for (const auto& line : split_lines(text)) {
        const std::string_view t = trim(line);
        const auto colons = t.find_first_not_of(':');
        const bool fence = starts_with(t, ":::");
        const std::string_view rest = colons == std::string_view::npos
                                          ? std::string_view{}
                                          : trim(t.substr(colons));
        const bool dropping =
            std::find(open.begin(), open.end(), Div::drop) != open.end();
        if (fence && rest.empty() && !open.empty()) {
            const Div closed = open.back();
            open.pop_back();
            if (closed == Div::keep && !dropping) {
                kept.push_back(line);
            }
            continue;
        }
        if (fence && !rest.empty()) {
            const Div div =
                rest.find("not-in-course") != std::string_view::npos ? Div::drop
                : rest.find("course-only") != std::string_view::npos ? Div::unwrap
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
    for (const auto& [marker, keep] :
         {std::pair<std::string, bool>{"]{.not-in-course}", false},
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

namespace {

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

} // namespace

std::map<std::string, std::string> region_tags(const fs::path& chapter_md) {
    std::map<std::string, std::string> tags;
    for (const auto& [region, tag] : region_tag_attributes(chapter_md)) {
        tags[region] = tag_text(tag.attributes);
    }
    return tags;
}

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

namespace {

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

} // namespace

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

} // namespace kits
