// live_figures.cpp: the C interface through which the HTML book's live figures
// (web/live.js) call the library, compiled to WebAssembly (web/CMakeLists.txt).
//
// Each function takes a figure's inputs as the reader set them (vertex positions in
// pixels, a gradient, a depth slope), calls the library's own functions, the ones the
// chapters' tests prove, and writes what the figure draws into `cells`, an array in the
// module's memory that live.js reads after the call. Nothing here decides coverage or a
// texel by itself: that is always the library's answer, so what a reader drags is what
// the tests prove. Inputs outside a figure's range are refused (the function returns -1)
// before the library is called, so the library's own checks (which throw, and throw
// traps here, see no_exception_runtime.cpp) never fire.
#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/raster/edge_function.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"
#include "exactpixels/raster/gradients.hpp"
#include "exactpixels/raster/scanline.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "exactpixels/texture/level_of_detail.hpp"
#include "exactpixels/texture/perspective.hpp"
#include "exactpixels/texture/rounding.hpp"
#include "exactpixels/texture/span_mappers.hpp"

#include "live_scenes.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#define EXPORT(name) extern "C" __attribute__((export_name(name)))

using namespace exactpixels;

namespace {

// The largest grid figure: 32 x 32 pixels, one cell each.
constexpr int max_side = 32;
// The answers: 4096 cells (chapter 7's image and its triangles are the most) and 4096
// real values (chapter 8's levels, 48 x 32, are the most).
constexpr int cell_count = 4096;
std::int32_t cells[cell_count];
constexpr int span_pixels = 64;
double values[4096];

// Text answers (a reason, a message), NUL-terminated.
char text[256];

void copy_text(const std::string& s) {
    const std::size_t n = std::min(s.size(), sizeof text - 1);
    std::copy(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(n), text);
    text[n] = '\0';
}

bool in_figure(double v, int side) {
    return std::isfinite(v) && v >= -1 && v <= side + 1;
}

bool fits(int width, int height) {
    return width > 0 && height > 0 && width <= max_side && height <= max_side;
}

// A triangle's corners (pixels) within a width x height figure, give or take a pixel.
bool triangle_fits(std::array<double, 3> x, std::array<double, 3> y, int width, int height) {
    return fits(width, height) &&
           std::all_of(x.begin(), x.end(), [&](double v) { return in_figure(v, width); }) &&
           std::all_of(y.begin(), y.end(), [&](double v) { return in_figure(v, height); });
}

} // namespace

/// Where the figures' answers are written: 4096 32-bit cells.
EXPORT("ep_cells") std::int32_t* ep_cells() {
    return cells;
}

/// Where the real-valued answers are written: 4096 doubles.
EXPORT("ep_values") double* ep_values() {
    return values;
}

/// Where text answers are written: a NUL-terminated string of at most 255 bytes.
EXPORT("ep_text") const char* ep_text() {
    return text;
}

/// Chapter 3, the mappers along one span: 64 pixels, u from 0 at pixel 0 to 64 at pixel
/// 63, depth w from 1 to `ratio` (the placement of @fig:span-u). values[m * 64 + k] is u
/// at pixel k by mapper m: 0 exact (map_span_exact), 1 affine (map_span_affine),
/// 2 quadratic (map_span_quadratic), 3 subdivided with pieces of 16 pixels
/// (map_span_subdivided). values[256 + m] is mapper m's largest |u - exact u| on the
/// span, and cells[m] the number of its pixels whose texel floor(u) is not the exact
/// one's. Returns 0, or -1 unless 1 <= ratio <= 64.
EXPORT("ep_span_mappers") int ep_span_mappers(double ratio) {
    if (!(ratio >= 1 && ratio <= 64)) {
        return -1;
    }
    const int count = span_pixels;
    const double u0 = 0.0, u1 = 64.0, w0 = 1.0, w1 = ratio, n = count - 1;
    const PerspectiveSpan<double> s{
        u0 / w0, 0.0, 1 / w0, (u1 / w1 - u0 / w0) / n, 0.0, (1 / w1 - 1 / w0) / n, count};
    const auto into = [](int m) {
        return [m](int k, double u, double) { values[m * span_pixels + k] = u; };
    };
    map_span_exact(s, into(0));
    map_span_affine(AffineSpan<double>{u0, 0.0, (u1 - u0) / n, 0.0, count}, into(1));
    map_span_quadratic(s, into(2));
    map_span_subdivided(s, 16, into(3));
    for (int m = 0; m < 4; ++m) {
        double worst = 0;
        int other = 0;
        for (int k = 0; k < count; ++k) {
            const double u = values[m * count + k], exact = values[k];
            worst = std::max(worst, std::abs(u - exact));
            other += std::floor(u) != std::floor(exact) ? 1 : 0;
        }
        values[4 * count + m] = worst;
        cells[m] = other;
    }
    return 0;
}

