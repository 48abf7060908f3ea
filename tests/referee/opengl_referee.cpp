// opengl_referee.cpp: see opengl_referee.hpp.
#include "referee/opengl_referee.hpp"

#include "exactpixels/base/error.hpp"
#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"
#include "exactpixels/raster/scanline.hpp"
#include "exactpixels/raster/screen_plane.hpp"
#include "exactpixels/scene/depth_buffer.hpp"
#include "exactpixels/scene/lighting.hpp"
#include "exactpixels/scene/scene_loader.hpp"
#include "exactpixels/scene/scene_pipeline.hpp"
#include "exactpixels/scene/scene_renderer.hpp"
#include "exactpixels/texture/texture_mapper.hpp"

#include <GL/osmesa.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <random>

namespace exactpixels {

namespace {

/// One OSMesa context for the whole program, made on first use.
struct Context {
    OSMesaContext context = nullptr;
    std::string problem; ///< why there is none
};

Context& context() {
    static Context c = [] {
        Context made;
        made.context = OSMesaCreateContextExt(OSMESA_RGBA, 32, 0, 0, nullptr);
        if (made.context == nullptr) {
            made.problem = "OSMesaCreateContextExt failed (no software OpenGL)";
        }
        return made;
    }();
    return c;
}

/// The triangle index that wins each pixel (-1: background), drawn as the renderer
/// draws: scanline_spans on the snapped corners, the nearness plane through them,
/// DepthBuffer's test when the depth stage runs.
std::vector<long long> our_ids(const SceneGeometry& geometry, int width, int height,
                               bool depth_on) {
    std::vector<long long> ids(static_cast<std::size_t>(width) * height, -1);
    std::optional<DepthBuffer> depth;
    if (depth_on) {
        depth.emplace(width, height);
    }
    long long index = 0;
    for (const auto& mesh : geometry.meshes) {
        for (const ScreenTriangle& t : mesh) {
            std::array<FixedPoint2, 3> snapped{};
            std::array<Point2, 3> p{};
            for (std::size_t k = 0; k < 3; ++k) {
                snapped[k] = snap_in_range(t.corners[k].position);
                p[k] = to_pixels(snapped[k]);
            }
            const ScreenPlane nearness = plane_through(p, t.nearness);
            scanline_spans(snapped, Viewport{width, height}, [&](Span s) {
                const double x = s.x_begin + 0.5, y = s.y + 0.5;
                for (int k = 0; k < s.x_end - s.x_begin; ++k) {
                    if (depth &&
                        !depth->test_and_write(s.x_begin + k, s.y,
                                               nearness_key(nearness.at(x + k, y)))) {
                        continue;
                    }
                    ids[static_cast<std::size_t>(s.y) * width + s.x_begin + k] = index;
                }
            });
            ++index;
        }
    }
    return ids;
}

/// The pixels the exact edge-function rasterizer (integer edge functions on the same
/// snapped corners) covers with any triangle.
std::vector<bool> exact_coverage(const SceneGeometry& geometry, int width, int height) {
    std::vector<bool> covered(static_cast<std::size_t>(width) * height, false);
    for (const auto& mesh : geometry.meshes) {
        for (const ScreenTriangle& t : mesh) {
            std::array<FixedPoint2, 3> snapped{};
            for (std::size_t k = 0; k < 3; ++k) {
                snapped[k] = snap_in_range(t.corners[k].position);
            }
            edge_rasterize_pixels(snapped, Viewport{width, height}, [&](int x, int y) {
                covered[static_cast<std::size_t>(y) * width + x] = true;
            });
        }
    }
    return covered;
}

/// What GL draws one mesh with in the colour pass.
struct MeshLook {
    bool comparable = true; ///< GL's fixed pipeline draws it as the renderer does
    MeshStages stages;
};

/// Draws every triangle through GL; `id_pass` gives each its index + 1 as a flat
/// colour, else the renderer's colours and nearest texels. Returns the pixels.
std::vector<Rgba8> draw_gl(const Scene& scene, const SceneGeometry& geometry,
                           const std::vector<MeshLook>& looks, bool depth_on,
                           bool id_pass) {
    const int width = scene.width, height = scene.height;
    std::vector<Rgba8> pixels(static_cast<std::size_t>(width) * height);
    if (!OSMesaMakeCurrent(context().context, pixels.data(), GL_UNSIGNED_BYTE, width,
                           height)) {
        throw Error("OSMesaMakeCurrent failed");
    }
    OSMesaPixelStore(OSMESA_Y_UP, 0); // row 0 of the buffer is our row 0, the top
    glViewport(0, 0, width, height);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, width, height, 0, -1, 1); // vertex (x, y) on our pixel (x, y), y down
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glDisable(GL_DITHER);
    glDisable(GL_LIGHTING);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE); // run_geometry has culled already
    const Rgba8 bg = to_rgba8(scene.background);
    if (id_pass) {
        glClearColor(0, 0, 0, 0);
    } else {
        glClearColor(bg.r / 255.0f, bg.g / 255.0f, bg.b / 255.0f, 1.0f);
    }
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (depth_on) {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LEQUAL); // a tie goes to the later triangle, as in DepthBuffer
    } else {
        glDisable(GL_DEPTH_TEST);
    }
    glShadeModel(id_pass ? GL_FLAT : GL_SMOOTH);
    glHint(GL_PERSPECTIVE_CORRECTION_HINT, GL_NICEST);
    // Nearness q (larger = nearer) to window depth 1 - q scaled into [0.05, 0.95]:
    // linear in q, so linear on screen like q; clip z = z_ndc w.
    double q_min = 0.0, q_max = 0.0;
    bool first = true;
    for (const auto& mesh : geometry.meshes) {
        for (const ScreenTriangle& t : mesh) {
            for (const double q : t.nearness) {
                q_min = first ? q : std::min(q_min, q);
                q_max = first ? q : std::max(q_max, q);
                first = false;
            }
        }
    }
    const double q_span = q_max > q_min ? q_max - q_min : 1.0;
    const bool perspective = scene.camera.projection == Projection::perspective;
    std::vector<GLuint> names(scene.textures.size(), 0);
    if (!id_pass && !names.empty()) {
        glGenTextures(static_cast<GLsizei>(names.size()), names.data());
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        for (std::size_t i = 0; i < names.size(); ++i) {
            const Texture& texture = scene.textures[i].texture;
            glBindTexture(GL_TEXTURE_2D, names[i]);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, texture.width(), texture.height(), 0,
                         GL_RGBA, GL_UNSIGNED_BYTE, texture.texels().data());
        }
        glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
    }
    long long index = 0;
    for (std::size_t i = 0; i < geometry.meshes.size(); ++i) {
        const SceneMesh& mesh = scene.meshes[i];
        const MeshStages& stages = looks[i].stages;
        const bool textured = !id_pass && stages.texture;
        if (textured) {
            glEnable(GL_TEXTURE_2D);
            glBindTexture(GL_TEXTURE_2D, names[*mesh.texture]);
            const GLint wrap = mesh.wrap == Wrap::repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE;
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
        } else {
            glDisable(GL_TEXTURE_2D);
        }
        const double tw = textured ? scene.textures[*mesh.texture].texture.width() : 1;
        const double th = textured ? scene.textures[*mesh.texture].texture.height() : 1;
        glBegin(GL_TRIANGLES);
        for (const ScreenTriangle& t : geometry.meshes[i]) {
            ++index;
            if (id_pass) {
                glColor4ub(static_cast<GLubyte>(index & 0xff),
                           static_cast<GLubyte>((index >> 8) & 0xff),
                           static_cast<GLubyte>((index >> 16) & 0xff), 255);
            } else if (!stages.colour) {
                const Colour c =
                    stages.texture && !stages.tint ? Colour{1.0, 1.0, 1.0} : mesh.colour;
                glColor4d(c.r, c.g, c.b, 1.0);
            }
            //> referee-vertex
            for (std::size_t k = 0; k < 3; ++k) {
                const Point2 p = to_pixels(snap_in_range(t.corners[k].position));
                const double w = perspective ? t.corners[k].w : 1.0;
                const double z_ndc = 0.9 - 1.8 * (t.nearness[k] - q_min) / q_span;
                if (!id_pass && stages.colour) {
                    glColor4d(t.colours[k].r, t.colours[k].g, t.colours[k].b, 1.0);
                }
                if (textured) {
                    glTexCoord2d(t.corners[k].uv.x / tw, t.corners[k].uv.y / th);
                }
                // glOrtho's z row is -z: clip z = -z_ndc w gives z_ndc after the divide.
                glVertex4d(p.x * w, p.y * w, -z_ndc * w, w);
            }
            //< referee-vertex
        }
        glEnd();
    }
    glFinish();
    if (!names.empty() && !id_pass) {
        glDeleteTextures(static_cast<GLsizei>(names.size()), names.data());
    }
    if (glGetError() != GL_NO_ERROR) {
        throw Error("OpenGL reported an error drawing the scene");
    }
    return pixels;
}

