// Chapter 9's referee (@sec:scene-referee): every shipped scene drawn again by Mesa's
// llvmpipe through OSMesa, from the same snapped triangles, and compared pixel for pixel:
// coverage, the triangle that wins each pixel, colours within the derived tolerances
// (per-pixel lighting through a GLSL program, and a planted fault that it catches).
// Not a ch09_*.cpp file (the chapter's kit does not link OSMesa); label ch09 all the
// same.
#include <doctest/doctest.h>

#ifdef EXACTPIXELS_HAVE_OSMESA

#include "exactpixels/scene/scene_loader.hpp"
#include "referee/opengl_referee.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <string>

using namespace exactpixels;

namespace {

/// Every shipped scene compared once for the whole program (empty when OSMesa cannot
/// make a context; `skip` then says why).
const std::map<std::string, RefereeComparison>& comparisons(std::string& skip) {
    static std::string why;
    static const std::map<std::string, RefereeComparison> all = [] {
        std::map<std::string, RefereeComparison> made;
        if (!opengl_referee_ready(why)) {
            return made;
        }
        for (const std::string& name : referee_scene_names()) {
            made.emplace(
                name, referee_scene(load_scene(shipped_scene_folder() / (name + ".toml")),
                                    name));
        }
        return made;
    }();
    skip = why;
    return all;
}

std::string named(const std::vector<RefereePixel>& pixels) {
    std::string text;
    for (std::size_t k = 0; k < pixels.size() && k < 20; ++k) {
        text += fmt::format(" ({}, {})", pixels[k].x, pixels[k].y);
    }
    return text;
}

} // namespace

TEST_CASE("the referee draws every shipped scene, our ID pass being the renderer's") {
    std::string skip;
    const auto& all = comparisons(skip);
    if (all.empty()) {
        MESSAGE("SKIPPED: OSMesa cannot make a context: " << skip);
        return;
    }
    CHECK(all.size() == referee_scene_names().size());
    CHECK(all.size() >= 10);
    for (const auto& [name_, c_] : all) {
        // References, not structured bindings: a lambda (INFO's) captures them, which
        // Clang 14 cannot do with a binding.
        const auto& name = name_;
        const auto& c = c_;
        INFO(name);
        CHECK(c.triangles > 0);
        CHECK(c.covered > 0);
        // Every pixel the renderer drew is one our ID pass gives a triangle.
        CHECK(c.image_matches_ids);
        // Our scanline coverage is the exact integer edge functions' (chapter 2).
        CHECK(c.exact_differences == 0);
    }
}

TEST_CASE("llvmpipe covers the pixels the renderer covers on every shipped scene") {
    std::string skip;
    for (const auto& [name_, c_] : comparisons(skip)) {
        // References, not structured bindings: a lambda (INFO's) captures them, which
        // Clang 14 cannot do with a binding.
        const auto& name = name_;
        const auto& c = c_;
        INFO(name << ": differing pixels" << named(c.coverage_differences));
        // Where llvmpipe differs, ours is the exact answer (integer edge functions on the
        // snapped corners) at every such pixel.
        CHECK(c.coverage_exact.size() == c.coverage_differences.size());
        CHECK(c.coverage_differences.empty());
    }
}

TEST_CASE("llvmpipe's depth test picks the renderer's triangle except at near ties") {
    std::string skip;
    for (const auto& [name_, c_] : comparisons(skip)) {
        // References, not structured bindings: a lambda (INFO's) captures them, which
        // Clang 14 cannot do with a binding.
        const auto& name = name_;
        const auto& c = c_;
        INFO(name << ": " << c.depth_differences << " pixels" << named(c.depth_pixels)
                  << ", worst gap " << c.worst_depth_gap << " of the depth range");
        // Where llvmpipe picks another triangle, ours is DepthBuffer's rule on the two
        // planes, and the two surfaces are a tie at llvmpipe's single precision.
        CHECK(c.depth_ours_right);
        CHECK(c.worst_depth_gap < referee_depth_tie);
        CHECK(c.depth_differences <= 4);
    }
}

