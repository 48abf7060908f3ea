// span_stages.hpp: drawing one mesh's triangles, span by span: coverage (chapter 1's
// scanline rasterizer), then the stages the mesh calls for on each span (depth, texture,
// filter, colour, lighting), counted into the render report.
//
// Usage (render_scene, once per mesh):
//   MeshContext m{scene, mesh, mesh_stages(scene, mesh), texture, frame, ...};
//   draw_mesh(m, geometry.meshes[i], geometry.shading[i], fast.lean_spans);
#pragma once

#include "exactpixels/base/framebuffer.hpp"
#include "exactpixels/fast/simd.hpp"
#include "exactpixels/scene/depth_buffer.hpp"
#include "exactpixels/scene/lighting.hpp"
#include "exactpixels/scene/render_report.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "exactpixels/texture/mipmap.hpp"

#include <limits>
#include <vector>

namespace exactpixels {

/// Everything the per-triangle code needs about the mesh and the frame.
struct MeshContext {
    const Scene& scene;        ///< the scene being drawn
    const SceneMesh& mesh;     ///< the mesh being drawn
    MeshStages stages;         ///< its stages (mesh_stages)
    const Texture* texture;    ///< its texture, or nullptr
    Framebuffer& frame;        ///< the image drawn into
    TexelMap* coordinates;     ///< where texel coordinates are recorded, or nullptr
    RenderReport& report;      ///< the counts and times of the render
    DepthBuffer* depth;        ///< the depth stage's buffer, or nullptr when it is off
    bool colour_perspective;   ///< colours as c/w over 1/w (else linear on screen)
    std::vector<Rgba8> row;    ///< one span of shaded pixels
    std::vector<char> visible; ///< depth stage: which pixels of the span passed the test
    MipChain* chain;           ///< filter stage: the texture in linear light, or nullptr
    bool* full_chain;          ///< filter stage: whether *chain has all its levels
    const std::vector<ViewLight>* lights; ///< lighting stage per pixel, or nullptr
    Material material;                    ///< the mesh's specular colour and exponent
    Rgba8 flat;                           ///< the mesh's colour, as written
    bool timed = true; ///< whether the triangle being drawn is one of the sampled ones
    bool masked_fetch = false; ///< FastPaths::masked_fetch, and the texture allows it
    /// FastPaths::exact_lanes: the exact mapper's instruction set (portable: plain loop)
    SimdVariant lanes = SimdVariant::portable;
    /// The first row drawn: 0, except in a band of the threaded driver
    /// (scene_renderer.cpp), which draws only the spans in its own rows.
    int first_row = 0;
    /// The row after the last drawn: all of them, except in a band.
    int end_row = std::numeric_limits<int>::max();
    /// Whether the triangle being drawn is counted into the per-triangle counts: always,
    /// except in the bands of the threaded driver that share it with a band above.
    bool counts_triangle = true;
};

/// Draws `triangles`, one mesh's, with their ShadedCorners `shading` (one per triangle
/// where the mesh has a colour or lighting stage, else none), in order with the stages of
/// `m` (each visible pixel straight to the frame where `lean_spans` and the mesh allow
/// it), times the whole and shares the time among the stages as the sampled triangles
/// spent it (share_drawing_time). Throws Error when a triangle leaves the rasterizer's or
/// the mapper's exact range.
void draw_mesh(MeshContext& m, const std::vector<ScreenTriangle>& triangles,
               const std::vector<ShadedCorners>& shading, bool lean_spans);

/// Whether draw_mesh draws the mesh of `m` through the direct span (lean_spans on, and
/// the mesh's stages allow it).
bool draws_direct(const MeshContext& m, bool lean_spans);

/// One triangle as draw_mesh draws each (the direct span where `direct`), with its
/// ShadedCorners or nullptr: the threaded driver's step. Throws as draw_mesh does.
void draw_one_triangle(MeshContext& m, const ScreenTriangle& triangle,
                       const ShadedCorners* shading, bool direct);

/// Makes the chain of a mesh with a filter stage what drawing `triangles` in order
/// leaves it (prepare_filter on each, until the chain is whole), so that the threaded
/// driver's bands only read it. Throws as draw_mesh does for a bad triangle.
void prepare_mesh_chain(MeshContext& m, const std::vector<ScreenTriangle>& triangles);

} // namespace exactpixels
