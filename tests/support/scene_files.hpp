// scene_files.hpp: the scene files in a folder, in one order on every machine, for the
// tests that go through every shipped (or every bad) scene.
#pragma once

#include <algorithm>
#include <filesystem>
#include <vector>

namespace exactpixels::testing {

/// Every `.toml` file directly in `folder`, sorted by path (a directory's own order
/// differs between file systems).
inline std::vector<std::filesystem::path> scene_files(const std::filesystem::path& folder) {
    std::vector<std::filesystem::path> files;
    for (const std::filesystem::directory_entry& entry :
         std::filesystem::directory_iterator(folder)) {
        if (entry.path().extension() == ".toml") {
            files.push_back(entry.path());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

} // namespace exactpixels::testing
