// Figure data for chapter 4's Exercise 5: how often a pixel of a perspective triangle is
// a tie (u or v exactly an integer at its centre), and how often the triangle's one
// rounding rule (choose_rounding, from the centroid) and the rule of each row
// (choose_rounding_on_row) pick different texels. For grid spacings g = 1, 1/2 and 1/4
// px, 400 random triangles in a 64 x 64 viewport with vertices on the grid, u and v on
// the same grid (in texels, 0 to 32) and depths 1, 2 or 4 (not all equal) are drawn with
// the exact mapper in 16.16 fixed point, once per rule. A tie is decided exactly in
// 64-bit integers: with positions scaled by 2/g and 1/w by 4, u at a centre is
// g * sum(l_k U_k Q_k) / sum(l_k Q_k), l_k the three edge functions (@eq:closed-form's
// cross products). Writes ch04_ties.txt into the folder argv[1], for each g (named 1,
// 0.5, 0.25): pixels_g, tie_pixels_g, differ_pixels_g, ties_g and differ_g (percent of
// the pixels), and differ_off_tie_g (pixels that differ without being a tie: the chapter
// says there are none).
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/split_mix.hpp"
#include "exactpixels/texture/rounding.hpp"
#include "exactpixels/texture/texture_mapper.hpp"
#include "support/figure_file.hpp"

#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

namespace {

using namespace exactpixels;

constexpr int viewport = 64;

/// A random grid triangle: positions in [0, 64] and u, v in [0, 32] on multiples of 1/k
/// (k = 1, 2 or 4), depths 1, 2 or 4, not all equal, with a non-zero area.
std::array<TexturedVertex, 3> random_triangle(SplitMix& random, int k) {
    const auto on_grid = [&](int cells) {
        return static_cast<double>(random.next() %
                                   static_cast<std::uint64_t>(cells * k + 1)) /
               k;
    };
    const double depths[] = {1.0, 2.0, 4.0};
    for (;;) {
        std::array<TexturedVertex, 3> v{};
        for (TexturedVertex& t : v) {
            t.position = {on_grid(viewport), on_grid(viewport)};
            t.w = depths[random.next() % 3];
            t.uv = {on_grid(32), on_grid(32)};
        }
        const double area =
            (v[1].position.x - v[0].position.x) * (v[2].position.y - v[0].position.y) -
            (v[1].position.y - v[0].position.y) * (v[2].position.x - v[0].position.x);
        if (area != 0 && !(v[0].w == v[1].w && v[1].w == v[2].w)) {
            return v;
        }
    }
}

/// Whether u (coordinate 0) or v (coordinate 1) is exactly an integer at the centre of
/// pixel (x, y): the exact perspective interpolation in integers, scaled as above.
bool is_tie(const std::array<TexturedVertex, 3>& v, int k, int x, int y, int coordinate) {
    const std::int64_t s = 2 * k; // positions * s are integers, and so are centres
    std::array<std::int64_t, 3> px{}, py{}, c{}, q{};
    for (std::size_t i = 0; i < 3; ++i) {
        px[i] = static_cast<std::int64_t>(v[i].position.x * s);
        py[i] = static_cast<std::int64_t>(v[i].position.y * s);
        c[i] = static_cast<std::int64_t>((coordinate == 0 ? v[i].uv.x : v[i].uv.y) * k);
        q[i] = static_cast<std::int64_t>(4.0 / v[i].w);
    }
    const std::int64_t cx = (2 * x + 1) * k, cy = (2 * y + 1) * k;
    std::int64_t num = 0, den = 0;
    for (std::size_t i = 0; i < 3; ++i) {
        const std::size_t a = (i + 1) % 3, b = (i + 2) % 3; // l_i: the edge facing i
        const std::int64_t l = (px[a] - cx) * (py[b] - cy) - (py[a] - cy) * (px[b] - cx);
        num += l * c[i] * q[i];
        den += l * q[i];
    }
    den *= k; // c[i] counts 1/k texels
    return den != 0 && num % den == 0;
}

/// part / whole as a double (whole > 0).
double share(long long part, long long whole) {
    return static_cast<double>(part) / static_cast<double>(whole);
}

} // namespace

int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    std::string facts =
        "# chapter 4, Exercise 5: ties and rule differences by grid spacing\n";
    try {
        for (const int k : {1, 2, 4}) {
            SplitMix random{4};
            long long pixels = 0, ties = 0, differ = 0, differ_off_tie = 0;
            for (int t = 0; t < 400; ++t) {
                const std::array<TexturedVertex, 3> v = random_triangle(random, k);
                MapperSettings one;
                one.precision = Precision::fixed;
                one.rounding = choose_rounding(v);
                MapperSettings per_row = one;
                per_row.row_rounding = choose_rounding_on_row;
                TexelMap a(viewport, viewport), b(viewport, viewport);
                map_textured_triangle(a, v, one);
                map_textured_triangle(b, v, per_row);
                for (int y = 0; y < viewport; ++y) {
                    for (int x = 0; x < viewport; ++x) {
                        const auto p = static_cast<std::size_t>(y * viewport + x);
                        if (!a.covered[p]) {
                            continue;
                        }
                        const bool tie = is_tie(v, k, x, y, 0) || is_tie(v, k, x, y, 1);
                        const bool different = a.i[p] != b.i[p] || a.j[p] != b.j[p];
                        ++pixels;
                        ties += tie;
                        differ += different;
                        differ_off_tie += different && !tie;
                    }
                }
            }
            const double g = 1.0 / k;
            facts +=
                fmt::format("pixels_{0:g} {1}\ntie_pixels_{0:g} {2}\ndiffer_pixels_{0:g} "
                            "{3}\nties_{0:g} {4:.4f}\ndiffer_{0:g} {5:.4f}\n"
                            "differ_off_tie_{0:g} {6}\n",
                            g, pixels, ties, differ, 100.0 * share(ties, pixels),
                            100.0 * share(differ, pixels), differ_off_tie);
        }
        write_figure_file(folder / "ch04_ties.txt", facts);
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch04_ties: %s\n", error.what());
        return 1;
    }
}
