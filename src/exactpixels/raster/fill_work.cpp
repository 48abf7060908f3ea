#include "exactpixels/raster/fill_work.hpp"

#include <algorithm>

namespace exactpixels {

long long fill_work(const std::array<Point2, 3>& corners, Viewport viewport) {
    // The whole pixels the box [x0, x1] x [y0, y1] touches, clamped to the viewport
    // first so that a corner far outside (up to the guard band) cannot overflow.
    // On [0, size] floor is the conversion to int (it truncates towards zero) and ceil
    // one more where that dropped a fraction: no call to floor or ceil per triangle.
    const auto pixels = [](double lo, double hi, int size) -> long long {
        const double low = std::clamp(lo, 0.0, double(size));
        const double high = std::clamp(hi, 0.0, double(size));
        const long long first = static_cast<long long>(low);
        const long long whole = static_cast<long long>(high);
        const long long end = whole + (double(whole) < high ? 1 : 0);
        return std::max(0LL, end - first);
    };
    const auto [x0, x1] = std::minmax({corners[0].x, corners[1].x, corners[2].x});
    const auto [y0, y1] = std::minmax({corners[0].y, corners[1].y, corners[2].y});
    return pixels(x0, x1, viewport.width) * pixels(y0, y1, viewport.height);
}

} // namespace exactpixels
