// kit_tree.cpp: which files of the source tree go into chapter NN's kit.
#include "kit.hpp"

#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/base/error.hpp"

namespace kits {

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

namespace {

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

} // namespace

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
    // A fixture the chapter's code names by path ("tests/fixtures/NAME") comes along, and
    // a fixture folder those fixtures name beside them ("../NAME/", as an MTL file names
    // its textures); so does another chapter's folder the code names by path (chapter
    // 9's tests draw chapter 7's scenes).
    const auto names_folder = [](const std::string& text, const std::string& path) {
        return text.find(path + "/") != std::string::npos ||
               text.find(path + "\"") != std::string::npos;
    };
    if (fs::is_directory(root / "tests/fixtures")) {
        std::string fixture_text;
        for (int pass = 0; pass < 2; ++pass) {
            for (const auto& entry : fs::directory_iterator(root / "tests/fixtures")) {
                const std::string name = entry.path().filename().string();
                const fs::path rel = fs::relative(entry.path(), root);
                const bool named = pass == 0
                                       ? names_folder(code, "tests/fixtures/" + name)
                                       : fixture_text.find("../" + name + "/") !=
                                             std::string::npos;
                if (!named) {
                    continue;
                }
                const std::size_t before = files.size();
                add_tree(rel, everything);
                for (std::size_t i = before; i < files.size(); ++i) {
                    const std::string ext = files[i].extension().string();
                    if (ext == ".mtl" || ext == ".obj" || ext == ".toml") {
                        fixture_text += read_text(root / files[i]);
                    }
                }
            }
        }
    }
    if (fs::is_directory(root / "chapters")) {
        for (const auto& entry : fs::directory_iterator(root / "chapters")) {
            const std::string name = entry.path().filename().string();
            if (entry.is_directory() && names_folder(code, "chapters/" + name)) {
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

} // namespace kits