int channel_difference(Rgba8 a, Rgba8 b) {
    return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

/// The nearness plane of a triangle (through its snapped corners) at pixel (x, y)'s
/// centre, as the renderer's depth stage evaluates it.
double nearness_at(const ScreenTriangle& t, int x, int y) {
    std::array<Point2, 3> p{};
    for (std::size_t k = 0; k < 3; ++k) {
        p[k] = to_pixels(snap_in_range(t.corners[k].position));
    }
    return plane_through(p, t.nearness).at(x + 0.5, y + 0.5);
}

double edge_distance(double u) {
    return std::abs(u - std::round(u));
}

} // namespace

bool opengl_referee_ready(std::string& why) {
    why = context().problem;
    return context().context != nullptr;
}

std::vector<std::string> referee_scene_names() {
    std::vector<std::string> names;
    for (const auto& entry :
         std::filesystem::directory_iterator(shipped_scene_folder())) {
        if (entry.path().extension() == ".toml") {
            names.push_back(entry.path().stem().string());
        }
    }
    std::sort(names.begin(), names.end());
    return names;
}

std::vector<ScreenTriangle> far_reaching_triangles(int count) {
    std::mt19937 random(17);
    const auto uniform = [&](double lo, double hi) {
        return lo + (hi - lo) * static_cast<double>(random()) / 4294967296.0;
    };
    std::vector<ScreenTriangle> triangles;
    for (int n = 0; n < count; ++n) {
        const double reach = std::ldexp(1.0, 10 + n % 10); // 2^10 .. 2^19 px
        ScreenTriangle t{};
        t.corners[0].position = {uniform(0, far_frame), uniform(0, far_frame)};
        t.corners[1].position = {uniform(-reach, reach), uniform(-reach, reach)};
        t.corners[2].position = {uniform(-reach, reach), uniform(-reach, reach)};
        for (auto& corner : t.corners) {
            corner.w = 1.0;
        }
        t.nearness = {1.0, 1.0, 1.0};
        triangles.push_back(t);
    }
    return triangles;
}