/// Chapter 1, the scanline walk and the gradient: the triangle (x0, y0), (x1, y1),
/// (x2, y2) in pixels (double, not snapped: chapter 1's form) with the value c = 0, 1,
/// 1/2 at its vertices. Its spans by scanline_spans fill cells 2y and 2y + 1 with the
/// row's first and one-past-last column (-1, -1 for a row without pixels), for the rows
/// 0 to height - 1; values[0], values[1] are the closed-form gradient (dc/dx, dc/dy),
/// values[2], values[3] the split-edge one (closed_form_gradient, split_edge_gradient).
/// Returns the number of covered pixels, or -1 for inputs outside the figure.
EXPORT("ep_scanline")
int ep_scanline(double x0, double y0, double x1, double y1, double x2, double y2,
                int width, int height) {
    if (!triangle_fits({x0, x1, x2}, {y0, y1, y2}, width, height)) {
        return -1;
    }
    const std::array<Point2, 3> v = {Point2{x0, y0}, Point2{x1, y1}, Point2{x2, y2}};
    for (int y = 0; y < height; ++y) {
        cells[2 * y] = cells[2 * y + 1] = -1;
    }
    int covered = 0;
    scanline_spans(v, Viewport{width, height}, [&](Span s) {
        cells[2 * s.y] = s.x_begin;
        cells[2 * s.y + 1] = s.x_end;
        covered += s.x_end - s.x_begin;
    });
    const std::array<double, 3> c = {0.0, 1.0, 0.5};
    const Gradient<double> closed = closed_form_gradient<double>(v, c);
    const Gradient<double> split = split_edge_gradient<double>(v, c);
    values[0] = closed.dx;
    values[1] = closed.dy;
    values[2] = split.dx;
    values[3] = split.dy;
    return covered;
}

/// Chapter 2, the fill rule: the triangle (x0, y0), (x1, y1), (x2, y2), snapped to
/// 1/256 px (snap_to_subpixel), rasterized by edge_rasterize_pixels into a width x
/// height grid. Cell y * width + x holds
///   bit 0        the pixel is covered (the rasterizer emitted it);
///   bits 1 to 2  0 when the centre is on no edge of the closed triangle, else 1 + the
///                index of the edge that decided the tie: for a covered pixel an edge it
///                lies on (a top or left edge, which owns it), for an uncovered one the
///                edge that gave it away (a bottom or right edge);
///   bit 3        edge 0 is a top or left edge (cell 0 only), bit 4 edge 1, bit 5 edge 2.
/// Returns the number of covered pixels, or -1 for inputs outside the figure.
EXPORT("ep_fill_rule")
int ep_fill_rule(double x0, double y0, double x1, double y1, double x2, double y2,
                 int width, int height) {
    if (!triangle_fits({x0, x1, x2}, {y0, y1, y2}, width, height)) {
        return -1;
    }
    const std::array<FixedPoint2, 3> v = {snap_to_subpixel(Point2{x0, y0}),
                                          snap_to_subpixel(Point2{x1, y1}),
                                          snap_to_subpixel(Point2{x2, y2})};
    for (int i = 0; i < width * height; ++i) {
        cells[i] = 0;
    }
    int covered = 0;
    edge_rasterize_pixels(v, Viewport{width, height}, [&](int x, int y) {
        cells[y * width + x] |= 1;
        ++covered;
    });
    const EdgeSetup<FixedEdge> s = setup_edges(v);
    if (s.empty) {
        return covered;
    }
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            // The edge function itself, without the top-left bias: 0 on the edge.
            std::array<std::int64_t, 3> e{};
            bool closed = true;
            for (int i = 0; i < 3; ++i) {
                e[i] = s.edge[i].at(x, y) - s.edge[i].bias;
                closed = closed && e[i] >= 0;
            }
            if (!closed) {
                continue;
            }
            const bool is_covered = (cells[y * width + x] & 1) != 0;
            for (int i = 0; i < 3; ++i) {
                // Covered: the first edge through the centre (all of them own it).
                // Not covered: the first edge through it that is not top or left.
                if (e[i] == 0 && (is_covered || s.edge[i].bias != 0)) {
                    cells[y * width + x] |= (i + 1) << 1;
                    break;
                }
            }
        }
    }
    for (int i = 0; i < 3; ++i) {
        if (s.edge[i].bias == 0) {
            cells[0] |= 1 << (3 + i);
        }
    }
    return covered;
}

