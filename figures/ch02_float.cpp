// Measurement: where float edge functions go wrong. Three meshes that must cover their
// pixels exactly once (a grid with every vertex on a pixel centre: ties everywhere; the
// same grid with its inner vertices jittered and snapped to 1/256 px; a fan of 720
// slivers) are drawn at growing distances from the origin by the fixed-point and float
// rasterizers and the naive one, counting centres covered by no triangle (gaps) or by
// two or more (overlaps). Writes ch02_float_table.md into the folder argv[1].
#include "exactpixels/base/error.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"
#include "exactpixels/raster/naive_rasterizer.hpp"
#include "support/figure_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace exactpixels;

namespace {

constexpr int side = 256; // every mesh lies in a 256 x 256 px window

/// A mesh and the pixels it must cover exactly once (its centres, relative to the
/// window's corner): the square of a grid mesh, or the centres well inside a fan.
struct Mesh {
    const char* name;
    std::vector<std::array<FixedPoint2, 3>> triangles; ///< 1/256 px, window-relative
    std::function<bool(int, int)> must_cover;          ///< pixel -> inside for sure
};

/// n x n cells of side/n px from (0.5, 0.5), each split in two along a diagonal, the
/// inner vertices moved by up to `jitter` px and snapped to 1/256 px.
Mesh grid_mesh(const char* name, int n, double jitter) {
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> wobble(-jitter, jitter);
    const double cell = static_cast<double>(side) / n;
    std::vector<std::vector<FixedPoint2>> p(n + 1, std::vector<FixedPoint2>(n + 1));
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
            const bool border = i == 0 || j == 0 || i == n || j == n;
            Point2 q{i * cell + 0.5, j * cell + 0.5}; // on a pixel centre
            if (!border) {
                q += Point2{wobble(rng), wobble(rng)};
            }
            p[j][i] = snap_to_subpixel(q);
        }
    }
    Mesh m{name, {}, [](int, int) { return true; }};
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            m.triangles.push_back({p[j][i], p[j][i + 1], p[j + 1][i + 1]});
            m.triangles.push_back({p[j][i], p[j + 1][i + 1], p[j + 1][i]});
        }
    }
    return m;
}

/// 720 slivers around a hub between pixel centres, out to a snapped 120 px circle.
Mesh fan_mesh() {
    const Point2 hub{128.3, 127.8};
    const auto rim = [&](int k) {
        const double angle = 2 * std::numbers::pi * k / 720;
        return snap_to_subpixel(hub + 120.0 * Point2{std::cos(angle), std::sin(angle)});
    };
    Mesh m{"fan of 720 slivers", {}, [hub](int x, int y) {
               return glm::length(pixel_centre(x, y) - hub) < 119.0;
           }};
    for (int k = 0; k < 720; ++k) {
        m.triangles.push_back({snap_to_subpixel(hub), rim(k), rim(k + 1)});
    }
    return m;
}

struct Faults {
    int gaps = 0;     ///< centres that must be covered, covered by none
    int overlaps = 0; ///< centres covered by two or more triangles
};

/// Draws the mesh moved by `offset` whole pixels with rasterizer `kind` and counts the
/// faults in the window.
Faults draw(const Mesh& mesh, int offset, int kind) {
    std::vector<int> count(side * side, 0);
    const Viewport viewport{offset + side + 8, offset + side + 8};
    const auto hit = [&](int x, int y) {
        const int i = x - offset, j = y - offset;
        if (i >= 0 && j >= 0 && i < side && j < side) {
            ++count[static_cast<std::size_t>(j * side + i)];
        }
    };
    const std::int64_t shift = std::int64_t{offset} * subpixel_scale;
    for (const auto& t : mesh.triangles) {
        std::array<FixedPoint2, 3> v;
        std::array<Point2f, 3> f;
        for (int k = 0; k < 3; ++k) {
            v[k] = {t[k].x + shift, t[k].y + shift};
            f[k] = Point2f(to_pixels(v[k])); // rounded to float's spacing at the offset
        }
        switch (kind) {
        case 0:
            edge_rasterize_blocks(v, viewport, hit);
            break;
        case 1:
            edge_rasterize_pixels(f, viewport, hit);
            break;
        case 2:
            edge_rasterize_blocks(f, viewport, hit);
            break;
        default:
            naive_rasterize(f, viewport, hit);
            break;
        }
    }
    Faults faults;
    for (int j = 0; j < side; ++j) {
        for (int i = 0; i < side; ++i) {
            const int n = count[static_cast<std::size_t>(j * side + i)];
            faults.gaps += n == 0 && mesh.must_cover(i, j);
            faults.overlaps += n > 1;
        }
    }
    return faults;
}

