// The three editions of the book (book/render.cmake), each in its own folder of the
// build: the page checks (bookcheck_html.cpp, bookcheck_pdf.cpp) run on every one of
// them, the same checks with the edition's folder as their one parameter.
#pragma once

#include <array>
#include <filesystem>

namespace exactpixels::bookcheck {

/// One edition: its build folder's name and whether its pages may carry worked solutions.
struct Edition {
    const char* folder;   ///< under the build folder: "book", "book-course", ...
    bool with_solutions; ///< the teacher's edition only
};

inline constexpr std::array<Edition, 3> editions = {{
    {"book", false},         // the public book
    {"book-course", false},  // the course edition: exercise regions as their stubs
    {"book-teacher", true},  // the teacher's edition: with worked solutions
}};

/// The folder of `edition` in this build.
inline std::filesystem::path edition_folder(const Edition& edition) {
    return std::filesystem::path(EXACTPIXELS_BINARY_DIR) / edition.folder;
}

} // namespace exactpixels::bookcheck
