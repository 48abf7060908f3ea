// Chapter 3 figures: the floor and the wall by each mapper, error heat maps, u along one
// span (data for ch03_span_u.gp), and the measured tables the chapter pulls in. The
// panels of each scene figure are PNG pictures inside one SVG that labels them (a), (b),
// ... with their mapper, so the caption can refer to each panel by its letter.
// Usage: fig_ch03_mappers FIGURE_DIR
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/lab/perspective_scenes.hpp"
#include "exactpixels/texture/perspective_error.hpp"
#include "exactpixels/texture/span_mappers.hpp"
#include "support/figure_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

using namespace exactpixels;
namespace fs = std::filesystem;

namespace {
struct Variant {
    const char* name;
    MapperSettings settings;
};
const Variant variants[] = {
    {"exact", {.mapper = {MapperKind::exact}}},
    {"affine", {.mapper = {MapperKind::affine}}},
    {"subdivided, N = 16", {.mapper = {MapperKind::subdivided, 16}}},
    {"quadratic", {.mapper = {MapperKind::quadratic}}},
    {"quadratic, N = 16", {.mapper = {MapperKind::quadratic_subdivided, 16}}},
};
constexpr int panel_w = 240, panel_h = 180, gap = 4;

/// Panels side by side, `gap` pixels of white between them.
Framebuffer side_by_side(const std::vector<Framebuffer>& panels) {
    Framebuffer out(int(panels.size()) * (panel_w + gap) - gap, panel_h,
                    rgba(255, 255, 255));
    for (std::size_t p = 0; p < panels.size(); ++p) {
        for (int y = 0; y < panel_h; ++y) {
            for (int x = 0; x < panel_w; ++x) {
                out.at(int(p) * (panel_w + gap) + x, y) = panels[p].at(x, y);
            }
        }
    }
    return out;
}

/// `bytes` in base 64 (RFC 4648), for a picture inside an SVG (a data: URL).
std::string base64(const std::string& bytes) {
    static const char digits[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
        std::uint32_t group = 0;
        for (std::size_t k = 0; k < 3; ++k) {
            group = (group << 8) | (k < n ? std::uint8_t(bytes[i + k]) : 0u);
        }
        for (std::size_t k = 0; k < 4; ++k) {
            out += k <= n ? digits[(group >> (18 - 6 * k)) & 63u] : '=';
        }
    }
    return out;
}

/// Writes `panels` side by side as `stem`.png and as `stem`.svg: the same picture with
/// the label "(a) NAME", "(b) NAME", ... under each panel (the book shows the SVG).
void write_labelled(const fs::path& folder, const std::string& stem,
                    const std::vector<Framebuffer>& panels,
                    const std::vector<std::string>& names) {
    const fs::path png = folder / (stem + ".png");
    write_png(png, side_by_side(panels));
    std::ifstream in(png, std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in),
                            std::istreambuf_iterator<char>()};
    if (!in || bytes.empty()) {
        throw Error(fmt::format("{}: cannot read the panels back", png.string()));
    }
    constexpr int label_h = 30;
    const int width = int(panels.size()) * (panel_w + gap) - gap;
    std::string svg = fmt::format(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" "
        "xmlns:xlink=\"http://www.w3.org/1999/xlink\" width=\"{0}\" height=\"{1}\" "
        "viewBox=\"0 0 {0} {1}\">\n<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n"
        "<image x=\"0\" y=\"0\" width=\"{0}\" height=\"{2}\" "
        "xlink:href=\"data:image/png;base64,{3}\"/>\n",
        width, panel_h + label_h, panel_h, base64(bytes));
    for (std::size_t p = 0; p < panels.size(); ++p) {
        svg += fmt::format("<text x=\"{}\" y=\"{}\" font-family=\"sans-serif\" "
                           "font-size=\"20\" text-anchor=\"middle\">({}) {}</text>\n",
                           int(p) * (panel_w + gap) + panel_w / 2, panel_h + 22,
                           char('a' + p), names[p]);
    }
    svg += "</svg>\n";
    write_figure_file(folder / (stem + ".svg"), svg);
}

/// Texel distance d to a colour: black for 0, then dark blue (1/64 texel) through red to
/// yellow-white (8 texels and more), on a log scale.
Rgba8 heat(double d) {
    if (d <= 0.0) {
        return rgba(0, 0, 0);
    }
    const double t = std::clamp(std::log2(d * 64.0) / 9.0, 0.0, 1.0);
    return to_rgba8({std::clamp(2.0 * t - 0.2, 0.0, 1.0),
                     std::clamp(2.0 * t - 1.0, 0.0, 1.0),
                     std::clamp(0.5 - std::abs(t - 0.3), 0.0, 1.0)});
}