TEST_CASE("llvmpipe's colours are the renderer's within the derived tolerance") {
    std::string skip;
    for (const auto& [name_, c_] : comparisons(skip)) {
        // References, not structured bindings: a lambda (INFO's) captures them, which
        // Clang 14 cannot do with a binding.
        const auto& name = name_;
        const auto& c = c_;
        INFO(name << ": tolerance " << c.tolerance << ", worst " << c.worst_colour
                  << ", beyond " << c.colour_over << " (on texel edges " << c.texel_edge
                  << "), worst off edges " << c.worst_off_edge << "; lit per pixel "
                  << c.lit_compared << ", worst off edges " << c.worst_lit_off_edge
                  << ", float bound " << c.worst_lit_float << "; not compared "
                  << c.colour_uncompared << " (" << c.uncompared << ")");
        // Off texel edges every compared pixel is within the tolerance; on them
        // llvmpipe's single-precision coordinate may take the neighbouring texel, at
        // no more than one pixel in a thousand.
        CHECK((c.colour_compared > 0 || !c.uncompared.empty()));
        CHECK(c.colour_over == c.texel_edge);
        CHECK(c.worst_off_edge <= c.tolerance);
        CHECK(c.texel_edge * 1000 <= c.colour_compared);
        // Pixels are left out only for a named reason.
        CHECK((c.colour_uncompared == 0) == c.uncompared.empty());
        if (c.colour_uncompared > 0) {
            MESSAGE(name << ": " << c.colour_uncompared
                         << " pixels' colours not compared: " << c.uncompared);
        }
    }
}

TEST_CASE("llvmpipe lights per pixel as the renderer does, within one level") {
    std::string skip;
    int lit_scenes = 0;
    for (const auto& [name_, c_] : comparisons(skip)) {
        // References, not structured bindings: a lambda (INFO's) captures them, which
        // Clang 14 cannot do with a binding.
        const auto& name = name_;
        const auto& c = c_;
        if (c.phong_meshes == 0) {
            continue;
        }
        INFO(name << ": " << c.lit_compared << " lit pixels compared, worst off texel "
                  << "edges " << c.worst_lit_off_edge << " levels, GL's float moves "
                  << "the lit value by at most " << c.worst_lit_float << " levels");
        lit_scenes += 1;
        CHECK(c.lit_compared > 0);
        // @eq:scene-referee-lit: two roundings of 1/2 level and GL's float error below
        // 1 keep two integers less than 2 apart, so within referee_lit_levels.
        CHECK(c.worst_lit_float < 1.0);
        CHECK(c.worst_lit_off_edge <= referee_lit_levels);
    }
    CHECK(lit_scenes >= 2); // lit and lit_torus
}

TEST_CASE("a fault planted in llvmpipe's per-pixel lighting goes beyond the tolerance") {
    // The comparison can fail: light the codes without the sRGB decode, or raise the
    // Blinn-Phong exponent by 8, on GL's side only, and the lit pixels part.
    std::string skip;
    for (const auto& [name_, c_] : comparisons(skip)) {
        // References, not structured bindings: a lambda (INFO's) captures them, which
        // Clang 14 cannot do with a binding.
        const auto& name = name_;
        const auto& c = c_;
        if (c.phong_meshes == 0) {
            continue;
        }
        const Scene scene = load_scene(shipped_scene_folder() / (name + ".toml"));
        const RefereeComparison undecoded = referee_scene(scene, name, {true, 0.0});
        const RefereeComparison shinier = referee_scene(scene, name, {false, 8.0});
        INFO(name << ": beyond the tolerance off texel edges "
                  << undecoded.colour_over - undecoded.texel_edge
                  << " without the decode, " << shinier.colour_over - shinier.texel_edge
                  << " with s + 8");
        CHECK(undecoded.colour_over - undecoded.texel_edge > c.lit_compared / 2);
        CHECK(shinier.colour_over - shinier.texel_edge > 100);
        CHECK(shinier.worst_lit_off_edge > 2 * referee_lit_levels);
    }
}

TEST_CASE("where llvmpipe departs on triangles reaching far off screen, ours is exact") {
    // One corner in a 64 x 64 frame, two up to 2^19 px away: GL takes the corners
    // through its single-precision viewport transform and clipper before it snaps; the
    // renderer snaps the corners themselves.
    std::string why;
    if (!opengl_referee_ready(why)) {
        MESSAGE("SKIPPED: OSMesa cannot make a context: " << why);
        return;
    }
    const std::vector<ScreenTriangle> triangles = far_reaching_triangles(far_count);
    long long departures = 0, covered = 0;
    for (std::size_t n = 0; n < triangles.size(); ++n) {
        const ScreenTriangle& t = triangles[n];
        const CoverageComparison c = referee_coverage({t}, far_frame, far_frame);
        INFO("triangle " << n << ": pixels" << named(c.differences));
        CHECK(c.exact_differences == 0); // ours is the exact edge functions' answer
        CHECK(c.ours_exact.size() == c.differences.size());
        departures += static_cast<long long>(c.differences.size());
        covered += c.covered;
    }
    MESSAGE("llvmpipe departs at " << departures << " of " << covered << " pixels");
    CHECK(covered > 0);
}

#else

TEST_CASE("the referee draws every shipped scene, our ID pass being the renderer's") {
    MESSAGE("SKIPPED: OSMesa (libosmesa6-dev) was not found when CMake configured this "
            "build, so the OpenGL referee is not built");
}

#endif