/// Chapter 4, choosing the rule: a row of `count` pixel centres, a = 0 .. count - 1,
/// whose texture coordinate is u(a) = (4 + dc_dx (a - 4)) / (1 + dq_dx (a - 4)), that is
/// p = u/w = 4 + dc_dx (a - 4) and q = 1/w = 1 + dq_dx (a - 4) (dq_dx = 0: affine), with
/// dp/dy = dc_dy and dq/dy = 0. The rule is choose_rule of the projected coordinate at
/// a = 4 (the sign of its numerator BC - AD, numerator_x); each centre's texel is
/// round_with_modifier of c = u - 1/2 in units of 1/256 (snap_to_subpixel), with that
/// rule's modifier. Cells: [0] the rule (1 or 2), [1] the numerator's sign (-1, 0, 1),
/// [2] numerator_y's sign, then for each centre a the texel by the chosen rule at
/// 3 + 2a and by rule 1 alone at 4 + 2a (a centre where q <= 0 has no u: 9999 in both).
/// Returns 0, or -1 for inputs outside the figure.
EXPORT("ep_texel_rule")
int ep_texel_rule(double dc_dx, double dc_dy, double dq_dx, int count) {
    if (count < 1 || count > 16 || !(std::abs(dc_dx) <= 4) || !(std::abs(dc_dy) <= 4) ||
        !(std::abs(dq_dx) <= 1)) {
        return -1;
    }
    const ProjectedCoordinate<double> at_4{4.0, 1.0, {dc_dx, dc_dy}, {dq_dx, 0.0}};
    const RoundingRule rule = choose_rule(at_4);
    const auto sign = [](double n) { return n > 0 ? 1 : n < 0 ? -1 : 0; };
    cells[0] = rule == RoundingRule::ties_up ? 1 : 2;
    cells[1] = sign(numerator_x(at_4));
    cells[2] = sign(numerator_y(at_4));
    constexpr int k = subpixel_bits; // c in units of 1/256 texel
    for (int a = 0; a < count; ++a) {
        const ProjectedCoordinate<double> here =
            moved_by(at_4, static_cast<double>(a - 4), 0.0);
        if (!(here.q > 0)) {
            cells[3 + 2 * a] = cells[4 + 2 * a] = 9999;
            continue;
        }
        const std::int64_t c = snap_to_subpixel(here.p / here.q - 0.5);
        cells[3 + 2 * a] =
            static_cast<std::int32_t>(round_with_modifier(c, rounding_modifier(rule, k), k));
        cells[4 + 2 * a] = static_cast<std::int32_t>(
            round_with_modifier(c, rounding_modifier(RoundingRule::ties_up, k), k));
    }
    return 0;
}

