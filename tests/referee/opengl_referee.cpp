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
#include "exactpixels/texture/srgb.hpp"
#include "exactpixels/texture/texture_mapper.hpp"

#define GL_GLEXT_PROTOTYPES 1 // glCreateShader and the rest: libOSMesa exports them
#include <GL/osmesa.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <random>
#include <utility>

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
    bool comparable = true; ///< GL draws its colours as the renderer does
    bool phong = false;     ///< lit per pixel: drawn with per_pixel_program()
    MeshStages stages;
};

/// The vertex stage of per-pixel lighting: the view-space point (texture unit 1's
/// coordinate) and normal go out as varyings, which GL interpolates perspective-correctly
/// (a/w over 1/w, in float), as the renderer's lighting stage does in double.
constexpr const char* per_pixel_vertex = R"(#version 450 compatibility
out vec3 point;
out vec3 normal;
out vec4 colour;
out vec2 uv;
void main() {
    gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;
    point = gl_MultiTexCoord1.xyz;
    normal = gl_Normal;
    colour = gl_Color;
    uv = gl_MultiTexCoord0.xy;
}
)";

//> referee-phong-shader
/// light_colour (lighting.cpp) in single precision, on the pixel the renderer's texture
/// and colour stages would write: the texel times the colour, rounded to 8 bits.
constexpr const char* per_pixel_fragment = R"(#version 450 compatibility
in vec3 point;
in vec3 normal;
in vec4 colour;
in vec2 uv;
uniform sampler2D texels;
uniform bool textured;
uniform bool perspective;
uniform bool decode_codes; // false only for a planted fault (RefereeFault)
uniform vec3 ambient;      // sRGB code / 255
uniform vec3 specular;     // sRGB code / 255
uniform float shininess;
uniform int light_count;         // at most 8, max_scene_lights
uniform bool light_is_point[8];
uniform vec3 light_towards[8];  // directional: unit vector to the light
uniform vec3 light_position[8]; // point: view space
uniform vec3 light_radiance[8]; // linear light
uniform float min_light_distance;
float decode(float s) {
    return s <= 0.04045 ? s / 12.92 : pow((s + 0.055) / 1.055, 2.4);
}
float encode(float l) {
    return l <= 0.0031308 ? 12.92 * l : 1.055 * pow(l, 1.0 / 2.4) - 0.055;
}
vec3 to_linear(vec3 c) {
    return decode_codes ? vec3(decode(c.r), decode(c.g), decode(c.b)) : c;
}
void main() {
    vec3 base = colour.rgb;
    if (textured) {
        base *= texture(texels, uv).rgb;
    }
    base = floor(clamp(base, 0.0, 1.0) * 255.0 + 0.5) / 255.0; // an 8-bit pixel
    vec3 n = normalize(normal);
    vec3 to_eye = perspective ? normalize(-point) : vec3(0.0, 0.0, -1.0);
    vec3 lambert = to_linear(ambient);
    vec3 highlight = vec3(0.0);
    for (int i = 0; i < light_count; ++i) {
        vec3 towards = light_towards[i];
        vec3 irradiance = light_radiance[i];
        if (light_is_point[i]) {
            vec3 d = light_position[i] - point;
            float d2 = max(dot(d, d), min_light_distance * min_light_distance);
            towards = d / sqrt(d2);
            irradiance /= d2;
        }
        float cosine = dot(n, towards);
        if (cosine <= 0.0) {
            continue; // the light is behind the surface
        }
        lambert += cosine * irradiance;
        vec3 sum = towards + to_eye;
        if (dot(sum, sum) > 0.0) {
            float facing = max(0.0, dot(n, normalize(sum)));
            highlight += pow(facing, shininess) * irradiance;
        }
    }
    vec3 l = max(to_linear(base) * lambert + to_linear(specular) * highlight, 0.0);
    gl_FragColor = vec4(encode(l.r), encode(l.g), encode(l.b), 1.0);
}
)";
//< referee-phong-shader
static_assert(max_scene_lights == 8, "per_pixel_fragment's light arrays hold 8");

/// In place of per_pixel_fragment, for the probe passes: one float the lighting starts
/// from (the renormalised normal's x, y or z, or the point's, as `component` says 0..5),
/// its 32 bits written as the pixel's four 8-bit channels, so that the referee reads
/// exactly what GL interpolated.
constexpr const char* probe_fragment = R"(#version 450 compatibility
in vec3 point;
in vec3 normal;
uniform int component;
void main() {
    vec3 n = normalize(normal);
    float value = component < 3 ? n[component] : point[component - 3];
    uint bits = floatBitsToUint(value);
    gl_FragColor = vec4(float(bits & 255u), float((bits >> 8) & 255u),
                        float((bits >> 16) & 255u), float(bits >> 24)) / 255.0;
}
)";

