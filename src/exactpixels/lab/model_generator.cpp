#include "exactpixels/lab/model_generator.hpp"

#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/base/split_mix.hpp"

#include <fmt/format.h>
#include <glm/glm.hpp>

#include <array>
#include <cassert>
#include <cmath>
#include <numbers>

namespace exactpixels {

namespace {

/// A number as the files write it: 6 significant digits, no "-0".
std::string num(double x) {
    const std::string s = fmt::format("{:.6g}", x);
    return s == "-0" ? "0" : s;
}

std::string vec3_line(const char* key, glm::dvec3 p) {
    return fmt::format("{} {} {} {}\n", key, num(p.x), num(p.y), num(p.z));
}

/// A box's faces, corners numbered 1..8 as (-,-,-) (+,-,-) (+,+,-) (-,+,-) (-,-,+)
/// (+,-,+) (+,+,+) (-,+,+): counter-clockwise seen from outside, right-handed.
constexpr int box_faces[6][4] = {{5, 6, 7, 8}, {2, 1, 4, 3}, {6, 2, 3, 7},
                                 {1, 5, 8, 4}, {8, 7, 3, 4}, {1, 2, 6, 5}};
constexpr double box_normals[6][3] = {{0, 0, 1},  {0, 0, -1}, {1, 0, 0},
                                      {-1, 0, 0}, {0, 1, 0},  {0, -1, 0}};

/// Appends a box from `lo` to `hi`: 8 positions, then per face 4 texture coordinates
/// (`repeat` texture widths per unit) and a normal, and the face; every index relative
/// (negative), so boxes can be appended anywhere. `inwards` turns every face round.
/// `material(face)` names the material of each face ("" keeps the current one).
template <class Material>
void append_box(std::string& obj, glm::dvec3 lo, glm::dvec3 hi, double repeat,
                bool inwards, Material material) {
    std::array<glm::dvec3, 8> corner;
    for (int k = 0; k < 8; ++k) {
        const int x = (k == 1 || k == 2 || k == 5 || k == 6);
        const int y = (k == 2 || k == 3 || k == 6 || k == 7);
        const int z = k >= 4;
        corner[static_cast<std::size_t>(k)] = {x ? hi.x : lo.x, y ? hi.y : lo.y,
                                               z ? hi.z : lo.z};
        obj += vec3_line("v", corner[static_cast<std::size_t>(k)]);
    }
    for (int f = 0; f < 6; ++f) {
        std::array<int, 4> face{box_faces[f][0], box_faces[f][1], box_faces[f][2],
                                box_faces[f][3]};
        if (inwards) {
            face = {face[3], face[2], face[1], face[0]};
        }
        const auto at = [&](int k) {
            return corner[static_cast<std::size_t>(face[static_cast<std::size_t>(k)] -
                                                   1)];
        };
        const double du = glm::length(at(1) - at(0)) * repeat;
        const double dv = glm::length(at(3) - at(0)) * repeat;
        obj += fmt::format("vt 0 0\nvt {} 0\nvt {} {}\nvt 0 {}\n", num(du), num(du),
                           num(dv), num(dv));
        const double sign = inwards ? -1.0 : 1.0;
        obj += vec3_line("vn", sign * glm::dvec3{box_normals[f][0], box_normals[f][1],
                                                 box_normals[f][2]});
        const std::string name = material(f);
        if (!name.empty()) {
            obj += "usemtl " + name + "\n";
        }
        obj += "f";
        for (int k = 0; k < 4; ++k) {
            obj += fmt::format(" {}/{}/-1", face[static_cast<std::size_t>(k)] - 9, k - 4);
        }
        obj += "\n";
    }
}

std::uint8_t byte(double x) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(x, 0.0, 1.0) * 255.0));
}

} // namespace

