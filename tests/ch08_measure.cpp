// Chapter 8 tests, part 4: the measurement. The chapter's claims about which filter is
// closer to the reference are checked here against freshly computed errors, so the text
// cannot state an ordering that the data does not show.
#include "exactpixels/lab/filter_measure.hpp"
#include "exactpixels/texture/ewa.hpp"
#include "support/measured_facts.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

using namespace exactpixels;
using exactpixels::testing::record_fact;

namespace {

/// Every configuration's image of the scene, by name.
std::map<std::string, std::vector<LinearTexel>> images_of(const FilterScene& fs) {
    std::map<std::string, std::vector<LinearTexel>> images;
    for (const FilterConfig& c : filter_configs()) {
        images[c.name] = filter_image(fs, c);
    }
    return images;
}

/// Every image's error against `reference` on the selected pixels, by name.
std::map<std::string, double>
errors_against(const std::map<std::string, std::vector<LinearTexel>>& images,
               const std::vector<LinearTexel>& reference,
               const std::vector<bool>& selected) {
    std::map<std::string, double> e;
    for (const auto& [name, image] : images) {
        e[name] = rms_code_error(image, reference, selected);
    }
    return e;
}

/// Every configuration's error on the scene, by name: on the minified pixels, or on all
/// pixels when `all` is set.
std::map<std::string, double> errors_on(const AccuracyScene& scene, bool all = false) {
    const FilterScene fs = prepare_filter_scene(scene);
    const std::map<std::string, double> e =
        errors_against(images_of(fs), reference_image(fs),
                       all ? std::vector<bool>{} : minified_pixels(fs));
    for (const auto& [name, error] : e) {
        MESSAGE(scene.name << " " << name << ": " << error);
    }
    return e;
}

/// The configuration of filter_configs() named `name`.
FilterConfig config_named(const std::string& name) {
    for (const FilterConfig& c : filter_configs()) {
        if (c.name == name) {
            return c;
        }
    }
    FAIL("no configuration named " << name);
    return {};
}

} // namespace

TEST_CASE(
    "nearest from 8-bit texels draws the same pixels as nearest through linear light") {
    // The baseline copies the texel floor(u), floor(v) as stored; the linear-light chain
    // picks the same texel, decodes it and encodes it again, which gives back every code
    // (the round-trip test of ch08_bilinear.cpp). So the two frames agree at every pixel
    // of every scene, not just on average.
    const FilterConfig stored = config_named("nearest");
    const FilterConfig light = config_named("nearest linear-light");
    CHECK(stored.path == TexelPath::as_stored);
    CHECK(light.path == TexelPath::linear_light);
    std::vector<AccuracyScene> scenes = filter_scenes();
    scenes.push_back(oblique_wall_scene());
    for (const AccuracyScene& scene : scenes) {
        const FilterScene fs = prepare_filter_scene(scene);
        Framebuffer a(scene.width, scene.height, rgba(1, 2, 3));
        Framebuffer b(scene.width, scene.height, rgba(1, 2, 3));
        filter_frame(a, fs, stored);
        filter_frame(b, fs, light);
        long differ = 0, dark = 0;
        for (const FilterPixel& p : fs.pixels) {
            differ += a.at(p.x, p.y) == b.at(p.x, p.y) ? 0 : 1;
            dark += a.at(p.x, p.y).r < 128 ? 1 : 0;
        }
        MESSAGE(scene.name << ": " << fs.pixels.size() << " pixels, " << dark
                           << " on dark texels, " << differ << " differ");
        CHECK(differ == 0);
        // Not a blank frame: both colours of the pattern appear.
        CHECK(dark > 0);
        CHECK(dark < static_cast<long>(fs.pixels.size()));
        // And the images the errors are computed from agree too.
        CHECK(filter_image(fs, stored) == filter_image(fs, light));
    }
}

