#include "exactpixels/scene/scene_renderer.hpp"

#include "exactpixels/base/error.hpp"
#include "exactpixels/raster/fill_work.hpp"
#include "exactpixels/scene/depth_buffer.hpp"
#include "exactpixels/scene/render_report.hpp"
#include "exactpixels/scene/scene_pipeline.hpp"
#include "exactpixels/scene/span_stages.hpp"
#include "exactpixels/texture/mipmap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <vector>

namespace exactpixels {

namespace {

/// Refuses, before anything is drawn, a scene whose triangles ask for more than
/// max_fill_work pixels of drawing, naming the mesh that takes the sum past it.
void check_fill_work(const Scene& scene, const SceneGeometry& geometry) {
    const std::vector<long long> work =
        fill_work(geometry, Viewport{scene.width, scene.height});
    long long sum = 0;
    for (std::size_t i = 0; i < work.size(); ++i) {
        sum += work[i];
        if (sum > max_fill_work) {
            throw Error(fmt::format(
                "{}: the triangles up to this mesh ask for {} pixels of drawing (their "
                "bounding boxes in the image), more than the {} allowed",
                scene.meshes[i].origin, sum, max_fill_work));
        }
    }
}

} // namespace

RenderResult render_scene(const Scene& scene, TexelMap* coordinates, FastPaths fast) {
    const Clock::time_point start = Clock::now();
    RenderResult result{
        Framebuffer(scene.width, scene.height, to_rgba8(scene.background)), {}};
    RenderReport& report = result.report;
    const bool lit = !scene.lights.empty();
    const SceneGeometry geometry = run_geometry(scene, report);
    check_fill_work(scene, geometry); // before the first pixel is drawn
    const DepthPlan depth_plan = plan_depth(scene.options.depth, geometry.footprints,
                                            Viewport{scene.width, scene.height});
    report.depth_on = depth_plan.on;
    report.depth_reason = depth_plan.reason;
    std::vector<MipChain> chains(scene.textures.size()); // filled on demand
    std::vector<bool> full_chains(scene.textures.size(), false);
    std::optional<DepthBuffer> depth;
    if (depth_plan.on) {
        depth.emplace(scene.width, scene.height);
    }
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const SceneMesh& mesh = scene.meshes[i];
        bool corrected = scene.options.colours == ColourInterpolation::perspective;
        if (mesh_stages(scene, mesh).colour) { // the screen path's bound, vs the budget
            const std::vector<ScreenTriangle>& triangles = geometry.meshes[i];
            for (std::size_t k = 0; k < triangles.size(); ++k) {
                const ScreenTriangle& t = triangles[k];
                const double bound =
                    colour_error_bound({t.corners[0].w, t.corners[1].w, t.corners[2].w},
                                       geometry.shading[i][k].colours);
                report.colour_bound = std::max(report.colour_bound, bound);
                corrected = corrected ||
                            (scene.options.colours == ColourInterpolation::automatic &&
                             bound > scene.options.budget);
            }
        }
        MeshContext m{scene,
                      mesh,
                      mesh_stages(scene, mesh),
                      mesh.texture ? &scene.textures[*mesh.texture].texture : nullptr,
                      result.image,
                      coordinates,
                      report,
                      depth ? &*depth : nullptr,
                      corrected,
                      {},
                      {},
                      mesh.texture ? &chains[*mesh.texture] : nullptr,
                      nullptr,
                      lit && mesh_shading(scene, mesh) == Shading::phong
                          ? &geometry.lights
                          : nullptr,
                      Material{mesh.specular, mesh.shininess},
                      to_rgba8(mesh.colour),
                      true};
        m.masked_fetch = fast.masked_fetch && m.texture != nullptr &&
                         can_fetch_masked(*m.texture, mesh.wrap);
        m.lanes = fast.exact_lanes ? chosen_simd() : SimdVariant::portable;
        bool full_chain = mesh.texture && full_chains[*mesh.texture];
        m.full_chain = &full_chain;
        try {
            draw_mesh(m, geometry.meshes[i], geometry.shading[i], fast.lean_spans);
            if (mesh.texture) {
                full_chains[*mesh.texture] = full_chain;
            }
        } catch (const Error& error) {
            throw Error(fmt::format("{}: {}", mesh.origin, error.what()));
        }
    }
    report.seconds = seconds_since(start);
    return result;
}

TexelError check_against_exact(Scene scene) {
    TexelMap map(scene.width, scene.height), reference(scene.width, scene.height);
    render_scene(scene, &map);
    scene.options.mapper = {false, {MapperKind::exact}};
    scene.options.precision = Precision::float64;
    render_scene(scene, &reference);
    return compare_texel_maps(reference, map);
}

} // namespace exactpixels