CoverageComparison referee_coverage(const std::vector<ScreenTriangle>& triangles,
                                    int width, int height) {
    std::string why;
    if (!opengl_referee_ready(why)) {
        throw Error(why);
    }
    Scene frame;
    frame.width = width;
    frame.height = height;
    frame.camera.projection = Projection::orthographic; // GL gets w = 1
    frame.meshes.resize(1);
    SceneGeometry geometry;
    geometry.meshes.push_back(triangles);
    const std::vector<long long> ids = our_ids(geometry, width, height, false);
    const std::vector<bool> exact = exact_coverage(geometry, width, height);
    const std::vector<Rgba8> gl_ids = draw_gl(frame, geometry, {MeshLook{}}, false, true);
    CoverageComparison c;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t at = static_cast<std::size_t>(y) * width + x;
            const Rgba8 g = gl_ids[at];
            const bool theirs = (g.r | g.g | g.b) != 0;
            const bool ours = ids[at] >= 0;
            c.covered += ours;
            c.exact_differences += ours != exact[at];
            if (ours != theirs) {
                c.differences.push_back({x, y});
                if (ours == exact[at]) {
                    c.ours_exact.push_back({x, y});
                }
            }
        }
    }
    return c;
}

RefereeComparison referee_scene(const Scene& scene, const std::string& name) {
    std::string why;
    if (!opengl_referee_ready(why)) {
        throw Error(why);
    }
    RefereeComparison c;
    c.name = name;
    c.width = scene.width;
    c.height = scene.height;
    RenderResult ours = render_scene(scene);
    c.depth_on = ours.report.depth_on;
    // The colour reference: the same scene with the exact mapper in double precision and
    // colours perspective-correct, as GL interpolates them (chapter 7 measures how far
    // the scene's own mapper and colour choice stray from it: check_against_exact).
    Scene exact_scene = scene;
    exact_scene.options.mapper = {false, {MapperKind::exact}};
    exact_scene.options.precision = Precision::float64;
    exact_scene.options.colours = ColourInterpolation::perspective;
    TexelMap texels(scene.width, scene.height);
    const RenderResult reference = render_scene(exact_scene, &texels);
    RenderReport geometry_report;
    const SceneGeometry geometry = run_geometry(scene, geometry_report);
    std::vector<const ScreenTriangle*> triangles;
    for (const auto& mesh : geometry.meshes) {
        for (const ScreenTriangle& t : mesh) {
            triangles.push_back(&t);
        }
    }
    std::vector<MeshLook> looks(scene.meshes.size());
    std::vector<std::size_t> mesh_of; // per triangle index
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const SceneMesh& mesh = scene.meshes[i];
        looks[i].stages = mesh_stages(scene, mesh); // the renderer's own choice
        const bool lit = !scene.lights.empty();
        if (lit && mesh_shading(scene, mesh) == Shading::phong) {
            looks[i].comparable = false;
            c.uncompared = "per-pixel lighting";
        }
        if (looks[i].stages.texture && scene.options.filter != SceneFilter::nearest) {
            looks[i].comparable = false;
            c.uncompared = "filtered texels";
        }
        mesh_of.insert(mesh_of.end(), geometry.meshes[i].size(), i);
    }
    c.triangles = static_cast<long long>(mesh_of.size());
    double q_low = 0.0, q_high = 0.0; // the nearness range GL's depth [0.05, 0.95] spans
    for (std::size_t k = 0; k < triangles.size(); ++k) {
        for (const double q : triangles[k]->nearness) {
            q_low = k == 0 ? q : std::min(q_low, q);
            q_high = k == 0 ? q : std::max(q_high, q);
        }
    }
    const double q_range = q_high > q_low ? q_high - q_low : 1.0;
    const std::vector<long long> ids =
        our_ids(geometry, scene.width, scene.height, c.depth_on);
    const std::vector<bool> exact = exact_coverage(geometry, scene.width, scene.height);
    const std::vector<Rgba8> gl_ids = draw_gl(scene, geometry, looks, c.depth_on, true);
    const std::vector<Rgba8> gl_colours =
        draw_gl(scene, geometry, looks, c.depth_on, false);
    c.tolerance = referee_rounding_levels;
    const Rgba8 background = to_rgba8(scene.background);
    c.theirs = Framebuffer(scene.width, scene.height, background);
    c.differences = Framebuffer(scene.width, scene.height, background);
    for (int y = 0; y < scene.height; ++y) {
        for (int x = 0; x < scene.width; ++x) {
            const std::size_t at = static_cast<std::size_t>(y) * scene.width + x;
            const Rgba8 g = gl_ids[at];
            const long long theirs_id = (g.r | (g.g << 8) | (g.b << 16)) - 1LL;
            const long long ours_id = ids[at];
            const Rgba8 mine = ours.image.at(x, y);
            c.theirs.at(x, y) = gl_colours[at];
            const int grey = (mine.r + mine.g + mine.b) / 6 + 64;
            Rgba8 shown =
                rgba(static_cast<std::uint8_t>(grey), static_cast<std::uint8_t>(grey),
                     static_cast<std::uint8_t>(grey));
            c.covered += ours_id >= 0;
            c.exact_differences += (ours_id >= 0) != exact[at];
            if (ours_id < 0 && !(mine == background)) {
                c.image_matches_ids = false;
            }
            if ((ours_id >= 0) != (theirs_id >= 0)) {
                c.coverage_differences.push_back({x, y});
                if ((ours_id >= 0) == exact[at]) {
                    c.coverage_exact.push_back({x, y});
                }
                shown = rgba(255, 0, 0);
            } else if (ours_id != theirs_id) {
                c.depth_differences += 1;
                const ScreenTriangle& mine_t =
                    *triangles[static_cast<std::size_t>(ours_id)];
                const ScreenTriangle& gl_t =
                    *triangles[static_cast<std::size_t>(theirs_id)];
                const double q_mine = nearness_at(mine_t, x, y);
                const double q_gl = nearness_at(gl_t, x, y);
                c.worst_depth_gap =
                    std::max(c.worst_depth_gap, std::abs(q_mine - q_gl) / q_range);
                // Ours obeys DepthBuffer's rule: the nearer key wins, a tie the later.
                const float k_mine = nearness_key(q_mine), k_gl = nearness_key(q_gl);
                c.depth_ours_right =
                    c.depth_ours_right &&
                    (k_mine > k_gl || (k_mine == k_gl && ours_id > theirs_id));
                c.depth_pixels.push_back({x, y});
                shown = rgba(255, 220, 0);
            } else if (ours_id >= 0 &&
                       looks[mesh_of[static_cast<std::size_t>(ours_id)]].comparable) {
                c.colour_compared += 1;
                c.shipped_differ +=
                    channel_difference(mine, gl_colours[at]) > c.tolerance;
                const int d =
                    channel_difference(reference.image.at(x, y), gl_colours[at]);
                c.worst_colour = std::max(c.worst_colour, d);
                const bool on_edge =
                    texels.covered[at] &&
                    std::min(edge_distance(texels.u[at]), edge_distance(texels.v[at])) <
                        referee_texel_edge;
                if (!on_edge) {
                    c.worst_off_edge = std::max(c.worst_off_edge, d);
                }
                if (d > c.tolerance) {
                    c.colour_over += 1;
                    c.texel_edge += on_edge;
                    shown = on_edge ? rgba(0, 200, 255) : rgba(255, 0, 255);
                }
            }
            c.differences.at(x, y) = shown;
        }
    }
    c.ours = std::move(ours.image);
    return c;
}

} // namespace exactpixels