TEST_CASE("the reference of a pixel inside one texel is that texel, exactly") {
    // On the facing wall a pixel covers half a texel each way; where its centre is a
    // texel centre (odd columns and rows of the quad) the whole pixel lies in that texel.
    const AccuracyScene wall = wall_facing_scene();
    const FilterScene fs = prepare_filter_scene(wall);
    const std::vector<LinearTexel> reference = reference_image(fs);
    int inside = 0;
    for (std::size_t k = 0; k < fs.pixels.size(); ++k) {
        const TexCoord uv = fs.pixels[k].uv;
        if (uv.x - std::floor(uv.x) == 0.5 && uv.y - std::floor(uv.y) == 0.5) {
            ++inside;
            const int i = static_cast<int>(std::floor(uv.x)) % wall.texture.width();
            const int j = static_cast<int>(std::floor(uv.y)) % wall.texture.height();
            REQUIRE(reference[k] == decode_texel(wall.texture.texel(i, j)));
        }
    }
    CHECK(inside == static_cast<int>(fs.pixels.size()) / 4);
}

TEST_CASE("the exact reference weights each texel by the area of the pixel it covers") {
    // An affine mapping with u = 2x + 2y: the texel edges u = i cross every pixel as
    // diagonals half a pixel apart, and cut it into four pieces of areas 1/8, 3/8, 3/8
    // and 1/8, one for each texel of a 4 x 1 texture. Whole-number corners and planes
    // keep every cut, area and sum exact, so the reference must be the weighted mean
    // exactly.
    const std::vector<Rgba8> texels{rgba(200, 30, 30), rgba(30, 200, 30),
                                    rgba(30, 30, 200), rgba(250, 250, 250)};
    const auto corner = [](double x, double y) {
        return TexturedVertex{{x, y}, 1.0, {2 * x + 2 * y, 0.5}};
    };
    const AccuracyScene diagonal{"diagonal",
                                 16,
                                 16,
                                 {{corner(0, 0), corner(32, 0), corner(0, 32)}},
                                 {4, 1, texels}};
    const FilterScene fs = prepare_filter_scene(diagonal);
    const std::vector<LinearTexel> reference = reference_image(fs);
    REQUIRE(fs.pixels.size() == 16u * 16u);
    for (std::size_t k = 0; k < fs.pixels.size(); ++k) {
        const FilterPixel& p = fs.pixels[k];
        const int first = 2 * (p.x + p.y); // u at the pixel's top-left corner
        const auto texel = [&](int i) { return decode_texel(texels[(first + i) % 4]); };
        const LinearTexel expected =
            (texel(0) + 3.0 * texel(1) + 3.0 * texel(2) + texel(3)) / 8.0;
        CHECK(reference[k] == expected);
    }
}