/// Chapter 0, pixel centres on an edge: the edge from (ax, ay) to (bx, by), snapped to
/// 1/256 px, against every centre of a width x height grid. Cell y * width + x is 1 when
/// the centre of pixel (x, y) lies on the closed segment (its edge_function is exactly 0
/// and it lies between the ends); cells width * height and width * height + 1 hold the
/// exponents of the largest powers of two dividing dx and dy in whole pixels (-1 for 0),
/// which the chapter says decide whether the edge meets a centre at all. Returns the
/// number of such centres, or -1 for inputs outside the figure.
EXPORT("ep_edge_centres")
int ep_edge_centres(double ax, double ay, double bx, double by, int width, int height) {
    if (!fits(width, height) || width * height + 2 > max_side * max_side ||
        !in_figure(ax, width) || !in_figure(bx, width) ||
        !in_figure(ay, height) || !in_figure(by, height)) {
        return -1;
    }
    const FixedPoint2 a = snap_to_subpixel(Point2{ax, ay});
    const FixedPoint2 b = snap_to_subpixel(Point2{bx, by});
    int count = 0;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const FixedPoint2 p = fixed_pixel_centre(x, y);
            const std::int64_t along = (p.x - a.x) * (b.x - a.x) + (p.y - a.y) * (b.y - a.y);
            const std::int64_t length2 =
                (b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y);
            const bool on = !(a == b) && edge_function(a, b, p) == 0 && along >= 0 &&
                            along <= length2;
            cells[y * width + x] = on ? 1 : 0;
            count += on ? 1 : 0;
        }
    }
    const auto twos = [](std::int64_t d_units) { // d in 1/256 px; 8 of its twos are the units
        return d_units == 0 ? -1
                            : std::countr_zero(static_cast<std::uint64_t>(
                                  d_units < 0 ? -d_units : d_units)) - subpixel_bits;
    };
    cells[width * height] = twos(b.x - a.x);
    cells[width * height + 1] = twos(b.y - a.y);
    return count;
}


/// Chapter 2, blocks of 8 x 8 pixels: the triangle (x0, y0), (x1, y1), (x2, y2), snapped
/// to 1/256 px, in a width x height grid (multiples of 8). Cell y * width + x is 1 for a
/// pixel traverse_blocks emits (the plain block walk of @sec:edge-blocks), else 0. Cell
/// width * height + j * (width / 8) + i is the block in column i, row j of blocks:
/// 0 outside the bounding box (pixel_bounds), 1 rejected, 2 accepted, 3 partial (tested
/// pixel by pixel), as classify_block says of the block cut to the box, or 4 for every
/// block of a box within one block, which traverse_blocks walks pixel by pixel without
/// classifying. Returns the number of pixels emitted, or -1 for inputs outside the figure.
EXPORT("ep_blocks")
int ep_blocks(double x0, double y0, double x1, double y1, double x2, double y2, int width,
              int height) {
    if (!triangle_fits({x0, x1, x2}, {y0, y1, y2}, width, height) || width % block_size ||
        height % block_size) {
        return -1;
    }
    const std::array<FixedPoint2, 3> v = {snap_to_subpixel(Point2{x0, y0}),
                                          snap_to_subpixel(Point2{x1, y1}),
                                          snap_to_subpixel(Point2{x2, y2})};
    const int columns = width / block_size, rows = height / block_size;
    std::fill(cells, cells + width * height + columns * rows, 0);
    const EdgeSetup<FixedEdge> s = setup_edges(v);
    const PixelRect box = pixel_bounds(v, Viewport{width, height});
    if (s.empty || box.empty()) {
        return 0;
    }
    int emitted = 0;
    auto emit = [&](int x, int y) {
        cells[y * width + x] = 1;
        ++emitted;
    };
    traverse_blocks(s, box, emit);
    const bool one_block =
        box.x_end - box.x_begin <= block_size && box.y_end - box.y_begin <= block_size;
    for (int j = 0; j < rows; ++j) {
        for (int i = 0; i < columns; ++i) {
            const PixelRect b{std::max(i * block_size, box.x_begin),
                              std::max(j * block_size, box.y_begin),
                              std::min((i + 1) * block_size, box.x_end),
                              std::min((j + 1) * block_size, box.y_end)};
            int verdict = 0;
            if (!b.empty()) {
                verdict = one_block ? 4 : 1 + static_cast<int>(classify_block(s, b));
            }
            cells[width * height + j * columns + i] = verdict;
        }
    }
    return emitted;
}