//> torus-model
GeneratedModel torus_model(int rings, int sides, const std::string& name) {
    assert(rings >= 3 && sides >= 3);
    constexpr double major = 1.0, minor = 0.4;
    GeneratedModel m{name, {}, {}, {}};
    m.obj = fmt::format("# A torus of {} x {} quads, made by model_generator.cpp\n"
                        "mtllib {}.mtl\no torus\n",
                        rings, sides, name);
    for (int i = 0; i < rings; ++i) { // positions and normals: one per grid point
        const double theta = 2.0 * std::numbers::pi * i / rings;
        for (int j = 0; j < sides; ++j) {
            const double phi = 2.0 * std::numbers::pi * j / sides;
            const glm::dvec3 out{std::cos(phi) * std::cos(theta), std::sin(phi),
                                 std::cos(phi) * std::sin(theta)};
            const glm::dvec3 centre{major * std::cos(theta), 0.0,
                                    major * std::sin(theta)};
            m.obj += vec3_line("v", centre + minor * out);
            m.obj += vec3_line("vn", out);
        }
    }
    for (int i = 0; i <= rings; ++i) { // texture coordinates: the seams repeat
        for (int j = 0; j <= sides; ++j) {
            m.obj +=
                fmt::format("vt {} {}\n", num(8.0 * i / rings), num(2.0 * j / sides));
        }
    }
    m.obj += "usemtl striped\ns 1\n";
    const auto corner = [&](int i, int j) {
        const int p = (i % rings) * sides + (j % sides) + 1;
        const int t = i * (sides + 1) + j + 1;
        return fmt::format("{}/{}/{}", p, t, p);
    };
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < sides; ++j) { // counter-clockwise seen from outside
            m.obj += fmt::format("f {} {} {} {}\n", corner(i, j), corner(i, j + 1),
                                 corner(i + 1, j + 1), corner(i + 1, j));
        }
    }
    m.mtl = fmt::format("# The torus's material, made by model_generator.cpp\n"
                        "newmtl striped\nKd 1 1 1\nmap_Kd {}.png\n",
                        name);
    Framebuffer texture(64, 32);
    for (int y = 0; y < texture.height(); ++y) {
        for (int x = 0; x < texture.width(); ++x) {
            const bool stripe = (x / 8) % 2 == 0;
            const bool line = y % 16 == 0 || x % 16 == 0;
            texture.at(x, y) = line     ? rgba(250, 240, 220)
                               : stripe ? rgba(200, 60, 40)
                                        : rgba(40, 90, 170);
        }
    }
    m.textures.emplace_back(name + ".png", std::move(texture));
    return m;
}
//< torus-model

GeneratedModel room_model() {
    GeneratedModel m{"room", {}, {}, {}};
    m.obj = "# A room with a table, a bed and a cabinet, made by model_generator.cpp\n"
            "mtllib room.mtl\no room\n";
    // The room: inwards, its floor (face 5, -y) wooden, the rest plaster.
    append_box(m.obj, {-3, 0, -2.5}, {3, 3, 2.5}, 0.5, true, [](int face) {
        return face == 5 ? std::string("wood") : face == 0 ? "plaster" : "";
    });
    const auto furniture = [&](const char* what, const char* material, glm::dvec3 lo,
                               glm::dvec3 hi) {
        m.obj += fmt::format("o {}\nusemtl {}\n", what, material);
        append_box(m.obj, lo, hi, 1.0, false, [](int) { return std::string(); });
    };
    furniture("table_top", "oak", {-1.2, 0.72, -0.6}, {0.4, 0.8, 0.4});
    for (const double x : {-1.1, 0.24}) {
        for (const double z : {-0.5, 0.24}) {
            furniture("table_leg", "oak", {x, 0, z}, {x + 0.06, 0.72, z + 0.06});
        }
    }
    furniture("bed", "linen", {1.0, 0, 0.4}, {2.9, 0.5, 2.4});
    furniture("pillow", "plaster", {2.2, 0.5, 0.6}, {2.8, 0.62, 2.2});
    furniture("cabinet", "teal", {-2.9, 0, 1.6}, {-2.0, 1.8, 2.4});
    m.mtl = "# The room's materials, made by model_generator.cpp\n"
            "newmtl wood\nKd 1 1 1\nmap_Kd room_wood.png\n"
            "newmtl plaster\nKd 0.92 0.9 0.85\n"
            "newmtl oak\nKd 0.62 0.42 0.24\n"
            "newmtl linen\nKd 0.75 0.8 0.9\n"
            "newmtl teal\nKd 0.2 0.55 0.55\n";
    Framebuffer wood(64, 64);
    for (int y = 0; y < wood.height(); ++y) { // planks 8 texels wide, staggered
        const int plank = y / 8;
        for (int x = 0; x < wood.width(); ++x) {
            const int offset = (plank * 23) % 64;
            SplitMix shade(static_cast<std::uint64_t>(plank * 64 + (x + offset) / 32));
            const double base = 0.55 + 0.2 * shade.uniform();
            const double grain = 0.04 * std::sin(0.9 * x + 3.0 * plank);
            const bool gap = y % 8 == 7 || (x + offset) % 32 == 0;
            const double v = gap ? 0.25 : base + grain;
            wood.at(x, y) = rgba(byte(v), byte(0.72 * v), byte(0.45 * v));
        }
    }
    m.textures.emplace_back("room_wood.png", std::move(wood));
    return m;
}

