// render_report.hpp: what a render did, stage by stage (counts, divides and times), the
// report as a table, and the clocks the stages are timed with. The stages return
// what they did and the drawing counts it; their times come from one sampled timer
// around the stage calls (StageTimer) and are shared among the stages afterwards
// (share_drawing_time).
//
// Usage:
//   RenderReport report;                       // filled in by run_geometry, render_scene
//   std::fputs(format_report(report).c_str(), stdout);
//   const long long total = report.divides();
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cstddef>
#include <string>

namespace exactpixels {

/// The work one part of a render did over the whole of it: a stage, a mapper, auto's
/// choice, the pixels the depth test hid.
struct WorkCount {
    long long triangles = 0; ///< triangles it ran on
    long long spans = 0;     ///< row spans it ran on
    long long pixels = 0;    ///< pixels it ran on
    long long divides = 0;   ///< divides it performed
    double seconds = 0.0;    ///< time spent in it
};

/// What ran while rendering a scene: one counter per stage and per mapper.
struct RenderReport {
    WorkCount geometry; ///< triangles moved to view space and projected
    /// triangles wholly outside one plane of the view volume (a screen edge, near or
    /// far), dropped before they are projected or lit
    WorkCount rejected;
    /// triangles cut in view space because a corner lies nearer than the near plane,
    /// beyond the far plane or past the guard band (guard_band_px)
    WorkCount clipping;
    WorkCount culling; ///< triangles skipped because their back faces the camera
    WorkCount depth;   ///< depth stage: the triangles, spans and pixels it tested
    WorkCount hidden;  ///< pixels that failed the depth test (spans with any)
    WorkCount raster;  ///< coverage: the triangles, spans and pixels drawn
    WorkCount flat;    ///< pixels written with the mesh's flat colour
    WorkCount colour;  ///< vertex colours interpolated and applied
    WorkCount colour_perspective; ///< of those, perspective-correct (c/w over 1/w)
    WorkCount texture;            ///< texture coordinates computed and texels sampled
    WorkCount auto_choice;        ///< spans whose mapper `auto` chose, and its divides
    std::array<WorkCount, 5> mappers; ///< per MapperKind (index = the enum's value)
    WorkCount filter; ///< pixels filtered (any filter but nearest), 3 divides each
    /// Lighting per pixel (Phong): the triangles, spans and pixels lit, and one divide
    /// per pixel, 1/w (the reciprocal square roots of normalising are not counted)
    WorkCount lighting;
    long long lit_vertices = 0; ///< corners lit per vertex (Gouraud), in the geometry
    bool lighting_on = false;   ///< whether the scene has lights (the stage ran)
    int lights = 0;             ///< how many
    int phong_meshes = 0;       ///< meshes lit per pixel
    int gouraud_meshes = 0;     ///< meshes lit per vertex
    /// Triangles per filter the filter stage ran: bilinear, trilinear, anisotropic.
    std::array<long long, 3> filter_triangles{};
    int mip_chains = 0;    ///< mip chains built (one per texture that needed one)
    double seconds = 0.0;  ///< the whole render
    bool depth_on = false; ///< whether the depth stage ran
    double colour_bound =
        0.0; ///< largest screen-colour error bound, levels (colour meshes)
    std::string depth_reason; ///< why it ran or not (plan_depth)

    /// Every divide performed: the mappers', auto's, the perspective colours', the
    /// filter stage's and per-pixel lighting's.
    long long divides() const;
};

/// The report as a table: one line per stage and per mapper that ran.
std::string format_report(const RenderReport& report);

/// The clock the stages are timed with.
using Clock = std::chrono::steady_clock;

/// Seconds from `start` to now.
inline double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// About this many triangles of each mesh have their stages timed span by span (every
/// triangle of a smaller mesh): reading the clock costs more than shading a small span,
/// and 512 evenly spread triangles split a mesh's time among its stages as well.
inline constexpr std::size_t timed_triangles_per_mesh = 512;

/// Which triangles of a mesh of `count` are timed: one in every this many.
inline std::size_t timed_triangle_interval(std::size_t count) {
    return std::max<std::size_t>(1, count / timed_triangles_per_mesh);
}

/// The one place the drawing stages are timed (as clox keeps its tracing in one block):
/// on a triangle its mesh samples (timed_triangles_per_mesh) it reads the clock around
/// each stage call and adds the time to the stage's seconds and to the triangle's
/// shading time; on every other triangle it only calls the stage.
struct StageTimer {
    bool on = true;       ///< whether this triangle is one of the timed ones
    double shading = 0.0; ///< seconds its stages took (the rest is coverage's)
    /// The time now, or a dummy when off.
    Clock::time_point now() const { return on ? Clock::now() : Clock::time_point{}; }
    /// Seconds since `start`, or 0 when off.
    double since(Clock::time_point start) const {
        return on ? seconds_since(start) : 0.0;
    }
    /// Calls stage() and returns what it returns; when on, adds its time to `seconds`.
    /// (One call of stage(): the compiler inlines it.)
    template <class Stage> auto timed(double& seconds, Stage&& stage) {
        const Clock::time_point start = now();
        const auto result = stage();
        if (on) {
            const double spent = seconds_since(start);
            seconds += spent;
            shading += spent;
        }
        return result;
    }
};

/// Splits `spent`, the time of drawing one mesh, among the drawing stages in the
/// proportions of the seconds the timed triangles added to them since `before`.
void share_drawing_time(RenderReport& report, const RenderReport& before, double spent);

} // namespace exactpixels
