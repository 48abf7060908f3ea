#include "support/figure_file.hpp"

#include "exactpixels/base/atomic_file.hpp"

namespace exactpixels {

void write_figure_file(const std::filesystem::path& path, std::string_view text) {
    write_file_atomically(path, "figure data", text);
}

} // namespace exactpixels
