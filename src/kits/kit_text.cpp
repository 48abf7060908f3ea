// kit_text.cpp: make-kit's text helpers: files read and written whole, lines, trimming.
#include "kit.hpp"

#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/base/error.hpp"

namespace kits {

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

} // namespace kits
