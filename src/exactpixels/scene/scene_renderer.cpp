#include "exactpixels/scene/scene_renderer.hpp"

#include "exactpixels/base/error.hpp"
#include "exactpixels/fast/worker_pool.hpp"
#include "exactpixels/raster/fill_work.hpp"
#include "exactpixels/scene/depth_buffer.hpp"
#include "exactpixels/scene/render_report.hpp"
#include "exactpixels/scene/scene_pipeline.hpp"
#include "exactpixels/scene/span_stages.hpp"
#include "exactpixels/texture/mipmap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <numeric>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace exactpixels {

namespace {

/// The triangle counts of the meshes of `geometry`.
std::vector<std::size_t> triangle_counts(const SceneGeometry& geometry) {
    std::vector<std::size_t> counts;
    for (const std::vector<ScreenTriangle>& mesh : geometry.meshes) {
        counts.push_back(mesh.size());
    }
    return counts;
}

/// fill_work(geometry, image) on `threads` threads: each thread sums its stretch of the
/// triangles per mesh, and the sums of whole numbers are added.
std::vector<long long> fill_work_threaded(const SceneGeometry& geometry, Viewport image,
                                          int threads) {
    const std::vector<std::size_t> counts = triangle_counts(geometry);
    std::vector<std::vector<long long>> sums(static_cast<std::size_t>(threads),
                                             std::vector<long long>(counts.size()));
    run_on_shared_pool(threads, [&](int t) {
        for_thread_stretch(counts, t, threads,
                           [&](std::size_t i, std::size_t first, std::size_t end) {
                               long long& sum = sums[static_cast<std::size_t>(t)][i];
                               for (std::size_t k = first; k < end; ++k) {
                                   const auto& c = geometry.meshes[i][k].corners;
                                   sum += fill_work({c[0].position, c[1].position,
                                                     c[2].position},
                                                    image);
                               }
                           });
    });
    std::vector<long long> work(counts.size());
    for (const std::vector<long long>& thread_sums : sums) {
        for (std::size_t i = 0; i < work.size(); ++i) {
            work[i] += thread_sums[i];
        }
    }
    return work;
}

/// Refuses, before anything is drawn, a scene whose triangles ask for more than
/// max_fill_work pixels of drawing, naming the mesh that takes the sum past it.
void check_fill_work(const Scene& scene, const SceneGeometry& geometry, int threads) {
    const Viewport image{scene.width, scene.height};
    const std::vector<long long> work = threads > 1
                                            ? fill_work_threaded(geometry, image, threads)
                                            : fill_work(geometry, image);
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

/// Whether mesh i's vertex colours are interpolated perspective-correct: the scene asks
/// for it, or `auto` and the screen path's bound exceeds the budget. The largest bound
/// goes into the report.
bool colour_corrected(const Scene& scene, const SceneGeometry& geometry, std::size_t i,
                      RenderReport& report) {
    bool corrected = scene.options.colours == ColourInterpolation::perspective;
    if (mesh_stages(scene, scene.meshes[i]).colour) { // the screen path's bound
        const std::vector<ScreenTriangle>& triangles = geometry.meshes[i];
        for (std::size_t k = 0; k < triangles.size(); ++k) {
            const ScreenTriangle& t = triangles[k];
            const double bound =
                colour_error_bound({t.corners[0].w, t.corners[1].w, t.corners[2].w},
                                   geometry.shading[i][k].colours);
            report.colour_bound = std::max(report.colour_bound, bound);
            corrected =
                corrected || (scene.options.colours == ColourInterpolation::automatic &&
                              bound > scene.options.budget);
        }
    }
    return corrected;
}

/// What every mesh's MeshContext is made from: the frame and what the meshes share.
struct Frame {
    const Scene& scene;
    const SceneGeometry& geometry;
    Framebuffer& image;
    TexelMap* coordinates;
    DepthBuffer* depth;
    std::vector<MipChain>& chains; ///< per texture, filled on demand
    FastPaths fast;
};

/// Mesh i's context, counting into `report` (its full_chain is the caller's to set).
MeshContext mesh_context(const Frame& f, std::size_t i, RenderReport& report,
                         bool corrected) {
    const Scene& scene = f.scene;
    const SceneMesh& mesh = scene.meshes[i];
    const bool lit = !scene.lights.empty();
    MeshContext m{scene,
                  mesh,
                  mesh_stages(scene, mesh),
                  mesh.texture ? &scene.textures[*mesh.texture].texture : nullptr,
                  f.image,
                  f.coordinates,
                  report,
                  f.depth,
                  corrected,
                  {},
                  {},
                  mesh.texture ? &f.chains[*mesh.texture] : nullptr,
                  nullptr,
                  lit && mesh_shading(scene, mesh) == Shading::phong ? &f.geometry.lights
                                                                     : nullptr,
                  Material{mesh.specular, mesh.shininess},
                  to_rgba8(mesh.colour),
                  true};
    m.masked_fetch = f.fast.masked_fetch && m.texture != nullptr &&
                     can_fetch_masked(*m.texture, mesh.wrap);
    m.lanes = f.fast.exact_lanes ? chosen_simd() : SimdVariant::portable;
    return m;
}

/// The rows of one band of the threaded driver. 64: the covered bits of a TexelMap (a
/// std::vector<bool>, in 64-bit words) of 64 rows fill whole words, so two bands never
/// write one word.
constexpr int band_rows = 64;

/// One triangle in a band's bin.
struct Binned {
    std::uint32_t mesh = 0;     ///< its mesh
    std::uint32_t triangle = 0; ///< its index in the mesh's triangles
    bool owned = false;  ///< the first band it is in: it counts the per-triangle counts
    bool shared = false; ///< it is in more than one band
};

/// Per band of band_rows rows, its triangles in scene order.
using Bins = std::vector<std::vector<Binned>>;

/// Bins triangles `from` .. `to` - 1 of mesh i into `bins` (see bin_by_rows).
void bin_triangles(const SceneGeometry& geometry, int height, std::size_t i,
                   std::size_t from, std::size_t to, Bins& bins) {
    const double last_row = height - 1;
    const std::vector<ScreenTriangle>& triangles = geometry.meshes[i];
    for (std::size_t k = from; k < to; ++k) {
        const std::array<TexturedVertex, 3>& c = triangles[k].corners;
        const double top = std::min({c[0].position.y, c[1].position.y, c[2].position.y});
        const double bottom =
            std::max({c[0].position.y, c[1].position.y, c[2].position.y});
        // Rows clamped to the image before they are floored: the same rows (the bounds
        // are whole), and a value in [0, last_row] converts to int by truncation, which
        // is its floor.
        const int first = static_cast<int>(std::clamp(top - 0.5 - 1.0 / 256.0, 0.0,
                                                      last_row)) /
                          band_rows;
        const int last = static_cast<int>(std::clamp(bottom - 0.5 + 1.0 / 256.0, 0.0,
                                                     last_row)) /
                         band_rows;
        for (int b = first; b <= last; ++b) {
            bins[static_cast<std::size_t>(b)].push_back(
                {static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(k),
                 b == first, last > first});
        }
    }
}

/// The bins: per band of band_rows rows, the triangles that may cover a pixel centre in
/// it, in scene order. Row y's centre y + 1/2 lies between the snapped corners' top and
/// bottom, each within 1/512 px of the corner: y from floor(top - 1/2 - 1/256) to
/// floor(bottom - 1/2 + 1/256). A triangle below or above the image goes to the last
/// or first band. Thread t of `threads` bins its stretch of the triangles in scene order
/// (for_thread_stretch) into bins of its own, bins[t][band].
std::vector<Bins> bin_by_rows(const SceneGeometry& geometry, int height, int threads) {
    std::vector<Bins> bins(static_cast<std::size_t>(threads),
                           Bins(static_cast<std::size_t>((height + band_rows - 1) /
                                                         band_rows)));
    const std::vector<std::size_t> counts = triangle_counts(geometry);
    run_on_shared_pool(threads, [&](int thread) {
        for_thread_stretch(counts, thread, threads,
                           [&](std::size_t i, std::size_t first, std::size_t end) {
                               bin_triangles(geometry, height, i, first, end,
                                             bins[static_cast<std::size_t>(thread)]);
                           });
    });
    return bins;
}

/// Per mesh, the index of its first triangle in the scene's list of all triangles, mesh
/// after mesh; then the number of all.
std::vector<std::size_t> first_triangles(const SceneGeometry& geometry) {
    std::vector<std::size_t> first{0};
    for (const std::vector<ScreenTriangle>& mesh : geometry.meshes) {
        first.push_back(first.back() + mesh.size());
    }
    return first;
}

/// Triangle (mesh, triangle) as its index in the scene's list of all triangles, mesh
/// after mesh (so in scene order), `first` as first_triangles gives it.
std::size_t scene_index(const std::vector<std::size_t>& first, const Binned& b) {
    return first[b.mesh] + b.triangle;
}

/// What a band drew: its counts, the mappers each of its shared triangles used there
/// (scene_index, bit k: MapperKind k), counted once per triangle after the bands, and
/// its first error.
struct BandResult {
    RenderReport report;
    std::vector<std::pair<std::size_t, unsigned>> shared_mappers;
    std::size_t error_at = ~std::size_t{0}; ///< scene_index of the failing triangle
    std::string error;                          ///< its message, as render_scene's
};

/// One mesh's triangles `part` of a band, as draw_mesh draws them; `first` as
/// scene_index's. False after an error.
bool draw_band_part(MeshContext& m, const Frame& f, const std::vector<std::size_t>& first,
                    std::span<const Binned> part, BandResult& out) {
    const std::size_t i = part.front().mesh;
    const bool direct = draws_direct(m, f.fast.lean_spans);
    m.visible.resize(static_cast<std::size_t>(f.image.width()));
    const RenderReport before = out.report;
    const Clock::time_point t0 = Clock::now();
    // The triangles draw_mesh times: the sample is the mesh's, not the band's (sampled
    // per band, the big torus's twelve bands read the clock twelve times as often: 8 %
    // of the frame's time, perf).
    const std::size_t interval = timed_triangle_interval(f.geometry.meshes[i].size());
    for (const Binned& b : part) {
        m.timed = b.triangle % interval == 0;
        m.counts_triangle = b.owned;
        const std::vector<ShadedCorners>& shading = f.geometry.shading[i];
        std::array<long long, 5> used{};
        for (std::size_t kind = 0; kind < used.size(); ++kind) {
            used[kind] = out.report.mappers[kind].triangles;
        }
        try {
            draw_one_triangle(m, f.geometry.meshes[i][b.triangle],
                              shading.empty() ? nullptr : &shading[b.triangle], direct);
        } catch (const Error& error) {
            out.error_at = scene_index(first, b);
            out.error = fmt::format("{}: {}", m.mesh.origin, error.what());
            return false;
        }
        if (b.shared) { // counted once per triangle after the bands
            unsigned mask = 0;
            for (std::size_t kind = 0; kind < used.size(); ++kind) {
                WorkCount& counter = out.report.mappers[kind];
                mask |= counter.triangles != used[kind] ? 1U << kind : 0U;
                counter.triangles = used[kind];
            }
            out.shared_mappers.emplace_back(scene_index(first, b), mask);
        }
    }
    share_drawing_time(out.report, before, seconds_since(t0));
    return true;
}

/// Draws band `band`'s bin mesh by mesh; `whole` says which textures' chains are whole,
/// `first` as scene_index's.
BandResult draw_band(const Frame& f, const std::vector<char>& corrected, bool* whole,
                     const std::vector<std::size_t>& first, std::span<const Binned> bin,
                     int band) {
    BandResult out;
    bool no_chain = false;
    for (std::size_t at = 0, end = 0; at < bin.size(); at = end) {
        end = at;
        while (end < bin.size() && bin[end].mesh == bin[at].mesh) {
            ++end;
        }
        const std::size_t i = bin[at].mesh;
        MeshContext m = mesh_context(f, i, out.report, corrected[i] != 0);
        const std::optional<std::size_t> texture = f.scene.meshes[i].texture;
        m.full_chain = texture ? &whole[*texture] : &no_chain;
        m.first_row = band * band_rows;
        m.end_row = m.first_row + band_rows;
        if (!draw_band_part(m, f, first, bin.subspan(at, end - at), out)) {
            break;
        }
    }
    return out;
}

/// Adds the drawing stages' counts and times of `part` to `report`.
void add_drawing(RenderReport& report, const RenderReport& part) {
    const auto add = [](WorkCount& a, const WorkCount& b) {
        a.triangles += b.triangles;
        a.spans += b.spans;
        a.pixels += b.pixels;
        a.divides += b.divides;
        a.seconds += b.seconds;
    };
    for (auto stage :
         {&RenderReport::depth, &RenderReport::hidden, &RenderReport::raster,
          &RenderReport::flat, &RenderReport::colour, &RenderReport::colour_perspective,
          &RenderReport::texture, &RenderReport::auto_choice, &RenderReport::filter,
          &RenderReport::lighting}) {
        add(report.*stage, part.*stage);
    }
    for (std::size_t k = 0; k < report.mappers.size(); ++k) {
        add(report.mappers[k], part.mappers[k]);
    }
    for (std::size_t k = 0; k < report.filter_triangles.size(); ++k) {
        report.filter_triangles[k] += part.filter_triangles[k];
    }
    report.mip_chains += part.mip_chains;
}

/// The bands' results into `report` in band order; the mappers of a triangle in several
/// bands counted once (`triangles`: how many the scene has); the first error in scene
/// order thrown.
void merge_bands(const std::vector<BandResult>& bands, std::size_t triangles,
                 RenderReport& report) {
    const auto first_error = std::min_element(
        bands.begin(), bands.end(),
        [](const BandResult& a, const BandResult& b) { return a.error_at < b.error_at; });
    if (first_error != bands.end() && !first_error->error.empty()) {
        throw Error(first_error->error);
    }
    std::vector<unsigned char> used(triangles); // per triangle: the mappers counted
    for (const BandResult& band : bands) {
        add_drawing(report, band.report);
        for (const auto& [triangle, mask] : band.shared_mappers) {
            const unsigned fresh = mask & ~unsigned{used[triangle]}; // not yet counted
            used[triangle] = static_cast<unsigned char>(used[triangle] | mask);
            for (std::size_t kind = 0; kind < report.mappers.size(); ++kind) {
                report.mappers[kind].triangles += (fresh >> kind) & 1U;
            }
        }
    }
}

//> draw-threaded
/// The threaded driver (FastPaths::threads > 1): the chains the filter stage will read
/// made first, in scene order; each thread bins its share of the triangles into bands of
/// rows (bin_by_rows); the threads take the bands one at a time, the fullest first,
/// join each band's parts in thread order and draw its triangles in scene order, their
/// spans in its rows only; the bands' counts added in band order. Returns
/// false, having drawn nothing, when making a chain meets a bad triangle: the book's
/// loop then finds the first error in scene order.
bool draw_threaded(const Frame& f, RenderReport& report) {
    const std::size_t meshes = f.scene.meshes.size();
    std::vector<char> corrected(meshes);
    std::unique_ptr<bool[]> whole(new bool[f.scene.textures.size() + 1]());
    for (std::size_t i = 0; i < meshes; ++i) {
        corrected[i] = colour_corrected(f.scene, f.geometry, i, report);
        MeshContext m = mesh_context(f, i, report, corrected[i] != 0);
        m.full_chain = m.texture != nullptr ? &whole[*m.mesh.texture] : nullptr;
        try {
            if (m.full_chain != nullptr && m.stages.texture &&
                f.scene.options.filter != SceneFilter::nearest) {
                prepare_mesh_chain(m, f.geometry.meshes[i]); // before any thread reads it
            }
        } catch (const Error&) {
            return false;
        }
    }
    const std::vector<Bins> parts = // per thread
        bin_by_rows(f.geometry, f.image.height(), f.fast.threads);
    std::vector<std::size_t> sizes(parts[0].size()); // per band
    for (std::size_t b = 0; b < sizes.size(); ++b) {
        for (const Bins& part : parts) {
            sizes[b] += part[b].size();
        }
    }
    std::vector<std::size_t> fullest(sizes.size()); // taken fullest first: they even out
    std::iota(fullest.begin(), fullest.end(), std::size_t{0});
    std::stable_sort(fullest.begin(), fullest.end(),
                     [&](std::size_t a, std::size_t b) { return sizes[a] > sizes[b]; });
    const std::vector<std::size_t> first = first_triangles(f.geometry); // scene_index's
    std::vector<BandResult> bands(sizes.size());
    std::atomic<std::size_t> next{0};
    const std::function<void(int)> take_bands = [&](int) {
        for (std::size_t n = next++; n < sizes.size(); n = next++) {
            const std::size_t b = fullest[n];
            std::vector<Binned> bin; // the threads' parts in order: scene order
            bin.reserve(sizes[b]);
            for (const Bins& part : parts) {
                bin.insert(bin.end(), part[b].begin(), part[b].end());
            }
            bands[b] = draw_band(f, corrected, whole.get(), first, bin,
                                 static_cast<int>(b));
        }
    };
    run_on_shared_pool(f.fast.threads, take_bands); // threads kept from frame to frame
    merge_bands(bands, first.back(), report);
    return true;
}
//< draw-threaded

} // namespace

void check_thread_count(int threads) {
    if (threads < 1 || threads > max_threads) {
        throw Error(
            fmt::format("thread count {} is outside 1 .. {}", threads, max_threads));
    }
}

RenderResult render_scene(const Scene& scene, TexelMap* coordinates, FastPaths fast) {
    check_thread_count(fast.threads); // before any work
    const Clock::time_point start = Clock::now();
    RenderResult result{
        Framebuffer(scene.width, scene.height, to_rgba8(scene.background)), {}};
    RenderReport& report = result.report;
    const SceneGeometry geometry =
        run_geometry(scene, report, fast.threads, fast.lean_geometry);
    check_fill_work(scene, geometry, fast.threads); // before the first pixel is drawn
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
    const Frame frame{
        scene,  geometry, result.image, coordinates, depth ? &*depth : nullptr,
        chains, fast};
    if (fast.threads > 1 && draw_threaded(frame, report)) {
        report.seconds = seconds_since(start);
        return result;
    }
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) { // the book's loop
        const SceneMesh& mesh = scene.meshes[i];
        MeshContext m =
            mesh_context(frame, i, report, colour_corrected(scene, geometry, i, report));
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
