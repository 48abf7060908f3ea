// section_meshes.cpp: a scene's [[mesh]] tables. A mesh is a primitive, generated from a
// few numbers by the table of primitives below, or a model file (section_models.cpp);
// both take the same options (read_mesh_options) and transform (read_transform), and
// every mesh is placed and checked the same way (place_and_check).
#include "exactpixels/scene/scene_sections.hpp"

#include <numbers>

namespace exactpixels::scene_format {

namespace {

/// The quad a-b-c-d as two triangles sharing the diagonal a-c.
void add_quad(SceneMesh& mesh, const std::array<SceneVertex, 4>& q) {
    mesh.triangles.push_back({q[0], q[1], q[2]});
    mesh.triangles.push_back({q[0], q[2], q[3]});
}

/// A vertex on a plane spanned by two axes, uv = texels_per_unit * plane coordinates.
SceneVertex planar_vertex(glm::dvec3 p, glm::dvec2 plane, double texels_per_unit) {
    return {p, plane * texels_per_unit, {1.0, 1.0, 1.0}};
}

/// The `texels_per_unit` of a generated primitive's texture coordinates (16 unless set).
double texels_per_unit(const TableReader& t) {
    const toml::node* n = t.find("texels_per_unit");
    return n ? read_positive(t.context(), *n, t.child("texels_per_unit"), 0.0, 1e6)
             : 16.0;
}

/// The list of N-vectors at `key`, or an empty list when the key is absent.
template <int N>
std::vector<glm::vec<N, double>> optional_vectors(const TableReader& t, const char* key,
                                                  std::size_t count, double lo,
                                                  double hi) {
    const toml::node* n = t.find(key);
    return n ? read_vectors<N>(t.context(), *n, t.child(key), count, lo, hi)
             : std::vector<glm::vec<N, double>>{};
}

/// The corners the table lists at `key` (`count` of them, or any multiple of 3 when
/// count is 0), each with its optional uv, colour and normal.
std::vector<SceneVertex> read_corners(const TableReader& t, SceneMesh& mesh,
                                      const char* key, std::size_t count) {
    const Context& c = t.context();
    const std::vector<glm::dvec3> p = read_vectors<3>(c, t.require(key), t.child(key),
                                                      count, -world_limit, world_limit);
    if (count == 0 && p.size() % 3 != 0) {
        c.fail(t.require(key).source(), t.child(key),
               fmt::format("{} points do not make whole triangles (need a "
                           "multiple of 3)",
                           p.size()));
    }
    const auto uv = optional_vectors<2>(t, "uv", p.size(), -uv_limit, uv_limit);
    const auto rgb = optional_vectors<3>(t, "colours", p.size(), 0.0, 1.0);
    mesh.vertex_colours = !rgb.empty();
    std::vector<SceneVertex> v(p.size());
    for (std::size_t k = 0; k < p.size(); ++k) {
        v[k] = {p[k], uv.empty() ? TexCoord{} : uv[k],
                rgb.empty() ? Colour{1.0, 1.0, 1.0} : rgb[k]};
    }
    const toml::node* normals = t.find("normals");
    if (normals != nullptr && normals->is_array()) { // one per vertex, any length
        const toml::array& array =
            read_array(c, *normals, t.child("normals"), p.size(), p.size());
        for (std::size_t k = 0; k < p.size(); ++k) {
            v[k].normal = read_direction(c, *array.get(k),
                                         fmt::format("{}[{}]", t.child("normals"), k));
        }
        mesh.normals = NormalSource::given;
    }
    return v;
}

/// triangles: `positions`, three corners per triangle.
void read_triangles(const TableReader& t, SceneMesh& mesh) {
    const std::vector<SceneVertex> v = read_corners(t, mesh, "positions", 0);
    for (std::size_t k = 0; k < v.size(); k += 3) {
        mesh.triangles.push_back({v[k], v[k + 1], v[k + 2]});
    }
}

/// quad: four `corners`, two triangles.
void read_quad(const TableReader& t, SceneMesh& mesh) {
    const std::vector<SceneVertex> v = read_corners(t, mesh, "corners", 4);
    add_quad(mesh, {v[0], v[1], v[2], v[3]});
}

/// box: six faces around `centre` of `size`, each counter-clockwise seen from outside.
void read_box(const TableReader& t, SceneMesh& mesh) {
    const Context& c = t.context();
    const glm::dvec3 centre = read_point(c, t.require("centre"), t.child("centre"));
    const glm::dvec3 h =
        0.5 * read_vector<3>(c, t.require("size"), t.child("size"), 0.0, world_limit);
    const double s = texels_per_unit(t);
    for (int axis = 0; axis < 3; ++axis) {
        for (const double side : {-1.0, 1.0}) {
            const int a = (axis + 1) % 3, b = (axis + 2) % 3; // the face's axes
            std::array<SceneVertex, 4> q;
            const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
            for (int k = 0; k < 4; ++k) {
                glm::dvec3 p = centre;
                p[axis] += side * h[axis];
                // Walk the face one way on the + side and the other way on the - side,
                // so that all faces turn the same way seen from outside.
                const double ca = corners[k][0], cb = corners[k][1] * side;
                p[a] += ca * h[a];
                p[b] += cb * h[b];
                q[static_cast<std::size_t>(k)] =
                    planar_vertex(p, {(ca + 1) * h[a], (1 - corners[k][1]) * h[b]}, s);
            }
            // The walk above turns from axis a to axis b, counter-clockwise about the
            // outward axis in a right-handed frame; world space is left-handed (x right,
            // y up, z forward), where that turn looks clockwise from outside. Reversed,
            // each face is counter-clockwise seen from outside, which is what the
            // renderer's back-face test takes as a front face.
            add_quad(mesh, {q[0], q[3], q[2], q[1]});
        }
    }
}

/// floor: a horizontal rectangle at height `y` over `x` and `z`.
void read_floor(const TableReader& t, SceneMesh& mesh) {
    const Context& c = t.context();
    const double y =
        read_number(c, t.require("y"), t.child("y"), -world_limit, world_limit);
    const glm::dvec2 x =
        read_vector<2>(c, t.require("x"), t.child("x"), -world_limit, world_limit);
    const glm::dvec2 z =
        read_vector<2>(c, t.require("z"), t.child("z"), -world_limit, world_limit);
    const double s = texels_per_unit(t);
    add_quad(mesh, {planar_vertex({x[0], y, z[0]}, {x[0], -z[0]}, s),
                    planar_vertex({x[0], y, z[1]}, {x[0], -z[1]}, s),
                    planar_vertex({x[1], y, z[1]}, {x[1], -z[1]}, s),
                    planar_vertex({x[1], y, z[0]}, {x[1], -z[0]}, s)});
}

/// fan: a disc of `segments` triangles around `centre`, facing -z.
void read_fan(const TableReader& t, SceneMesh& mesh) {
    const Context& c = t.context();
    const glm::dvec3 centre = read_point(c, t.require("centre"), t.child("centre"));
    const double radius =
        read_positive(c, t.require("radius"), t.child("radius"), 0.0, world_limit);
    const int segments =
        read_integer(c, t.require("segments"), t.child("segments"), 3, 4096);
    const auto rim = optional_vectors<3>(t, "rim_colours", 0, 0.0, 1.0);
    const toml::node* hub = t.find("centre_colour");
    mesh.vertex_colours = !rim.empty() || hub != nullptr;
    const Colour hub_colour =
        hub ? read_colour(c, *hub, t.child("centre_colour")) : Colour{1.0, 1.0, 1.0};
    const double s = texels_per_unit(t);
    const auto rim_vertex = [&](int k) {
        const double angle = 2.0 * std::numbers::pi * (k % segments) / segments;
        const glm::dvec2 d{std::cos(angle), std::sin(angle)};
        SceneVertex v = planar_vertex(centre + radius * glm::dvec3{d.x, d.y, 0.0},
                                      radius * glm::dvec2{1.0 + d.x, 1.0 - d.y}, s);
        if (!rim.empty()) {
            v.colour = rim[static_cast<std::size_t>(k % segments) % rim.size()];
        }
        return v;
    };
    SceneVertex middle = planar_vertex(centre, {radius, radius}, s);
    middle.colour = hub_colour;
    for (int k = 0; k < segments; ++k) {
        mesh.triangles.push_back({middle, rim_vertex(k), rim_vertex(k + 1)});
    }
}

/// A primitive a [[mesh]] may name: its name, its own keys, and the reader that fills
/// mesh.triangles from them.
struct Primitive {
    const char* name;
    std::vector<std::string> keys;
    void (*read)(const TableReader& t, SceneMesh& mesh);
    MeshKind kind; ///< whether its corners may each have a normal
};

const std::vector<Primitive>& primitives() {
    static const std::vector<Primitive> table = {
        {"triangles",
         {"positions", "uv", "colours"},
         read_triangles,
         MeshKind::primitive_with_normals},
        {"quad",
         {"corners", "uv", "colours"},
         read_quad,
         MeshKind::primitive_with_normals},
        {"box", {"centre", "size", "texels_per_unit"}, read_box, MeshKind::primitive},
        {"floor", {"y", "x", "z", "texels_per_unit"}, read_floor, MeshKind::primitive},
        {"fan",
         {"centre", "radius", "segments", "rim_colours", "centre_colour",
          "texels_per_unit"},
         read_fan,
         MeshKind::primitive},
    };
    return table;
}

/// A [[mesh]] of a primitive: the primitive first, as it decides which keys are allowed.
SceneMesh read_mesh(const Context& c, const toml::table& table, const std::string& path,
                    const Scene& scene) {
    const toml::node* kind_node = table.get("primitive");
    if (kind_node == nullptr) {
        c.fail(table.source(), path,
               "the required key 'primitive' (or 'file', for a model) is missing");
    }
    std::vector<std::string> names;
    for (const Primitive& p : primitives()) {
        names.push_back(p.name);
    }
    const Primitive& primitive =
        primitives()[read_choice(c, *kind_node, path + ".primitive", names)];
    std::vector<std::string> allowed = mesh_option_keys(primitive.kind);
    allowed.insert(allowed.end(), primitive.keys.begin(), primitive.keys.end());
    allowed.insert(allowed.end(), transform_keys().begin(), transform_keys().end());
    const TableReader t(c, table, path, allowed);
    SceneMesh mesh;
    read_mesh_options(t, scene, primitive.kind, mesh);
    primitive.read(t, mesh);
    const MeshTransform transform = read_transform(t);
    t.finish();
    place_and_check(c, table, path, mesh, transform);
    return mesh;
}

} // namespace

const std::vector<std::string>& mesh_option_keys(MeshKind kind) {
    static const std::vector<std::string> primitive{
        "primitive", "name",    "texture", "wrap",     "colour",
        "cull",      "normals", "shading", "specular", "shininess"};
    static const std::vector<std::string> model{
        "file", "name", "wrap", "cull", "normals", "shading", "specular", "shininess"};
    return kind == MeshKind::model ? model : primitive;
}

void read_mesh_options(const TableReader& t, const Scene& scene, MeshKind kind,
                       SceneMesh& mesh) {
    const Context& c = t.context();
    const bool model = kind == MeshKind::model;
    mesh.name = t.path();
    mesh.origin = fmt::format("{}:{}:{}: {}", c.file, t.table().source().begin.line,
                              t.table().source().begin.column, t.path());
    if (const auto* n = t.find("name")) {
        mesh.name = read_string(c, *n, t.child("name"));
    }
    if (const auto* n = model ? nullptr : t.find("texture")) {
        const std::string name = read_string(c, *n, t.child("texture"));
        const auto found =
            std::find_if(scene.textures.begin(), scene.textures.end(),
                         [&](const SceneTexture& s) { return s.name == name; });
        if (found == scene.textures.end()) {
            c.fail(n->source(), t.child("texture"),
                   fmt::format("no texture named '{}' under [textures]", name));
        }
        mesh.texture = static_cast<std::size_t>(found - scene.textures.begin());
    }
    if (const auto* n = t.find("wrap")) {
        mesh.wrap = read_enum(c, *n, t.child("wrap"), {"repeat", "clamp"},
                              std::array{Wrap::repeat, Wrap::clamp});
    }
    if (const auto* n = model ? nullptr : t.find("colour")) {
        mesh.colour = read_colour(c, *n, t.child("colour"));
    }
    if (const auto* n = t.find("cull")) {
        mesh.cull_back = read_choice(c, *n, t.child("cull"), {"none", "back"}) == 1;
    }
    if (const auto* n = t.find("normals"); model) { // "given": the OBJ's vn
        if (n != nullptr) {
            mesh.normals =
                read_enum(c, *n, t.child("normals"), {"face", "smooth", "given"},
                          std::array{NormalSource::face, NormalSource::smooth,
                                     NormalSource::given});
        }
    } else if (n != nullptr && !n->is_array()) {
        mesh.normals = read_enum(c, *n, t.child("normals"), {"face", "smooth"},
                                 std::array{NormalSource::face, NormalSource::smooth});
    } else if (n != nullptr && kind != MeshKind::primitive_with_normals) {
        c.fail(n->source(), t.child("normals"),
               "one normal per vertex is possible only for \"triangles\" and \"quad\" "
               "(here: \"face\" or \"smooth\")");
    }
    if (const auto* n = t.find("shading")) {
        mesh.shading = read_enum(c, *n, t.child("shading"), {"gouraud", "phong"},
                                 std::array{Shading::gouraud, Shading::phong});
    }
    if (const auto* n = t.find("specular")) {
        mesh.specular = read_colour(c, *n, t.child("specular"));
    }
    if (const auto* n = t.find("shininess")) {
        mesh.shininess = read_number(c, *n, t.child("shininess"), 1.0, max_shininess);
    }
}

const std::vector<std::string>& transform_keys() {
    static const std::vector<std::string> keys{"translate", "rotate", "scale"};
    return keys;
}

MeshTransform read_transform(const TableReader& t) {
    const Context& c = t.context();
    MeshTransform transform;
    if (const auto* n = t.find("scale")) { // a number or three factors, each > 0
        if (n->is_array()) {
            const toml::array& array = read_array(c, *n, t.child("scale"), 3, 3);
            for (int k = 0; k < 3; ++k) {
                transform.scale[k] =
                    read_positive(c, *array.get(static_cast<std::size_t>(k)),
                                  fmt::format("{}[{}]", t.child("scale"), k), 0.0, 1e6);
            }
        } else {
            transform.scale =
                glm::dvec3{read_positive(c, *n, t.child("scale"), 0.0, 1e6)};
        }
    }
    if (const auto* n = t.find("rotate")) { // three angles in degrees
        transform.rotate_degrees = read_vector<3>(c, *n, t.child("rotate"), -3600, 3600);
    }
    if (const auto* n = t.find("translate")) {
        transform.translate = read_point(c, *n, t.child("translate"));
    }
    return transform;
}

void place_and_check(const Context& c, const toml::table& table, const std::string& path,
                     SceneMesh& mesh, const MeshTransform& transform) {
    try {
        transform_mesh(mesh, transform);
    } catch (const Error& error) {
        c.fail(table.source(), path, error.what());
    }
    for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
        const auto& tri = mesh.triangles[k];
        for (const SceneVertex& v : tri) {
            for (int i = 0; i < 3; ++i) {
                if (!(std::abs(v.position[i]) <= world_limit)) {
                    c.fail(table.source(), path,
                           fmt::format("{} reaches {} after the transform, "
                                       "beyond the world's +-{}",
                                       triangle_name(mesh, k), v.position[i],
                                       world_limit));
                }
            }
        }
        // A triangle of zero area in the world has no plane to interpolate on: reject
        // it here rather than draw nothing later.
        const glm::dvec3 e1 = tri[1].position - tri[0].position;
        const glm::dvec3 e2 = tri[2].position - tri[0].position;
        const double area2 = glm::length(glm::cross(e1, e2));
        if (!(area2 > 1e-12 * glm::length(e1) * glm::length(e2))) {
            c.fail(table.source(), path,
                   fmt::format("{} is degenerate (its corners are collinear or "
                               "coincide, so it has no area)",
                               triangle_name(mesh, k)));
        }
    }
    share_positions(mesh); // the geometry stage moves each distinct position once
}

