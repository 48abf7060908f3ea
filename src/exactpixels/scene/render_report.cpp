#include "exactpixels/scene/render_report.hpp"

#include "exactpixels/texture/texture_mapper.hpp"

#include <fmt/format.h>

namespace exactpixels {

long long RenderReport::divides() const {
    long long total = auto_choice.divides + colour_perspective.divides + filter.divides +
                      lighting.divides;
    for (const WorkCount& m : mappers) {
        total += m.divides;
    }
    return total;
}

void share_drawing_time(RenderReport& report, const RenderReport& before, double spent) {
    double sampled = 0.0; // texture's seconds hold its mappers': not again
    for (const auto stage :
         {&RenderReport::depth, &RenderReport::raster, &RenderReport::colour,
          &RenderReport::texture, &RenderReport::filter, &RenderReport::lighting}) {
        sampled += (report.*stage).seconds - (before.*stage).seconds;
    }
    const double scale = sampled > 0.0 ? spent / sampled : 0.0;
    const auto rescale = [&](WorkCount& now, const WorkCount& then) {
        now.seconds = then.seconds + scale * (now.seconds - then.seconds);
    };
    for (const auto stage :
         {&RenderReport::depth, &RenderReport::raster, &RenderReport::colour,
          &RenderReport::texture, &RenderReport::filter, &RenderReport::lighting}) {
        rescale(report.*stage, before.*stage);
    }
    for (std::size_t k = 0; k < report.mappers.size(); ++k) {
        rescale(report.mappers[k], before.mappers[k]);
    }
}

std::string format_report(const RenderReport& r) {
    std::string out = fmt::format("{:<18} {:>10} {:>8} {:>10} {:>10} {:>10}\n", "stage",
                                  "triangles", "spans", "pixels", "divides", "ms");
    const auto line = [&](const std::string& name, const WorkCount& c, bool always) {
        if (always || c.triangles > 0 || c.spans > 0) {
            out +=
                fmt::format("{:<18} {:>10} {:>8} {:>10} {:>10} {:>10.3f}\n", name,
                            c.triangles, c.spans, c.pixels, c.divides, 1e3 * c.seconds);
        }
    };
    line("geometry", r.geometry, true);
    line("rejected", r.rejected, false);
    line("clipping", r.clipping, true);
    line("culling", r.culling, false);
    line("depth", r.depth, false);
    line("  hidden", r.hidden, false);
    line("raster", r.raster, true);
    line("flat colour", r.flat, true);
    line("vertex colour", r.colour, true);
    line("  perspective", r.colour_perspective, false);
    line("texture", r.texture, true);
    line("auto choice", r.auto_choice, false);
    for (std::size_t k = 0; k < r.mappers.size(); ++k) {
        line(fmt::format("  mapper {}", mapper_kind_name(static_cast<MapperKind>(k))),
             r.mappers[k], false);
    }
    line("filter", r.filter, false);
    line("lighting", r.lighting, false);
    if (r.filter.triangles > 0) {
        out += fmt::format("filter stage: {} bilinear, {} trilinear, {} anisotropic "
                           "triangles; {} mip chains built\n",
                           r.filter_triangles[0], r.filter_triangles[1],
                           r.filter_triangles[2], r.mip_chains);
    }
    out +=
        fmt::format("depth stage: {} ({})\n", r.depth_on ? "on" : "off", r.depth_reason);
    if (r.lighting_on) {
        out += fmt::format("lighting stage: on ({} light{}; phong {} mesh{}, gouraud {} "
                           "mesh{}); {} corners lit per vertex\n",
                           r.lights, r.lights == 1 ? "" : "s", r.phong_meshes,
                           r.phong_meshes == 1 ? "" : "es", r.gouraud_meshes,
                           r.gouraud_meshes == 1 ? "" : "es", r.lit_vertices);
    } else {
        out += "lighting stage: off (no [[light]])\n";
    }
    out += fmt::format("total: {} divides, {:.3f} ms\n", r.divides(), 1e3 * r.seconds);
    return out;
}

} // namespace exactpixels