/// Compiles one shader stage; throws Error with GL's log when it fails.
GLuint compile_shader(GLenum kind, const char* source) {
    const GLuint shader = glCreateShader(kind);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        std::string log(4096, '\0');
        GLsizei length = 0;
        glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), &length, log.data());
        log.resize(static_cast<std::size_t>(length));
        throw Error("the referee's per-pixel lighting shader does not compile: " + log);
    }
    return shader;
}

/// Links per_pixel_vertex with `fragment`; throws Error when it fails.
GLuint link_program(const char* fragment) {
    const GLuint made = glCreateProgram();
    glAttachShader(made, compile_shader(GL_VERTEX_SHADER, per_pixel_vertex));
    glAttachShader(made, compile_shader(GL_FRAGMENT_SHADER, fragment));
    glLinkProgram(made);
    GLint ok = GL_FALSE;
    glGetProgramiv(made, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        throw Error("the referee's per-pixel lighting program does not link");
    }
    return made;
}

/// The per-pixel lighting program, linked once (the context must be current).
GLuint per_pixel_program() {
    static const GLuint program = link_program(per_pixel_fragment);
    return program;
}

/// The probe program (probe_fragment), linked once.
GLuint probe_program() {
    static const GLuint program = link_program(probe_fragment);
    return program;
}

/// Sets the per-pixel program's uniforms for one mesh: the scene's lights (view space,
/// as run_geometry moved them), ambient, the mesh's material, and `fault`.
void set_lighting_uniforms(GLuint program, const Scene& scene,
                           const SceneGeometry& geometry, const SceneMesh& mesh,
                           bool textured, const RefereeFault& fault) {
    const auto at = [&](const char* name) { return glGetUniformLocation(program, name); };
    const auto vec3 = [&](const char* name, std::size_t k, double x, double y, double z) {
        const std::string indexed = fmt::format("{}[{}]", name, k);
        glUniform3f(at(indexed.c_str()), static_cast<float>(x), static_cast<float>(y),
                    static_cast<float>(z));
    };
    glUniform1i(at("texels"), 0);
    glUniform1i(at("textured"), textured ? 1 : 0);
    glUniform1i(at("perspective"),
                scene.camera.projection == Projection::perspective ? 1 : 0);
    glUniform1i(at("decode_codes"), fault.skip_decode ? 0 : 1);
    const Colour& a = scene.options.ambient;
    glUniform3f(at("ambient"), static_cast<float>(a.r), static_cast<float>(a.g),
                static_cast<float>(a.b));
    glUniform3f(at("specular"), static_cast<float>(mesh.specular.r),
                static_cast<float>(mesh.specular.g), static_cast<float>(mesh.specular.b));
    glUniform1f(at("shininess"),
                static_cast<float>(mesh.shininess + fault.shininess_offset));
    if (geometry.lights.size() > static_cast<std::size_t>(max_scene_lights)) {
        throw Error(fmt::format("the referee's shader takes at most {} lights",
                                max_scene_lights)); // its arrays' size
    }
    glUniform1f(at("min_light_distance"), static_cast<float>(min_light_distance));
    glUniform1i(at("light_count"), static_cast<GLint>(geometry.lights.size()));
    for (std::size_t k = 0; k < geometry.lights.size(); ++k) {
        const ViewLight& light = geometry.lights[k];
        const std::string point = fmt::format("light_is_point[{}]", k);
        glUniform1i(at(point.c_str()), light.type == LightType::point ? 1 : 0);
        vec3("light_towards", k, light.towards.x, light.towards.y, light.towards.z);
        vec3("light_position", k, light.position.x, light.position.y, light.position.z);
        vec3("light_radiance", k, light.radiance.r, light.radiance.g, light.radiance.b);
    }
}

/// Uploads `texture` as the bound GL_TEXTURE_2D's only level (8-bit codes, nearest).
void upload_nearest(const Texture& texture) {
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, texture.width(), texture.height(), 0,
                 GL_RGBA, GL_UNSIGNED_BYTE, texture.texels().data());
}