void write_scene_figures(const fs::path& folder, const std::string& name,
                         const PerspectiveScene& scene, std::string& table) {
    std::vector<Framebuffer> renders, heats;
    TexelMap exact(panel_w, panel_h);
    map_scene(exact, scene, variants[0].settings);
    for (const Variant& v : variants) {
        Framebuffer frame(panel_w, panel_h, rgba(20, 30, 60));
        draw_scene(frame, scene, v.settings);
        renders.push_back(frame);
        TexelMap map(panel_w, panel_h);
        map_scene(map, scene, v.settings);
        Framebuffer h(panel_w, panel_h, rgba(255, 255, 255));
        double worst = 0.0;
        int wrong = 0, pixels = 0;
        for (int y = 0; y < panel_h; ++y) {
            for (int x = 0; x < panel_w; ++x) {
                const std::size_t at = std::size_t(y) * panel_w + std::size_t(x);
                if (!map.covered[at]) {
                    continue;
                }
                const double d =
                    std::hypot(map.u[at] - exact.u[at], map.v[at] - exact.v[at]);
                h.at(x, y) = heat(d);
                worst = std::max(worst, d);
                ++pixels;
                wrong += map.i[at] != exact.i[at] || map.j[at] != exact.j[at];
            }
        }
        heats.push_back(h);
        table += fmt::format("| {} | {} | {} | {} | {:.1f} % | {:.3g} |\n", name, v.name,
                             pixels, wrong, 100.0 * wrong / pixels, worst);
    }
    std::vector<std::string> names;
    for (const Variant& v : variants) {
        names.emplace_back(v.name);
    }
    write_labelled(folder, "ch03_" + name + "_mappers", renders, names);
    write_labelled(folder, "ch03_" + name + "_heat",
                   std::vector<Framebuffer>(heats.begin() + 1, heats.end()),
                   std::vector<std::string>(names.begin() + 1, names.end()));
}

/// u along one span of 64 pixels, depth ratio 4, 64 texels: exact, affine, quadratic and
/// subdivided (N = 16), one row per pixel.
void write_span_data(const fs::path& folder) {
    const int count = 64;
    const double u0 = 0.0, u1 = 64.0, w0 = 1.0, w1 = 4.0, n = count - 1;
    const PerspectiveSpan<double> s{
        u0 / w0, 0.0, 1 / w0, (u1 / w1 - u0 / w0) / n, 0.0, (1 / w1 - 1 / w0) / n, count};
    std::vector<double> exact(count), affine(count), quad(count), sub(count);
    map_span_exact(s, [&](int k, double u, double) { exact[k] = u; });
    map_span_affine(AffineSpan<double>{u0, 0.0, (u1 - u0) / n, 0.0, count},
                    [&](int k, double u, double) { affine[k] = u; });
    map_span_quadratic(s, [&](int k, double u, double) { quad[k] = u; });
    map_span_subdivided(s, 16, [&](int k, double u, double) { sub[k] = u; });
    std::ostringstream out;
    out << "# pixel exact affine quadratic subdivided16 (u in texels; r = 4, 64 "
           "texels)\n";
    for (int k = 0; k < count; ++k) {
        out << k << ' ' << exact[k] << ' ' << affine[k] << ' ' << quad[k] << ' ' << sub[k]
            << '\n';
    }
    write_figure_file(folder / "ch03_span_u.dat", out.str());
}

/// The error of affine and quadratic for a range of depth ratios, and how large r may
/// grow before each errs by more than half a texel.
void write_error_tables(const fs::path& folder) {
    std::ostringstream table;
    table
        << "| depth ratio $r$ | affine, fraction of $\\Delta U$ | quadratic, fraction of "
           "$\\Delta U$ | affine, $\\Delta U = 64$ | quadratic, $\\Delta U = 64$ |\n"
           "|---:|---:|---:|---:|---:|\n";
    for (const double r : {1.1, 1.25, 1.5, 2.0, 3.0, 4.0, 8.0, 16.0, 64.0, 256.0}) {
        const double a = affine_error_bound(r), q = quadratic_error_max(r);
        table << fmt::format("| {} | {:.4f} | {:.5f} | {:.2f} | {:.3f} |\n", r, a, q,
                             64 * a, 64 * q);
    }
    table
        << "\n: Worst error over one span whose ends are exact and have depth ratio $r$: "
           "affine (@eq:affine-bound) and quadratic (@eq:quadratic-error, maximised "
           "numerically). {#tbl:span-error}\n";

    write_figure_file(folder / "ch03_error_table.md", table.str());

    std::ostringstream limits;
    limits << "| span extent $\\Delta U$ (texels) | affine: largest $r$ | quadratic: "
              "largest "
              "$r$ |\n|---:|---:|---:|\n";
    for (const double du : {4.0, 8.0, 16.0, 32.0, 64.0, 128.0, 256.0}) {
        const double a = largest_ratio_within(affine_error_bound, du, 0.5);
        const double q = largest_ratio_within(quadratic_error_max, du, 0.5);
        limits << fmt::format("| {} | {:.3f} | {} |\n", du, a,
                              std::isinf(q) ? std::string("any")
                                            : fmt::format("{:.3f}", q));
    }
    limits
        << "\n: The largest depth ratio $r$ over one span with exact ends for which each "
           "mapper stays within half a texel of the exact coordinate. "
           "{#tbl:span-limit}\n";
    write_figure_file(folder / "ch03_limit_table.md", limits.str());
}
} // namespace

int main(int argc, char** argv) {
    const fs::path folder = argc > 1 ? argv[1] : ".";
    try {
        std::string table = "| scene | mapper | pixels | wrong texel | share | worst "
                            "distance (texels) |\n|---|---|---:|---:|---:|---:|\n";
        write_scene_figures(folder, "floor", floor_scene(panel_w, panel_h), table);
        write_scene_figures(folder, "wall", wall_scene(panel_w, panel_h), table);
        table += "\n: Pixels where each mapper picks another texel than the exact "
                 "one (double), and its largest distance from the exact "
                 "coordinate. {#tbl:scene-error}\n";
        write_figure_file(folder / "ch03_scene_table.md", table);
        write_span_data(folder);
        write_error_tables(folder);
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch03_mappers: %s\n", error.what());
        return 1;
    }
}
