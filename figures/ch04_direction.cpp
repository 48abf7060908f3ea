// Figure ch04_direction.svg: the texture direction bug. The book's F, 1:1, on a quad
// offset by half a pixel (so every sample is a tie) with u running right to left.
// Left: rule 1 everywhere; right: the rule chosen from du/dx < 0. Pixels showing a
// texel that is shown twice are outlined; the column of the F that never shows is named.
// Usage: fig_ch04_direction FIGURE_DIR
#include "exactpixels/base/error.hpp"
#include "exactpixels/texture/rounding.hpp"
#include "exactpixels/texture/texture.hpp"
#include "exactpixels/texture/texture_mapper.hpp"
#include "support/svg.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

using namespace exactpixels;

namespace {

constexpr int panel_gap = 5; // empty pixels between the panels
constexpr int top = 3;       // rows above the quads, for the titles

std::string hex(Rgba8 c) {
    return fmt::format("#{:02x}{:02x}{:02x}", c.r, c.g, c.b);
}

/// The texel map of the mirrored quad with its corner at (x0 + 0.5, top + 0.5).
TexelMap mirrored_quad(const Texture& t, int frame_width, int frame_height, int x0,
                       bool choose) {
    const double l = x0 + 0.5, r = l + t.width(), y0 = top + 0.5, y1 = y0 + t.height();
    const double u_l = t.width(), u_r = 0.0, v_t = 0.0, v_b = t.height();
    const TexturedVertex tl{{l, y0}, 1.0, {u_l, v_t}}, tr{{r, y0}, 1.0, {u_r, v_t}};
    const TexturedVertex br{{r, y1}, 1.0, {u_r, v_b}}, bl{{l, y1}, 1.0, {u_l, v_b}};
    TexelMap map(frame_width, frame_height);
    for (const std::array<TexturedVertex, 3>& tri :
         {std::array{tl, tr, br}, std::array{tl, br, bl}}) {
        MapperSettings s{.mapper = {MapperKind::exact},
                         .precision = Precision::fixed,
                         .wrap = Wrap::clamp};
        s.rounding = choose ? choose_rounding(tri, s.mapper.kind) : TexelRounding{};
        map_textured_triangle(map, tri, s);
    }
    return map;
}

/// Draws a panel's pixels and outlines those whose texel column shows twice; returns
/// the texel columns that never show.
std::vector<int> draw_panel(SvgDiagram& d, const Texture& t, const TexelMap& map) {
    std::vector<int> shown(static_cast<std::size_t>(t.width()), 0);
    for (int y = 0; y < map.height; ++y) {
        for (int x = 0; x < map.width; ++x) {
            const std::size_t at =
                std::size_t(y) * std::size_t(map.width) + std::size_t(x);
            if (map.covered[at] && y == top) {
                ++shown[std::size_t(wrap_index(map.i[at], t.width(), Wrap::clamp))];
            }
        }
    }
    for (int y = 0; y < map.height; ++y) {
        for (int x = 0; x < map.width; ++x) {
            const std::size_t at =
                std::size_t(y) * std::size_t(map.width) + std::size_t(x);
            if (!map.covered[at]) {
                continue;
            }
            const int i = wrap_index(map.i[at], t.width(), Wrap::clamp);
            const int j = wrap_index(map.j[at], t.height(), Wrap::clamp);
            d.fill_pixel(x, y, hex(t.texel(i, j)), 0.85);
            if (shown[std::size_t(i)] > 1) {
                d.polygon({{x + 0.1, y + 0.1},
                           {x + 0.9, y + 0.1},
                           {x + 0.9, y + 0.9},
                           {x + 0.1, y + 0.9}},
                          {.stroke = "#ffb000", .width = 3.0});
            }
        }
    }
    std::vector<int> never;
    for (int i = 0; i < t.width(); ++i) {
        if (shown[std::size_t(i)] == 0) {
            never.push_back(i);
        }
    }
    return never;
}

} // namespace

int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    try {
        const Texture f = f_texture(1); // 5 x 7 texels: every column of the F differs
        const int w = 2 * f.width() + panel_gap + 5, h = f.height() + top + 3;
        const int left_x = 1, right_x = 1 + f.width() + panel_gap;
        const TexelMap broken = mirrored_quad(f, w, h, left_x, false);
        const TexelMap fixed = mirrored_quad(f, w, h, right_x, true);

        SvgDiagram d(w, h, 28.0);
        const std::vector<int> never_broken = draw_panel(d, f, broken);
        const std::vector<int> never_fixed = draw_panel(d, f, fixed);
        d.grid();
        for (const int x0 : {left_x, right_x}) {
            const double l = x0 + 0.5, r = l + f.width(), t0 = top + 0.5;
            d.polygon({{l, t0}, {r, t0}, {r, t0 + f.height()}, {l, t0 + f.height()}},
                      {.stroke = "black", .width = 2.0, .dashed = true});
            for (int k = 0; k < f.width(); ++k) { // u at each column's pixel centres
                d.text({x0 + k + 0.5, top - 0.25}, fmt::format("u={}", f.width() - k), 10,
                       SvgAnchor::middle);
            }
        }
        d.text({left_x, 1.2}, "rule 1 everywhere: floor(u)", 14);
        d.text({right_x, 1.2}, "du/dx < 0: rule 2, ceil(u) - 1", 14);
        const auto columns = [](const std::vector<int>& c) {
            return c.empty() ? std::string("none")
                             : fmt::format("{}", fmt::join(c, ", "));
        };
        d.text({left_x, h - 1.2}, "F column never shown: " + columns(never_broken), 13);
        d.text({left_x, h - 0.4}, "outlined: a column shown twice", 13, SvgAnchor::start,
               "#b07000");
        d.text({right_x, h - 1.2}, "F column never shown: " + columns(never_fixed), 13);
        d.write(folder / "ch04_direction.svg");
        std::printf("wrote %s\n", (folder / "ch04_direction.svg").c_str());
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch04_direction: %s\n", error.what());
        return 1;
    }
}