/// The texels of `texture` each multiplied by `tint` as the renderer's colour stage
/// multiplies them (code / 255 times the tint, rounded to the nearest code).
Texture tinted(const Texture& texture, const Colour& tint) {
    std::vector<Rgba8> texels = texture.texels();
    for (Rgba8& t : texels) {
        t = to_rgba8(
            Colour{t.r / 255.0 * tint.r, t.g / 255.0 * tint.g, t.b / 255.0 * tint.b});
    }
    return Texture(texture.width(), texture.height(), std::move(texels));
}

/// Draws every triangle through GL; `id_pass` gives each its index + 1 as a flat
/// colour, else the renderer's colours and nearest texels, and per-pixel lighting (with
/// `fault` planted) for the meshes lit per pixel, or, when `probe` is 0..5, those
/// meshes' probe_fragment value of that component. Returns the pixels.
std::vector<Rgba8> draw_gl(const Scene& scene, const SceneGeometry& geometry,
                           const std::vector<MeshLook>& looks, bool depth_on,
                           bool id_pass, const RefereeFault& fault = {}, int probe = -1) {
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
    // One GL texture per scene texture, and for each tinted mesh lit per pixel one
    // more, its texels tinted as the renderer's colour stage tints them (the shader
    // lights that 8-bit product, as the renderer's lighting stage does).
    std::vector<GLuint> names(id_pass ? 0 : scene.textures.size() + scene.meshes.size(),
                              0);
    if (!names.empty()) {
        glGenTextures(static_cast<GLsizei>(names.size()), names.data());
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        for (std::size_t i = 0; i < scene.textures.size(); ++i) {
            glBindTexture(GL_TEXTURE_2D, names[i]);
            upload_nearest(scene.textures[i].texture);
        }
        for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
            const SceneMesh& mesh = scene.meshes[i];
            if (looks[i].phong && looks[i].stages.texture && looks[i].stages.tint) {
                glBindTexture(GL_TEXTURE_2D, names[scene.textures.size() + i]);
                upload_nearest(
                    tinted(scene.textures[*mesh.texture].texture, mesh.colour));
            }
        }
        glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
    }
    long long index = 0;
    for (std::size_t i = 0; i < geometry.meshes.size(); ++i) {
        const SceneMesh& mesh = scene.meshes[i];
        const MeshStages& stages = looks[i].stages;
        const bool textured = !id_pass && stages.texture;
        const bool phong = !id_pass && looks[i].phong;
        const bool pretinted = phong && stages.texture && stages.tint;
        if (phong && probe >= 0) {
            const GLuint program = probe_program();
            glUseProgram(program);
            glUniform1i(glGetUniformLocation(program, "component"), probe);
        } else if (phong) {
            const GLuint program = per_pixel_program();
            glUseProgram(program);
            set_lighting_uniforms(program, scene, geometry, mesh, textured, fault);
        } else {
            glUseProgram(0);
        }
        if (textured) {
            glEnable(GL_TEXTURE_2D);
            glBindTexture(GL_TEXTURE_2D,
                          names[pretinted ? scene.textures.size() + i : *mesh.texture]);
            const GLint wrap = mesh.wrap == Wrap::repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE;
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
        } else {
            glDisable(GL_TEXTURE_2D);
        }
        const double tw = textured ? scene.textures[*mesh.texture].texture.width() : 1;
        const double th = textured ? scene.textures[*mesh.texture].texture.height() : 1;
        glBegin(GL_TRIANGLES);
        for (std::size_t n = 0; n < geometry.meshes[i].size(); ++n) {
            const ScreenTriangle& t = geometry.meshes[i][n];
            // Colours, points and normals: kept where a colour or lighting stage reads
            // them, which is where they are read here.
            const ShadedCorners* shaded =
                geometry.shading[i].empty() ? nullptr : &geometry.shading[i][n];
            ++index;
            if (id_pass) {
                glColor4ub(static_cast<GLubyte>(index & 0xff),
                           static_cast<GLubyte>((index >> 8) & 0xff),
                           static_cast<GLubyte>((index >> 16) & 0xff), 255);
            } else if (phong && !stages.colour) { // the 8-bit colour the shader lights
                const Rgba8 c =
                    stages.texture ? rgba(255, 255, 255) : to_rgba8(mesh.colour);
                glColor4ub(c.r, c.g, c.b, 255);
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
                    const Colour& c = shaded->colours[k];
                    glColor4d(c.r, c.g, c.b, 1.0);
                }
                if (textured) {
                    glTexCoord2d(t.corners[k].uv.x / tw, t.corners[k].uv.y / th);
                }
                if (phong) { // the view-space point and normal the lighting stage uses
                    const glm::dvec3 &at = shaded->points[k], &n = shaded->normals[k];
                    glMultiTexCoord3d(GL_TEXTURE1, at.x, at.y, at.z);
                    glNormal3d(n.x, n.y, n.z);
                }
                // glOrtho's z row is -z: clip z = -z_ndc w gives z_ndc after the divide.
                glVertex4d(p.x * w, p.y * w, -z_ndc * w, w);
            }
            //< referee-vertex
        }
        glEnd();
    }
    glUseProgram(0);
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