void read_meshes(const Context& c, const toml::node& node, Scene& scene,
                 long long& texture_bytes) {
    const toml::array& list =
        read_array(c, node, "mesh", 1, static_cast<std::size_t>(max_scene_meshes));
    ModelCache models;
    long long triangles = 0;
    for (std::size_t k = 0; k < list.size(); ++k) {
        const std::string path = fmt::format("mesh[{}]", k);
        const toml::node& entry = *list.get(k);
        const toml::table& table = read_table(c, entry, path);
        const std::size_t before = scene.meshes.size();
        if (table.contains("file")) {
            read_model(c, table, path, scene, models, texture_bytes, triangles);
        } else {
            scene.meshes.push_back(read_mesh(c, table, path, scene));
        }
        for (std::size_t m = before; m < scene.meshes.size(); ++m) {
            triangles += static_cast<long long>(scene.meshes[m].triangles.size());
        }
        if (triangles > max_scene_triangles) {
            c.fail(
                entry.source(), path,
                fmt::format("the scene has more than {} triangles", max_scene_triangles));
        }
        if (scene.meshes.size() > static_cast<std::size_t>(max_scene_meshes)) {
            c.fail(entry.source(), path,
                   fmt::format("the scene has more than {} meshes (each material of a "
                               "model is one)",
                               max_scene_meshes));
        }
    }
}

} // namespace exactpixels::scene_format
