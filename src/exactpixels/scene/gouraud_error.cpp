#include "exactpixels/scene/gouraud_error.hpp"

#include "exactpixels/scene/mesh_transform.hpp"
#include "exactpixels/scene/scene_renderer.hpp"

#include <algorithm>
#include <cmath>

namespace exactpixels {

//> gouraud-error
GouraudError gouraud_perspective_error(const Scene& scene) {
    GouraudError total;
    double sum = 0.0;
    for (int channel = 0; channel < 3; ++channel) {
        // The channel becomes u on every vertex-coloured mesh (any texture will do: only
        // the coordinates are compared); other meshes stay untextured and only hide.
        Scene probe = scene;
        probe.textures.push_back({"gouraud probe", Texture(1, 1, {Rgba8{}}), {}});
        for (SceneMesh& mesh : probe.meshes) {
            if (!mesh.vertex_colours) {
                mesh.texture.reset();
                continue;
            }
            mesh.texture = probe.textures.size() - 1;
            for (std::array<SceneVertex, 3>& triangle : mesh.triangles) {
                for (SceneVertex& vertex : triangle) {
                    vertex.uv = {vertex.colour[channel], 0.0};
                }
            }
            share_positions(mesh); // the fast paths read uv from its copy (chapter 10)
        }
        probe.options.precision = Precision::float64;
        probe.options.mapper = {false,
                                {MapperKind::affine, 16}}; // the colour stage's line
        TexelMap gouraud(scene.width, scene.height);
        render_scene(probe, &gouraud);
        probe.options.mapper = {false, {MapperKind::exact, 16}}; // c/w over 1/w
        TexelMap correct(scene.width, scene.height);
        render_scene(probe, &correct);
        // |Gouraud - correct| over the pixels both maps cover.
        long long pixels = 0;
        for (std::size_t k = 0; k < correct.covered.size(); ++k) {
            if (correct.covered[k] && gouraud.covered[k]) {
                const double d = std::abs(gouraud.u[k] - correct.u[k]);
                total.worst = std::max(total.worst, d);
                sum += d;
                ++pixels;
            }
        }
        total.pixels = pixels;
    }
    total.mean = total.pixels > 0 ? sum / (3.0 * static_cast<double>(total.pixels)) : 0.0;
    return total;
}
//< gouraud-error

} // namespace exactpixels