/// The view-space point and unit normal the renderer's lighting stage lights at pixel
/// (x, y)'s centre: point/w and n/w planes through the snapped corners over the 1/w
/// plane, the normal renormalised (scene_renderer.cpp, the lighting stage).
std::pair<glm::dvec3, glm::dvec3>
lit_point_normal(const ScreenTriangle& t, const ShadedCorners& shaded, int x, int y) {
    std::array<Point2, 3> p{};
    std::array<double, 3> q{};
    for (std::size_t k = 0; k < 3; ++k) {
        p[k] = to_pixels(snap_in_range(t.corners[k].position));
        q[k] = 1.0 / t.corners[k].w;
    }
    const double px = x + 0.5, py = y + 0.5;
    const double w = 1.0 / plane_through(p, q).at(px, py);
    glm::dvec3 point{}, normal{};
    for (int c = 0; c < 3; ++c) {
        std::array<double, 3> a{}, n{};
        for (std::size_t k = 0; k < 3; ++k) {
            a[k] = shaded.points[k][c] * q[k];
            n[k] = shaded.normals[k][c] * q[k];
        }
        point[c] = plane_through(p, a).at(px, py) * w;
        normal[c] = plane_through(p, n).at(px, py);
    }
    return {point, glm::normalize(normal)};
}

/// The unit vector from a view-space point to the eye, as the renderer's to_eye.
glm::dvec3 eye_direction(const Scene& scene, glm::dvec3 p) {
    return scene.camera.projection == Projection::perspective
               ? glm::normalize(-p)
               : glm::dvec3{0.0, 0.0, -1.0};
}

/// The float a probe pass wrote at pixel `at` (its four channels are its 32 bits).
float probed(const std::vector<Rgba8>& pass, std::size_t at) {
    const Rgba8 b = pass[at];
    const std::uint32_t bits =
        static_cast<std::uint32_t>(b.r) | (static_cast<std::uint32_t>(b.g) << 8) |
        (static_cast<std::uint32_t>(b.b) << 16) | (static_cast<std::uint32_t>(b.a) << 24);
    float value = 0.0f;
    std::memcpy(&value, &bits, sizeof value);
    return value;
}

