// The span measurements of accuracy_scenes.hpp (pixel writes, depth ratios): the part of
// chapter 5's bench that walks chapter 1's row spans rather than drawing.
#include "exactpixels/lab/accuracy_scenes.hpp"

#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/raster/gradients.hpp"
#include "exactpixels/raster/scanline.hpp"

#include <algorithm>
#include <limits>

namespace exactpixels {

namespace {
std::array<FixedPoint2, 3> snapped(const std::array<TexturedVertex, 3>& t) {
    return {snap_to_subpixel(t[0].position), snap_to_subpixel(t[1].position),
            snap_to_subpixel(t[2].position)};
}
} // namespace

std::int64_t pixel_writes(const AccuracyScene& scene) {
    std::int64_t count = 0;
    for (const auto& triangle : scene.triangles) {
        scanline_spans(snapped(triangle), Viewport{scene.width, scene.height},
                       [&](Span s) { count += s.x_end - s.x_begin; });
    }
    return count;
}

std::string benchmark_name(const AccuracyScene& scene, const MapperConfig& mapper) {
    std::string name = scene.name + "/";
    for (const char c : mapper.name) {
        if (c != '+') {
            name += c == ' ' ? '_' : c;
        }
    }
    return name;
}

namespace {
/// Calls f(span, ratio, far) for every row span of the scene, ratio = max(w) / min(w)
/// between its first and last pixel centres (1/w is linear on screen) and far = max(w).
template <class F> void for_each_span_ratio(const AccuracyScene& scene, F&& f) {
    for (const auto& t : scene.triangles) {
        const std::array<FixedPoint2, 3> s = snapped(t);
        const std::array<Point2, 3> p{to_pixels(s[0]), to_pixels(s[1]), to_pixels(s[2])};
        const std::array<double, 3> q{1.0 / t[0].w, 1.0 / t[1].w, 1.0 / t[2].w};
        const Gradient<double> g = closed_form_gradient<double>(p, q);
        const auto one_w = [&](double x, double y) {
            return q[0] + g.dx * (x - p[0].x) + g.dy * (y - p[0].y);
        };
        scanline_spans(s, Viewport{scene.width, scene.height}, [&](Span span) {
            const double a = one_w(span.x_begin + 0.5, span.y + 0.5);
            const double b = one_w(span.x_end - 0.5, span.y + 0.5);
            f(span, std::max(a, b) / std::min(a, b), 1.0 / std::min(a, b));
        });
    }
}
} // namespace

std::vector<double> span_ratio_map(const AccuracyScene& scene) {
    std::vector<double> ratio(static_cast<std::size_t>(scene.width) *
                                  static_cast<std::size_t>(scene.height),
                              0.0);
    for_each_span_ratio(scene, [&](Span s, double r, double) {
        for (int x = s.x_begin; x < s.x_end; ++x) {
            ratio[static_cast<std::size_t>(s.y) * std::size_t(scene.width) +
                  std::size_t(x)] = r;
        }
    });
    return ratio;
}

std::vector<double> span_far_depth_map(const AccuracyScene& scene) {
    std::vector<double> far(static_cast<std::size_t>(scene.width) *
                                static_cast<std::size_t>(scene.height),
                            0.0);
    for_each_span_ratio(scene, [&](Span s, double, double w) {
        for (int x = s.x_begin; x < s.x_end; ++x) {
            far[static_cast<std::size_t>(s.y) * std::size_t(scene.width) +
                std::size_t(x)] = w;
        }
    });
    return far;
}

std::array<double, 2> span_depth_ratios(const AccuracyScene& scene) {
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for_each_span_ratio(scene, [&](Span s, double r, double) {
        if (s.x_end - s.x_begin >= 2) {
            lo = std::min(lo, r);
            hi = std::max(hi, r);
        }
    });
    return {lo, hi};
}

} // namespace exactpixels