GeneratedModel terrain_model(int cells) {
    assert(cells >= 1);
    GeneratedModel m{"terrain", {}, {}, {}};
    m.obj = fmt::format("# A terrain of {} x {} cells, made by model_generator.cpp\n"
                        "mtllib terrain.mtl\no terrain\n",
                        cells, cells);
    constexpr double size = 8.0;
    const auto height = [](double x, double z) {
        return 0.5 * std::sin(0.9 * x) * std::cos(0.7 * z) +
               0.25 * std::sin(1.7 * z + 1.0);
    };
    const int n = cells + 1;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const double x = size * (i / double(cells) - 0.5);
            const double z = size * (j / double(cells) - 0.5);
            m.obj += vec3_line("v", {x, height(x, z), z});
            constexpr double e = 1e-4; // the normal from the slopes, central differences
            const double dx = (height(x + e, z) - height(x - e, z)) / (2 * e);
            const double dz = (height(x, z + e) - height(x, z - e)) / (2 * e);
            m.obj += vec3_line("vn", glm::normalize(glm::dvec3{-dx, 1.0, -dz}));
            m.obj +=
                fmt::format("vt {} {}\n", num(4.0 * i / cells), num(4.0 * j / cells));
        }
    }
    m.obj += "usemtl grass\n";
    for (int j = 0; j < cells; ++j) {
        for (int i = 0; i < cells; ++i) { // counter-clockwise seen from above
            const auto k = [&](int a, int b) {
                const int index = b * n + a + 1;
                return fmt::format("{}/{}/{}", index, index, index);
            };
            m.obj += fmt::format("f {} {} {}\nf {} {} {}\n", k(i, j), k(i, j + 1),
                                 k(i + 1, j + 1), k(i, j), k(i + 1, j + 1), k(i + 1, j));
        }
    }
    m.mtl = "# The terrain's material, made by model_generator.cpp\n"
            "newmtl grass\nKd 1 1 1\nmap_Kd terrain_grass.png\n";
    Framebuffer grass(64, 64);
    SplitMix random(17);
    for (int y = 0; y < grass.height(); ++y) {
        for (int x = 0; x < grass.width(); ++x) {
            const double v = 0.75 + 0.25 * random.uniform();
            const bool path = std::abs((x + y) % 64 - 32) < 3;
            grass.at(x, y) = path ? rgba(byte(0.7 * v), byte(0.6 * v), byte(0.4 * v))
                                  : rgba(byte(0.3 * v), byte(0.6 * v), byte(0.2 * v));
        }
    }
    m.textures.emplace_back("terrain_grass.png", std::move(grass));
    return m;
}

std::vector<GeneratedModel> shipped_models() {
    std::vector<GeneratedModel> models;
    models.push_back(torus_model(36, 18));
    models.push_back(room_model());
    models.push_back(terrain_model(24));
    return models;
}

//> big-torus-scene
GeneratedModel big_torus_model() {
    return torus_model(400, 128, "big_torus"); // 2 x 400 x 128 = 102,400 triangles
}

std::string big_torus_scene() {
    return "[image]\nwidth = 1280\nheight = 720\nbackground = [0.55, 0.65, 0.8]\n"
           "[camera]\nfov = 40\nposition = [0.0, 1.8, -2.7]\ntarget = [0.0, 0.0, 0.0]\n"
           "[render]\nmapper = \"auto\"\ndepth = true\n"
           "[[mesh]]\nname = \"big torus\"\nfile = \"big_torus.obj\"\n"
           "cull = \"back\"\nrotate = [20, 0, 10]\n";
}
//< big-torus-scene

void write_generated_model(const GeneratedModel& model,
                           const std::filesystem::path& folder) {
    write_file_atomically(folder / (model.name + ".obj"), "model", model.obj);
    write_file_atomically(folder / (model.name + ".mtl"), "material", model.mtl);
    for (const auto& [file, image] : model.textures) {
        write_png(folder / file, image);
    }
}

} // namespace exactpixels
