#include "exactpixels/base/atomic_file.hpp"

#include "exactpixels/base/error.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <system_error>

namespace exactpixels {

void write_atomically(const std::filesystem::path& path, std::string_view kind,
                      const std::function<bool(const std::filesystem::path&)>& write) {
    std::filesystem::path temporary = path;
    temporary += ".partial";
    std::error_code ignored;
    errno = 0;
    if (!write(temporary)) {
        const std::string reason = errno != 0 ? std::strerror(errno) : "write failed";
        std::filesystem::remove(temporary, ignored);
        throw Error(
            fmt::format("{}: cannot write {} file ({})", path.string(), kind, reason));
    }
    std::error_code renamed;
    std::filesystem::rename(temporary, path, renamed);
    if (renamed) {
        std::filesystem::remove(temporary, ignored);
        throw Error(fmt::format("{}: cannot write {} file ({})", path.string(), kind,
                                renamed.message()));
    }
}

} // namespace exactpixels