// The stub of ch08-error (every error 0) breaks it: no gap is left.
TEST_CASE("jittered sampling converges on the exact reference within the filters' gaps" *
          doctest::description("points: 1; exercise: ch08-error")) {
    // The reference has no samples to add: it is exact up to rounding, and what could be
    // wrong is its bookkeeping of the pieces. So it is checked against an independent
    // estimate of the same mean, n x n jittered samples per pixel (seeded: the same in
    // every run). For every filter and scene, the error against the estimate must close
    // in on the error against the exact reference as n doubles (each doubling at least
    // halves the largest distance), and at n = 32 be within `tolerance` of it, with the
    // order of every two filters the same; from n = 16 to 32 no error may move by more
    // than `doubling`. The tolerance must be under a fifth of the smallest gap between
    // two filters whose order the chapter states (on the minified pixels).
    constexpr double tolerance = 0.1; // codes
    constexpr double doubling = 0.25; // codes
    struct Stated {
        const char* scene;
        const char* better;
        const char* worse;
    };
    const Stated stated[] = {
        {"horizon", "bilinear", "nearest"},
        {"horizon", "mip-nearest", "bilinear"},
        {"horizon", "trilinear", "mip-nearest"},
        {"horizon", "anisotropic-4", "trilinear"},
        {"horizon", "anisotropic-16", "anisotropic-4"},
        {"horizon", "ewa", "anisotropic-16"},
        {"horizon", "trilinear", "trilinear per-triangle"},
        {"field", "bilinear", "nearest"},
        {"field", "mip-nearest", "nearest"},
        {"field", "trilinear", "bilinear"},
        {"field", "anisotropic-16", "trilinear"},
        {"field", "ewa", "anisotropic-16"},
        {"floor", "ewa", "anisotropic-16"},
        {"floor", "ewa", "trilinear"},
    };
    double distance_8 = 0.0, distance_16 = 0.0, distance_32 = 0.0, moved = 0.0;
    double smallest_gap = 1e9;
    for (const AccuracyScene& scene :
         {horizon_floor_scene(), random_field_scene(), grazing_floor_scene()}) {
        const FilterScene fs = prepare_filter_scene(scene);
        const std::vector<bool> minified = minified_pixels(fs);
        const auto images = images_of(fs);
        const auto exact = errors_against(images, reference_image(fs), minified);
        std::map<int, std::map<std::string, double>> sampled;
        std::map<int, double> distance;
        for (int n : {8, 16, 32}) {
            sampled[n] = errors_against(
                images, sampled_reference_image(fs, n, SamplePattern::jittered, minified),
                minified);
            for (const auto& [name, error] : exact) {
                distance[n] = std::max(distance[n], std::abs(sampled[n][name] - error));
            }
        }
        for (const auto& [name_binding, error] : exact) {
            // Named copies for CHECK_MESSAGE, whose message is a lambda (Clang 14 cannot
            // capture structured bindings).
            const std::string& name = name_binding;
            moved = std::max(moved, std::abs(sampled[32][name] - sampled[16][name]));
            for (const auto& [other_binding, other_error] : exact) {
                const std::string& other = other_binding;
                if (error < other_error) { // the same order against the estimate
                    CHECK_MESSAGE(sampled[32][name] < sampled[32][other],
                                  scene.name << ": " << name << " and " << other);
                }
            }
        }
        MESSAGE(scene.name << ": largest distance from the exact reference's errors at "
                              "8, 16, 32 samples a side: "
                           << distance[8] << ", " << distance[16] << ", "
                           << distance[32]);
        CHECK(distance[16] <= 0.5 * distance[8]);
        CHECK(distance[32] <= 0.5 * distance[16]);
        CHECK(distance[32] <= tolerance);
        distance_8 = std::max(distance_8, distance[8]);
        distance_16 = std::max(distance_16, distance[16]);
        distance_32 = std::max(distance_32, distance[32]);
        for (const Stated& s : stated) {
            if (scene.name == s.scene) {
                const double gap = exact.at(s.worse) - exact.at(s.better);
                CHECK_MESSAGE(gap > 0.0,
                              s.scene << ": " << s.better << " against " << s.worse);
                smallest_gap = std::min(smallest_gap, gap);
            }
        }
    }
    MESSAGE("largest move from 16 to 32 samples a side: "
            << moved << "; smallest stated gap: " << smallest_gap);
    CHECK(moved <= doubling);
    CHECK(5 * tolerance < smallest_gap);
    record_fact("ch08_jittered_distance_8", distance_8);
    record_fact("ch08_jittered_distance_16", distance_16);
    record_fact("ch08_jittered_distance_32", distance_32);
    record_fact("ch08_jittered_doubling", moved);
    record_fact("ch08_jittered_tolerance", tolerance);
    record_fact("ch08_smallest_stated_gap", smallest_gap);
}

TEST_CASE(
    "on the facing wall bilinear matches the reference exactly and nearest does not" *
    doctest::description("points: 1; exercise: ch08-error")) {
    // Two pixels per texel, every other pixel centre on a texel edge: the pixel straddles
    // the edge half and half, which is exactly bilinear's 1/2, 1/2 at the tie.
    const std::map<std::string, double> e = errors_on(wall_facing_scene(), true);
    CHECK(e.at("bilinear") == 0.0);
    CHECK(e.at("trilinear") == 0.0);
    CHECK(e.at("nearest") > 0.0);
}

