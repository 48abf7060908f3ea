#include "exactpixels/raster/fill_work.hpp"

#include <algorithm>
#include <cmath>

namespace exactpixels {

long long fill_work(const std::array<Point2, 3>& corners, Viewport viewport) {
    // The whole pixels the box [x0, x1] x [y0, y1] touches, clamped to the viewport
    // first so that a corner far outside (up to the guard band) cannot overflow.
    const auto pixels = [](double lo, double hi, int size) -> long long {
        const double first = std::floor(std::clamp(lo, 0.0, double(size)));
        const double end = std::ceil(std::clamp(hi, 0.0, double(size)));
        return static_cast<long long>(std::max(0.0, end - first));
    };
    const auto [x0, x1] = std::minmax({corners[0].x, corners[1].x, corners[2].x});
    const auto [y0, y1] = std::minmax({corners[0].y, corners[1].y, corners[2].y});
    return pixels(x0, x1, viewport.width) * pixels(y0, y1, viewport.height);
}

} // namespace exactpixels
