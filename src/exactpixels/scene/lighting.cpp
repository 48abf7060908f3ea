#include "exactpixels/scene/lighting.hpp"

#include "exactpixels/texture/srgb.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace exactpixels {

//> face-normal
glm::dvec3 face_normal(const std::array<SceneVertex, 3>& t) {
    // World space is left-handed (x right, y up, z forward): corners counter-clockwise
    // seen from the front give a cross product e1 x e2 that points to the back.
    const glm::dvec3 e1 = t[1].position - t[0].position;
    const glm::dvec3 e2 = t[2].position - t[0].position;
    return glm::normalize(glm::cross(e2, e1));
}
//< face-normal

//> smooth-normals
std::vector<CornerNormals> mesh_normals(const SceneMesh& mesh) {
    std::vector<CornerNormals> normals(mesh.triangles.size());
    if (mesh.normals == NormalSource::given) {
        for (std::size_t t = 0; t < normals.size(); ++t) {
            for (std::size_t k = 0; k < 3; ++k) {
                normals[t][k] = mesh.triangles[t][k].normal; // unit (the loader checks)
            }
        }
        return normals;
    }
    if (mesh.normals == NormalSource::face) {
        for (std::size_t t = 0; t < normals.size(); ++t) {
            const glm::dvec3 n = face_normal(mesh.triangles[t]);
            normals[t] = {n, n, n};
        }
        return normals;
    }
    // Smooth: |e2 x e1| is twice the triangle's area, so summing the unnormalised cross
    // products weights each face by its area (@eq:scene-smooth-normal).
    using Key = std::tuple<double, double, double>;
    std::map<Key, glm::dvec3> sum;
    const auto key = [](glm::dvec3 p) { return Key{p.x, p.y, p.z}; };
    for (const auto& t : mesh.triangles) {
        const glm::dvec3 area2 =
            glm::cross(t[2].position - t[0].position, t[1].position - t[0].position);
        for (const SceneVertex& v : t) {
            sum[key(v.position)] += area2;
        }
    }
    for (std::size_t t = 0; t < normals.size(); ++t) {
        for (std::size_t k = 0; k < 3; ++k) {
            const glm::dvec3 s = sum[key(mesh.triangles[t][k].position)];
            // Faces that cancel exactly (a sheet folded flat) leave the face normal.
            normals[t][k] =
                glm::length(s) > 0.0 ? glm::normalize(s) : face_normal(mesh.triangles[t]);
        }
    }
    return normals;
}
//< smooth-normals

std::vector<CornerNormals>
mesh_normals_shared(const SceneMesh& mesh, const std::vector<glm::dvec3>& positions,
                    const std::vector<std::array<std::uint32_t, 3>>& corners) {
    // Equal as doubles is equal as bits for finite values, but for 0 and -0.
    const auto alike = [](double c) {
        return std::isfinite(c) && !(c == 0.0 && std::signbit(c));
    };
    const auto merged_alike = [&](const glm::dvec3& p) {
        return alike(p.x) && alike(p.y) && alike(p.z);
    };
    if (mesh.normals != NormalSource::smooth ||
        !std::all_of(positions.begin(), positions.end(), merged_alike)) {
        return mesh_normals(mesh);
    }
    // The map's sums, in its order: each position's faces added triangle by triangle.
    std::vector<glm::dvec3> sum(positions.size(), glm::dvec3{0.0});
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const std::array<SceneVertex, 3>& v = mesh.triangles[t];
        const glm::dvec3 area2 =
            glm::cross(v[2].position - v[0].position, v[1].position - v[0].position);
        for (const std::uint32_t at : corners[t]) {
            sum[at] += area2;
        }
    }
    std::vector<CornerNormals> normals(mesh.triangles.size());
    for (std::size_t t = 0; t < normals.size(); ++t) {
        for (std::size_t k = 0; k < 3; ++k) {
            const glm::dvec3 s = sum[corners[t][k]];
            normals[t][k] =
                glm::length(s) > 0.0 ? glm::normalize(s) : face_normal(mesh.triangles[t]);
        }
    }
    return normals;
}

std::vector<ViewLight>
lights_in_view(const std::vector<SceneLight>& lights,
               const std::function<glm::dvec3(glm::dvec3, bool)>& to_view) {
    std::vector<ViewLight> out;
    for (const SceneLight& light : lights) {
        ViewLight v;
        v.type = light.type;
        v.radiance = light.intensity * colour_to_linear(light.colour); // linear light
        if (light.type == LightType::directional) {
            v.towards = -to_view(light.direction, false); // it travels along direction
        } else {
            v.position = to_view(light.position, true);
        }
        out.push_back(v);
    }
    return out;
}

//> light-colour
Incident incident(const ViewLight& light, glm::dvec3 p) {
    if (light.type == LightType::directional) {
        return {light.towards, light.radiance};
    }
    const glm::dvec3 d = light.position - p;
    // Nearer than min_light_distance the light counts as that far: no infinity, and a
    // light exactly at p (d = 0, so l = 0) lights nothing there.
    const double d2 = std::max(glm::dot(d, d), min_light_distance * min_light_distance);
    return {d / std::sqrt(d2), light.radiance / d2}; // the inverse-square law
}

Colour light_colour(const std::vector<ViewLight>& lights, const Colour& ambient,
                    const Colour& diffuse, const Material& material, glm::dvec3 p,
                    glm::dvec3 normal, glm::dvec3 to_eye) {
    // The colours are sRGB codes / 255: light adds and scales only in linear light, so
    // decode first and encode once, at the end (@eq:scene-colour-rule).
    Colour lambert = colour_to_linear(ambient), highlight{0.0, 0.0, 0.0};
    for (const ViewLight& light : lights) {
        const Incident in = incident(light, p);
        const double cosine = glm::dot(normal, in.towards);
        if (cosine <= 0.0) {
            continue; // the light is behind the surface
        }
        lambert += cosine * in.irradiance;
        const glm::dvec3 sum = in.towards + to_eye; // zero only for a grazing view
        if (glm::dot(sum, sum) > 0.0) {
            const double facing = std::max(0.0, glm::dot(normal, glm::normalize(sum)));
            highlight += std::pow(facing, material.shininess) * in.irradiance;
        }
    }
    return linear_to_colour(colour_to_linear(diffuse) * lambert +
                            colour_to_linear(material.specular) * highlight);
}
//< light-colour

Shading mesh_shading(const Scene& scene, const SceneMesh& mesh) {
    return mesh.shading.value_or(scene.options.shading);
}

} // namespace exactpixels