TEST_CASE("on the horizon the error falls filter by filter, nearest to anisotropic" *
          doctest::description("points: 2; exercise: ch08-error")) {
    const std::map<std::string, double> e = errors_on(horizon_floor_scene());
    CHECK(e.at("bilinear") < e.at("nearest"));
    CHECK(e.at("mip-nearest") < e.at("bilinear"));
    CHECK(e.at("trilinear") < e.at("mip-nearest"));
    CHECK(e.at("anisotropic-4") < e.at("trilinear"));
    CHECK(e.at("anisotropic-16") <= e.at("anisotropic-4"));
    // One level per triangle gives back most of what trilinear gained: its error is
    // nearer bilinear's than trilinear's.
    const double per_triangle = e.at("trilinear per-triangle");
    CHECK(std::abs(per_triangle - e.at("bilinear")) <
          std::abs(per_triangle - e.at("trilinear")));
}

TEST_CASE(
    "on the random field anisotropic beats trilinear, which beats bilinear and nearest" *
    doctest::description("points: 1; exercise: ch08-error")) {
    const std::map<std::string, double> e = errors_on(random_field_scene());
    CHECK(e.at("bilinear") < e.at("nearest"));
    CHECK(e.at("mip-nearest") < e.at("nearest"));
    CHECK(e.at("trilinear") < e.at("bilinear"));
    CHECK(e.at("anisotropic-16") < e.at("trilinear"));
    // Small triangles: the level hardly changes across one, so per-triangle derivatives
    // cost little there (within 10% of per-pixel trilinear).
    CHECK(std::abs(e.at("trilinear per-triangle") - e.at("trilinear")) <
          0.1 * e.at("trilinear"));
}

// Not an exercise test: the stub of ch08-derivatives (every level 0) stays within the
// bound, so a fresh kit passes it.
TEST_CASE("per-span derivatives stay within the derived bound on every scene") {
    // Each pixel's per-span level differs from its exact level by at most @eq:level-bound
    // from the span's middle to the pixel (levels clamped at 0, which only shrinks the
    // difference), up to 1e-9 of rounding; the bound must be finite (g- > 0) everywhere.
    // Per-triangle derivatives obey the same bound from the centroid wherever it is
    // finite (far from the centroid g- can reach 0, and then it says nothing).
    // Per-triangle derivatives are worse than per-span ones on every scene with
    // minified pixels, at their worst and on average.
    for (const AccuracyScene& scene : filter_scenes()) {
        const FilterScene fs = prepare_filter_scene(scene);
        std::size_t bounded = 0;
        for (const FilterPixel& p : fs.pixels) {
            const auto& tri = scene.triangles[static_cast<std::size_t>(p.triangle)];
            const double bound =
                level_change_bound(tri, p.span_middle, pixel_centre(p.x, p.y));
            REQUIRE(std::isfinite(bound));
            const double error = std::abs(std::max(isotropic_level(p.span_wide), 0.0) -
                                          std::max(isotropic_level(p.exact), 0.0));
            CHECK(error <= bound + 1e-9);
            // The same bound from the centroid, where it says anything (g- > 0).
            const Point2 centroid =
                (tri[0].position + tri[1].position + tri[2].position) / 3.0;
            const double from_centroid =
                level_change_bound(tri, centroid, pixel_centre(p.x, p.y));
            const double triangle_error =
                std::abs(std::max(isotropic_level(p.triangle_wide), 0.0) -
                         std::max(isotropic_level(p.exact), 0.0));
            CHECK(triangle_error <= from_centroid + 1e-9);
            bounded += std::isfinite(from_centroid) ? 1 : 0;
        }
        MESSAGE(scene.name << ": per-triangle pixels with a finite bound: " << bounded
                           << " of " << fs.pixels.size());
        const LevelErrors span = level_errors(fs, Derivatives::per_span);
        const LevelErrors tri = level_errors(fs, Derivatives::per_triangle);
        MESSAGE(scene.name << ": span worst " << span.worst << " mean " << span.mean
                           << " changed " << span.changed << " bound " << span.worst_bound
                           << "; triangle worst " << tri.worst << " mean " << tri.mean
                           << " changed " << tri.changed);
        CHECK(span.worst <= span.worst_bound + 1e-9);
        const std::vector<bool> minified = minified_pixels(fs);
        if (std::count(minified.begin(), minified.end(), true) > 0) {
            CHECK(span.worst < tri.worst);
            CHECK(span.mean < tri.mean);
        }
    }
}