/// Pixels on which the float rasterizer `kind` (1: 1x1, 2: 8x8) differs from the exact
/// coverage of the very same vertices, over `count` random triangles about `size` px
/// across at `offset` px from the origin. Float vertices made from 1/256 px values are
/// themselves multiples of 1/256 px, so the fixed-point rasterizer gives their exact
/// coverage. Returns {pixels drawn exactly, wrong pixels of 1x1, wrong of 8x8, pixels
/// where 8x8 differs from the exact coverage of the original 1/256 px vertices (the
/// vertices moved when rounded to float)}.
std::array<long, 4> float_errors(int size, int offset, int count) {
    std::mt19937_64 rng(static_cast<std::uint64_t>(size) * 7919 + offset);
    std::uniform_real_distribution<double> u(0.0, size);
    const Viewport viewport{offset + size + 8, offset + size + 8};
    std::array<long, 4> result{0, 0, 0, 0};
    std::vector<int> exact(static_cast<std::size_t>(size + 8) * (size + 8));
    for (int n = 0; n < count; ++n) {
        std::array<Point2f, 3> f;
        std::array<FixedPoint2, 3> v, original;
        for (int k = 0; k < 3; ++k) {
            original[k] = snap_to_subpixel(Point2{offset + u(rng), offset + u(rng)});
            const Point2 p = to_pixels(original[k]);
            f[k] = Point2f(p);
            v[k] = snap_to_subpixel(Point2(f[k])); // exact: f[k] is on the 1/256 grid
        }
        std::fill(exact.begin(), exact.end(), 0);
        const auto index = [&](int x, int y) {
            return static_cast<std::size_t>(y - offset) * (size + 8) +
                   static_cast<std::size_t>(x - offset);
        };
        edge_rasterize_pixels(v, viewport, [&](int x, int y) {
            exact[index(x, y)] = 1;
            ++result[0];
        });
        std::vector<int> unrounded(exact.size(), 0);
        edge_rasterize_pixels(original, viewport,
                              [&](int x, int y) { unrounded[index(x, y)] = 1; });
        for (int kind = 1; kind <= 2; ++kind) {
            std::vector<int> drawn(exact.size(), 0);
            const auto hit = [&](int x, int y) { drawn[index(x, y)] = 1; };
            if (kind == 1) {
                edge_rasterize_pixels(f, viewport, hit);
            } else {
                edge_rasterize_blocks(f, viewport, hit);
            }
            for (std::size_t i = 0; i < drawn.size(); ++i) {
                result[kind] += drawn[i] != exact[i];
                result[3] += kind == 2 && drawn[i] != unrounded[i];
            }
        }
    }
    return result;
}

} // namespace

int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    const auto path = folder / "ch02_float_table.md";
    std::ostringstream out;
    const int offsets[] = {0, 1 << 12, 1 << 16, 1 << 18, (1 << 20) - side - 8};
    const char* names[] = {"fixed 8x8", "float 1x1", "float 8x8", "naive"};
    const Mesh meshes[] = {grid_mesh("grid, vertices on centres", 8, 0.0),
                           grid_mesh("grid, jittered", 8, 5.0), fan_mesh()};
    out << "| mesh | offset (px) |";
    for (const char* name : names) {
        out << ' ' << name << " |";
    }
    out << "\n|---|--:|--:|--:|--:|--:|\n";
    for (const Mesh& mesh : meshes) {
        for (const int offset : offsets) {
            out << "| " << mesh.name << " (" << mesh.triangles.size() << ") | " << offset
                << " |";
            for (int kind = 0; kind < 4; ++kind) {
                const Faults f = draw(mesh, offset, kind);
                out << ' ' << f.gaps << " / " << f.overlaps << " |";
            }
            out << '\n';
        }
    }
    out << "\n: Gaps / overlaps: pixel centres of a 256 x 256 px window covered by none "
           "of "
           "a mesh's triangles (where the mesh must cover them) or by two or more, with "
           "the "
           "mesh moved away from the origin by the offset (fig_ch02_float). "
           "{#tbl:edge-float-faults}\n";
    out << "\n| triangles, size (px) | offset (px) | pixels drawn | float 1x1 wrong | "
           "float 8x8 wrong | float 8x8 vs 1/256 vertices |\n|---|--:|--:|--:|--:|--:|\n";
    const std::pair<int, int> sizes[] = {{16, 4000}, {128, 400}, {1024, 12}};
    for (const auto& [size, count] : sizes) {
        for (const int offset : {0, 1 << 14, 1 << 18, (1 << 20) - size - 8}) {
            const auto r = float_errors(size, offset, count);
            out << "| " << count << " x " << size << " | " << offset << " | " << r[0]
                << " | " << r[1] << " | " << r[2] << " | " << r[3] << " |\n";
        }
    }
    out << "\n: Pixels on which the float rasterizers differ from the exact coverage of "
           "the "
           "same vertices, and from the exact coverage of the vertices before they were "
           "rounded to float, for random triangles about the given size across "
           "(fig_ch02_float). {#tbl:edge-float-wrong}\n";
    try {
        write_figure_file(path, out.str());
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch02_float: %s\n", error.what());
        return 1;
    }
    std::printf("wrote %s\n", path.c_str());
}
