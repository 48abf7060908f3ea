// atomic_file.hpp: writing a file all or nothing.
//
// Usage:
//   write_atomically("out.png", "PNG", [&](const std::filesystem::path& temporary) {
//       return write_the_bytes_to(temporary);  // true when every byte was written
//   });
//
// The content goes to "<path>.partial" beside the target, which is renamed over the
// target only when complete. On failure the temporary file is removed, the target is
// left as it was, and an Error names the path.
#pragma once

#include <filesystem>
#include <functional>
#include <string_view>

namespace exactpixels {

/// Writes `path` through `write`, which fills the temporary file it is given and returns
/// true on success. Throws Error ("PATH: cannot write KIND file (reason)") on failure,
/// leaving neither `path` (if it did not exist) nor the temporary file behind.
void write_atomically(const std::filesystem::path& path, std::string_view kind,
                      const std::function<bool(const std::filesystem::path&)>& write);

} // namespace exactpixels