/// Chapter 8, the level of detail on a tilted floor (live::tilted_floor, which holds
/// its size and camera): its two triangles rasterized by edge_rasterize_pixels into
/// 48 x 32 pixels; at each covered pixel centre values[y * 48 + x] is isotropic_level of
/// derivatives_at, the level chapter 8 reads, and cells[y * 48 + x] is 1 (0 where not
/// covered, values 0). values[1536] is the level at the image centre, where the view
/// axis meets the floor, and values[1537] its closed form log2(s d / (f cos a))
/// (@sec:level). Returns the number of covered pixels, or -1 for a tilt outside [0, 80]
/// degrees or a distance outside [4, 12].
EXPORT("ep_level")
int ep_level(double tilt, double distance) {
    if (!live::floor_allowed(tilt, distance)) {
        return -1;
    }
    constexpr int width = live::floor_width, height = live::floor_height;
    const auto triangles = live::tilted_floor(tilt, distance);
    std::fill(cells, cells + width * height, 0);
    std::fill(values, values + width * height + 2, 0.0);
    int covered = 0;
    for (const auto& t : triangles) {
        const std::array<FixedPoint2, 3> v = {snap_to_subpixel(t[0].position),
                                              snap_to_subpixel(t[1].position),
                                              snap_to_subpixel(t[2].position)};
        edge_rasterize_pixels(v, Viewport{width, height}, [&](int x, int y) {
            cells[y * width + x] = 1;
            values[y * width + x] =
                isotropic_level(derivatives_at(t, Point2{x + 0.5, y + 0.5}));
            ++covered;
        });
    }
    const Pinhole lens = live::floor_lens();
    values[width * height] = isotropic_level(derivatives_at(triangles[0], lens.centre));
    values[width * height + 1] =
        std::log2(live::floor_texels_per_unit * distance /
                  (lens.focal * std::cos(tilt * std::acos(-1.0) / 180.0)));
    return covered;
}

/// Chapter 7, the camera moved about a small scene (live_scenes.hpp) standing at
/// (x, 1.5, z), rendered by render_scene. Cells:
///   y * 64 + x (the first 64 x 40)  the pixel's colour, 0xRRGGBB;
///   2560 to 2569  the report: geometry, rejected, clipping and culling triangles,
///                 raster triangles and pixels, whether the depth stage ran, the pixels
///                 it tested and those it hid, and the number of triangles n;
///   2576 + 4k to 2579 + 4k  triangle k of the scene (meshes in order): what the
///                 geometry stage did to it, as render_scene reports it for a scene
///                 holding that triangle alone (the stage treats each triangle on its
///                 own): bit 0 rejected, bit 1 clipped; the pieces culled; the pieces
///                 drawn; the pixels they cover.
/// values[2k], values[2k + 1], ... the floor-plan (x, z) of triangle k's three corners,
/// six per triangle. The text at ep_text() is the depth plan's reason (depth_reason).
/// Returns the number of triangles, or -1 where the camera may not stand
/// (live::camera_allowed).
EXPORT("ep_scene")
int ep_scene(double x, double z) {
    if (!live::camera_allowed(x, z)) {
        return -1;
    }
    const Scene scene = live::live_scene(x, z);
    const RenderResult whole = render_scene(scene);
    const int width = scene.width, height = scene.height;
    static_assert(live::scene_width * live::scene_height <= 2560);
    for (int y = 0; y < height; ++y) {
        for (int i = 0; i < width; ++i) {
            const Rgba8 p = whole.image.at(i, y);
            cells[y * width + i] = (p.r << 16) | (p.g << 8) | p.b;
        }
    }
    const RenderReport& r = whole.report;
    std::int32_t* report = cells + 2560;
    const long long counts[] = {r.geometry.triangles, r.rejected.triangles,
                                r.clipping.triangles, r.culling.triangles,
                                r.raster.triangles,   r.raster.pixels,
                                r.depth_on ? 1 : 0,   r.depth.pixels,
                                r.hidden.pixels};
    for (int k = 0; k < 9; ++k) {
        report[k] = static_cast<std::int32_t>(counts[k]);
    }
    copy_text(r.depth_reason);
    int n = 0;
    for (const SceneMesh& mesh : scene.meshes) {
        for (const auto& triangle : mesh.triangles) {
            Scene alone = scene;
            alone.meshes = {mesh};
            alone.meshes[0].triangles = {triangle};
            const RenderReport one = render_scene(alone).report;
            std::int32_t* t = cells + 2576 + 4 * n;
            t[0] = (one.rejected.triangles > 0 ? 1 : 0) | (one.clipping.triangles > 0 ? 2 : 0);
            t[1] = static_cast<std::int32_t>(one.culling.triangles);
            t[2] = static_cast<std::int32_t>(one.raster.triangles);
            t[3] = static_cast<std::int32_t>(one.raster.pixels);
            for (int c = 0; c < 3; ++c) {
                values[6 * n + 2 * c] = triangle[c].position.x;
                values[6 * n + 2 * c + 1] = triangle[c].position.z;
            }
            ++n;
        }
    }
    report[9] = n;
    return n;
}
