#include "exactpixels/base/test_pattern.hpp"

#include <array>
#include <cassert>
#include <string_view>

namespace exactpixels {

namespace {
constexpr std::array<std::string_view, f_glyph_height> f_glyph = {
    "#####", "#....", "#....", "####.", "#....", "#....", "#....",
};
} // namespace

bool f_glyph_cell(int column, int row) {
    if (column < 0 || row < 0 || column >= f_glyph_width || row >= f_glyph_height) {
        return false;
    }
    return f_glyph[static_cast<std::size_t>(row)][static_cast<std::size_t>(column)] ==
           '#';
}

//> draw-f
Framebuffer draw_f_pattern(int cell) {
    assert(cell >= 1);
    Framebuffer frame(f_glyph_width * cell, f_glyph_height * cell, pattern_blue);
    for (int y = 0; y < frame.height(); ++y) {
        for (int x = 0; x < frame.width(); ++x) {
            if (f_glyph_cell(x / cell, y / cell)) { // which glyph cell holds this pixel
                frame.at(x, y) = pattern_red;
            }
        }
    }
    return frame;
}
//< draw-f

} // namespace exactpixels