// The stub of ch08-error (every error 0) breaks it.
TEST_CASE("the elliptical weighted average is the closest filter to the reference" *
          doctest::description("points: 1; exercise: ch08-error")) {
    // Heckbert's EWA weights the texels of the whole footprint by a Gaussian of the
    // pixel's second moments: on the minified pixels of the horizon and the random field
    // it is closer to the reference than every other filter, anisotropic-16 included.
    for (const AccuracyScene& scene : {horizon_floor_scene(), random_field_scene()}) {
        const std::map<std::string, double> e = errors_on(scene);
        for (const auto& [name_binding, error] : e) {
            const std::string& name = name_binding; // CHECK_MESSAGE captures it
            if (name != "ewa") {
                CHECK_MESSAGE(e.at("ewa") < error,
                              scene.name << ": ewa against " << name);
            }
        }
    }
}

TEST_CASE("the elliptical weighted average of a constant texture is that constant") {
    // The weights are normalised: whatever the footprint, a uniform texture comes back
    // unchanged (to rounding), on every level the sample may read.
    const Texture grey =
        checkerboard_texture(16, 16, 1, rgba(90, 90, 90), rgba(90, 90, 90));
    const MipChain chain = build_mip_chain(grey);
    const double expected = srgb_to_linear16(90);
    for (const TexelDerivatives d :
         {TexelDerivatives{0.25, 0, 0, 0.25}, TexelDerivatives{3, 1, -1, 2},
          TexelDerivatives{0.5, 0, 0, 300}, TexelDerivatives{40, 30, -3, 4}}) {
        const LinearTexel c = sample_ewa(chain, {5.3, 7.9}, d, Wrap::repeat);
        CHECK(c.r == doctest::Approx(expected).epsilon(1e-12));
        CHECK(c.a == doctest::Approx(65535.0).epsilon(1e-12));
    }
}

// The stub of ch08-derivatives (no footprint) minifies nothing, so this grades it too.
TEST_CASE("the oblique wall of the exercise: every pixel minified, at most 4 probes" *
          doctest::description("points: 1; exercise: ch08-derivatives")) {
    // What the exercise's solution relies on: the wall at 60 degrees minifies every
    // pixel it covers, and its footprint is never more than 4 times longer than wide,
    // so 4 probes are all the anisotropic filter uses (16 add nothing).
    const AccuracyScene wall = oblique_wall_scene();
    const FilterScene fs = prepare_filter_scene(wall);
    const std::vector<bool> minified = minified_pixels(fs);
    REQUIRE(fs.pixels.size() > 20000);
    CHECK(std::count(minified.begin(), minified.end(), true) ==
          static_cast<long>(fs.pixels.size()));
    int most_probes = 0;
    double worst_depth = 0.0, nearest_depth = 1e9;
    for (const FilterPixel& p : fs.pixels) {
        most_probes = std::max(most_probes, anisotropy(p.exact, 16).probes);
    }
    for (const auto& triangle : wall.triangles) {
        for (const TexturedVertex& v : triangle) {
            worst_depth = std::max(worst_depth, v.w);
            nearest_depth = std::min(nearest_depth, v.w);
        }
    }
    MESSAGE("most probes: ", most_probes, ", depth ", nearest_depth, " to ", worst_depth);
    CHECK(most_probes <= 4);
    CHECK(most_probes >= 2); // stretched, though: the wall is not seen head-on
    CHECK(nearest_depth == doctest::Approx(4.0 - 3.0 * std::sin(std::acos(-1.0) / 3)));
    CHECK(worst_depth == doctest::Approx(4.0 + 3.0 * std::sin(std::acos(-1.0) / 3)));
}
