#include "exactpixels/base/printable.hpp"

#include <fmt/format.h>

namespace exactpixels {

namespace {

/// The length of the UTF-8 sequence that starts at text[i], or 0 when it is not valid
/// UTF-8 (a stray continuation byte, a lead byte that can only start an overlong or
/// out-of-range sequence, a sequence cut short).
std::size_t utf8_length(std::string_view text, std::size_t i) {
    const auto lead = static_cast<unsigned char>(text[i]);
    const std::size_t length = lead < 0x80                    ? 1
                               : lead >= 0xc2 && lead <= 0xdf ? 2
                               : lead >= 0xe0 && lead <= 0xef ? 3
                               : lead >= 0xf0 && lead <= 0xf4 ? 4
                                                              : 0;
    if (length == 0 || i + length > text.size()) {
        return 0;
    }
    for (std::size_t k = 1; k < length; ++k) {
        if ((static_cast<unsigned char>(text[i + k]) & 0xc0) != 0x80) {
            return 0;
        }
    }
    return length;
}

/// The escape of the one-byte control character `c` (0x00-0x1f, 0x7f).
std::string escape_control(unsigned char c) {
    switch (c) {
    case '\0':
        return "\\0";
    case '\t':
        return "\\t";
    case '\n':
        return "\\n";
    case '\r':
        return "\\r";
    default:
        return fmt::format("\\x{:02x}", c);
    }
}

} // namespace

std::string printable(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    std::size_t i = 0;
    while (i < text.size()) {
        const auto c = static_cast<unsigned char>(text[i]);
        const std::size_t length = utf8_length(text, i);
        if (length == 0) {
            out += fmt::format("\\x{:02x}", c); // not UTF-8: show the byte
            i += 1;
        } else if (length == 1 && (c < 0x20 || c == 0x7f)) {
            out += escape_control(c);
            i += 1;
        } else if (length == 2 && c == 0xc2 &&
                   static_cast<unsigned char>(text[i + 1]) < 0xa0) {
            // U+0080 to U+009F, the C1 controls (0x9b starts an escape sequence too)
            out += fmt::format("\\u{:04x}", static_cast<unsigned char>(text[i + 1]));
            i += 2;
        } else {
            out.append(text, i, length);
            i += length;
        }
    }
    return out;
}

} // namespace exactpixels