/// How far GL's single precision can move a lit pixel's colour, levels, before the two
/// roundings (@eq:scene-referee-lit): the colour the renderer's light_colour gives at the
/// point and normal GL interpolated (read from the probe passes) against at its own,
/// plus the bound 115 x^(5/12) rho on GL's float arithmetic, x the linear light and rho
/// = referee_float_relative(shininess). Texel (i, j) is the one the exact render picked.
double lit_float_levels(const Scene& scene, const SceneGeometry& geometry,
                        const SceneMesh& mesh, const MeshStages& stages,
                        const ScreenTriangle& t, const ShadedCorners& shaded, int x,
                        int y, int i, int j,
                        const std::vector<std::vector<Rgba8>>& probes, std::size_t at) {
    Rgba8 base = to_rgba8(mesh.colour); // the pixel the stages before lighting write
    if (stages.texture) {
        base = fetch_texel(scene.textures[*mesh.texture].texture, i, j, mesh.wrap);
        if (stages.tint) {
            base = to_rgba8(Colour{base.r / 255.0 * mesh.colour.r,
                                   base.g / 255.0 * mesh.colour.g,
                                   base.b / 255.0 * mesh.colour.b});
        }
    }
    const Colour diffuse{base.r / 255.0, base.g / 255.0, base.b / 255.0};
    const Material material{mesh.specular, mesh.shininess};
    const auto [point, normal] = lit_point_normal(t, shaded, x, y);
    const glm::dvec3 gl_normal = glm::normalize(
        glm::dvec3{probed(probes[0], at), probed(probes[1], at), probed(probes[2], at)});
    const glm::dvec3 gl_point{probed(probes[3], at), probed(probes[4], at),
                              probed(probes[5], at)};
    const Colour ours =
        light_colour(geometry.lights, scene.options.ambient, diffuse, material, point,
                     normal, eye_direction(scene, point));
    const Colour moved =
        light_colour(geometry.lights, scene.options.ambient, diffuse, material, gl_point,
                     gl_normal, eye_direction(scene, gl_point));
    double interpolation = 0.0, arithmetic = 0.0;
    const double rho = referee_float_relative(mesh.shininess);
    for (int c = 0; c < 3; ++c) {
        interpolation = std::max(interpolation, 255.0 * std::abs(ours[c] - moved[c]));
        const double linear = srgb_decode(ours[c]); // the x that was encoded
        arithmetic = std::max(arithmetic, 115.0 * std::pow(linear, 5.0 / 12.0) * rho);
    }
    const double levels = interpolation + arithmetic;
    // A probe that did not hold a number (NaN) must not pass as a small bound.
    return std::isfinite(levels) ? levels : std::numeric_limits<double>::infinity();
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
    geometry.shading.emplace_back(); // one entry per mesh: none kept (no colour, no light)
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

RefereeComparison referee_scene(const Scene& scene, const std::string& name,
                                const RefereeFault& fault) {
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
    c.phong_meshes = ours.report.phong_meshes;
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
    std::vector<const ShadedCorners*> shading; // per triangle; nullptr where none kept
    for (std::size_t i = 0; i < geometry.meshes.size(); ++i) {
        for (std::size_t n = 0; n < geometry.meshes[i].size(); ++n) {
            triangles.push_back(&geometry.meshes[i][n]);
            shading.push_back(geometry.shading[i].empty() ? nullptr
                                                          : &geometry.shading[i][n]);
        }
    }
    std::vector<MeshLook> looks(scene.meshes.size());
    std::vector<std::size_t> mesh_of; // per triangle index
    bool any_phong = false;
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const SceneMesh& mesh = scene.meshes[i];
        looks[i].stages = mesh_stages(scene, mesh); // the renderer's own choice
        looks[i].phong =
            !scene.lights.empty() && mesh_shading(scene, mesh) == Shading::phong;
        any_phong = any_phong || looks[i].phong;
        if (looks[i].phong && looks[i].stages.colour) {
            // Both sides would round the interpolated colour to 8 bits before lighting
            // it, and at a tie the two roundings part by a level that lighting scales.
            looks[i].comparable = false;
            c.uncompared = "vertex colours lit per pixel";
        }
        if (looks[i].stages.texture && scene.options.filter != SceneFilter::nearest) {
            // GL leaves anisotropic filtering to the implementation and approximates
            // the level of detail from 2 x 2 pixel differences, where the renderer
            // uses exact derivatives: a difference would measure GL's approximation.
            looks[i].comparable = false;
            const auto& f = ours.report.filter_triangles;
            c.uncompared = fmt::format("filtered texels ({} bilinear, {} trilinear, {} "
                                       "anisotropic triangles)",
                                       f[0], f[1], f[2]);
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
        draw_gl(scene, geometry, looks, c.depth_on, false, fault);
    std::vector<std::vector<Rgba8>> probes; // GL's normal x, y, z and point x, y, z
    for (int component = 0; any_phong && component < 6; ++component) {
        probes.push_back(
            draw_gl(scene, geometry, looks, c.depth_on, false, fault, component));
    }
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
                       !looks[mesh_of[static_cast<std::size_t>(ours_id)]].comparable) {
                c.colour_uncompared += 1;
            } else if (ours_id >= 0) {
                const std::size_t mesh_index = mesh_of[static_cast<std::size_t>(ours_id)];
                const bool lit = looks[mesh_index].phong;
                const int tolerance = lit ? referee_lit_levels : c.tolerance;
                c.colour_compared += 1;
                c.lit_compared += lit;
                c.shipped_differ += channel_difference(mine, gl_colours[at]) > tolerance;
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
                if (!on_edge && lit) {
                    c.worst_lit_off_edge = std::max(c.worst_lit_off_edge, d);
                    const double bound = lit_float_levels(
                        scene, geometry, scene.meshes[mesh_index],
                        looks[mesh_index].stages,
                        *triangles[static_cast<std::size_t>(ours_id)],
                        *shading[static_cast<std::size_t>(ours_id)], x, y,
                        texels.covered[at] ? texels.i[at] : 0,
                        texels.covered[at] ? texels.j[at] : 0, probes, at);
                    c.worst_lit_float = std::max(c.worst_lit_float, bound);
                }
                if (d > tolerance) {
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
