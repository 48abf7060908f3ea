// Chapter 9's referee figure (@sec:scene-referee): every shipped scene compared with
// Mesa's llvmpipe (tests/referee/opengl_referee.hpp), meshes lit per pixel included.
// Writes the comparison table (ch09_referee.md), its totals as facts for the prose
// (ch09_referee_facts.txt) and, for the corridor, ours | llvmpipe | the differences
// highlighted (ch09_referee.png).
// Usage: fig_ch09_referee FIGURE_DIR
#include "exactpixels/base/error.hpp"

#ifdef EXACTPIXELS_HAVE_OSMESA

#include "exactpixels/base/png.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "referee/opengl_referee.hpp"
#include "support/figure_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

using namespace exactpixels;

namespace {

/// The scene the difference image shows.
constexpr const char* shown_scene = "corridor";

/// Pixels between the three panels.
constexpr int panel_gap = 8;

/// Half the side of the square that marks a differing pixel (single pixels would be
/// invisible at print size).
constexpr int mark_radius = 2;

/// Ours | llvmpipe | ours in grey with each difference marked by a square of its colour.
Framebuffer panels(const RefereeComparison& c) {
    const int w = c.width, h = c.height;
    Framebuffer out(3 * w + 2 * panel_gap, h, rgba(255, 255, 255));
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            out.at(x, y) = c.ours.at(x, y);
            out.at(w + panel_gap + x, y) = c.theirs.at(x, y);
            out.at(2 * (w + panel_gap) + x, y) = c.differences.at(x, y);
        }
    }
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const Rgba8 p = c.differences.at(x, y);
            const bool marked = p.r != p.g || p.g != p.b; // the grey copy is grey
            if (!marked) {
                continue;
            }
            for (int dy = -mark_radius; dy <= mark_radius; ++dy) {
                for (int dx = -mark_radius; dx <= mark_radius; ++dx) {
                    const int mx = std::clamp(x + dx, 0, w - 1);
                    const int my = std::clamp(y + dy, 0, h - 1);
                    out.at(2 * (w + panel_gap) + mx, my) = p;
                }
            }
        }
    }
    return out;
}

} // namespace

int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    try {
        std::string why;
        if (!opengl_referee_ready(why)) {
            throw Error("the OpenGL referee cannot run: " + why);
        }
        std::string table =
            "| scene | covered | coverage diff. | depth diff. | colours | lit | "
            "beyond (on edges) | worst off edges |\n"
            "|:------|----:|----:|---:|----:|----:|----:|---:|\n";
        long long scenes = 0, covered = 0, coverage = 0, depth = 0, compared = 0,
                  over = 0, edge = 0, shipped = 0, lit_scenes = 0, lit = 0,
                  uncompared = 0, shown_marked = 0, shown_any = 0;
        int worst_off_edge = 0, worst_lit = 0;
        double worst_gap = 0.0, worst_lit_float = 0.0;
        for (const std::string& name : referee_scene_names()) {
            const RefereeComparison c = referee_scene(
                load_scene(shipped_scene_folder() / (name + ".toml")), name);
            table += fmt::format(
                "| {} | {} | {} | {} | {} | {} | {} ({}) | {} |\n", name, c.covered,
                c.coverage_differences.size(), c.depth_differences,
                c.colour_compared > 0 ? fmt::format("{}", c.colour_compared) : "none",
                c.lit_compared, c.colour_over, c.texel_edge, c.worst_off_edge);
            scenes += 1;
            covered += c.covered;
            coverage += static_cast<long long>(c.coverage_differences.size());
            depth += c.depth_differences;
            compared += c.colour_compared;
            over += c.colour_over;
            edge += c.texel_edge;
            shipped += c.shipped_differ;
            lit_scenes += c.phong_meshes > 0;
            lit += c.lit_compared;
            uncompared += c.colour_uncompared;
            worst_lit = std::max(worst_lit, c.worst_lit_off_edge);
            worst_lit_float = std::max(worst_lit_float, c.worst_lit_float);
            worst_off_edge = std::max(worst_off_edge, c.worst_off_edge);
            worst_gap = std::max(worst_gap, c.worst_depth_gap);
            if (name == shown_scene) {
                write_png(folder / "ch09_referee.png", panels(c));
                // What the figure shows: the pixels it marks, and the pixels whose bytes
                // differ at all (most of them within the tolerance, so left unmarked).
                for (int y = 0; y < c.height; ++y) {
                    for (int x = 0; x < c.width; ++x) {
                        const Rgba8 p = c.differences.at(x, y);
                        shown_marked += p.r != p.g || p.g != p.b;
                        const Rgba8 a = c.ours.at(x, y), b = c.theirs.at(x, y);
                        shown_any += a.r != b.r || a.g != b.g || a.b != b.b;
                    }
                }
            }
        }
        table +=
            "\n: Every shipped scene drawn by the renderer and by llvmpipe from the "
            "same snapped triangles (generated by figures/ch09_referee.cpp). "
            "Depth diff.: pixels where another triangle wins. Colours: the pixels whose "
            "colours are compared (none where every texture is filtered); lit: of "
            "those, the pixels lit per pixel; beyond: "
            "those where the exact render and llvmpipe differ by more than the "
            "tolerance, " +
            std::to_string(referee_rounding_levels) + " levels (" +
            std::to_string(referee_lit_levels) +
            " where lit per pixel), and how many of them are on texel edges; worst off "
            "edges: the largest channel difference, levels, "
            "at pixels whose texture coordinate is not within 1/64 texel of a texel "
            "edge. {#tbl:scene-referee}\n";
        long long far_departures = 0, far_exact = 0, far_covered = 0;
        for (const ScreenTriangle& t : far_reaching_triangles(far_count)) {
            const CoverageComparison c = referee_coverage({t}, far_frame, far_frame);
            far_departures += static_cast<long long>(c.differences.size());
            far_exact += static_cast<long long>(c.ours_exact.size());
            far_covered += c.covered;
        }
        write_figure_file(folder / "ch09_referee.md", table);
        write_figure_file(
            folder / "ch09_referee_facts.txt",
            fmt::format(
                "# figures/ch09_referee.cpp: the referee's totals over every "
                "shipped scene\nreferee_scenes {}\nreferee_covered {}\n"
                "referee_coverage_differences {}\nreferee_depth_differences {}\n"
                "referee_depth_gap_millionths {:.3f}\nreferee_colours_compared {}\n"
                "referee_colour_over {}\nreferee_texel_edge {}\n"
                "referee_worst_off_edge {}\nreferee_shipped_differ {}\n"
                "referee_far_triangles {}\nreferee_far_covered {}\n"
                "referee_far_departures {}\nreferee_far_ours_exact {}\n"
                "referee_lit_scenes {}\nreferee_lit_compared {}\n"
                "referee_worst_lit_off_edge {}\nreferee_lit_float_levels {:.4f}\n"
                "referee_colour_uncompared {}\nreferee_shown_marked {}\n"
                "referee_shown_any {}\n",
                scenes, covered, coverage, depth, worst_gap * 1e6, compared, over, edge,
                worst_off_edge, shipped, far_count, far_covered, far_departures,
                far_exact, lit_scenes, lit, worst_lit, worst_lit_float, uncompared,
                shown_marked, shown_any));
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch09_referee: %s\n", error.what());
        return 2;
    }
    return 0;
}

#else

#include <cstdio>

int main() {
    std::fputs(
        "fig_ch09_referee: OSMesa (Debian libosmesa6-dev) was not found when CMake "
        "configured this build; the OpenGL referee cannot run\n",
        stderr);
    return 2;
}

#endif
