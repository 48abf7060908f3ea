#include "exactpixels/scene/depth_precision.hpp"

#include "exactpixels/scene/depth_buffer.hpp"

#include <cassert>
#include <cmath>
#include <limits>

namespace exactpixels {

double nearness_depth_step(double w) {
    return depth_resolution(w) * w;
}

double fixed_z_depth_step(double w, double near, double far, int bits) {
    assert(0.0 < near && near < far && near <= w && w <= far && bits > 0 && bits < 53);
    const double levels = std::ldexp(1.0, bits) - 1.0;
    const double key = std::nearbyint(far * (w - near) / ((far - near) * w) * levels);
    // d = f (w - n) / ((f - n) w) solved for w: w = f n / (f - d (f - n)).
    const auto depth = [&](double d) { return far * near / (far - d * (far - near)); };
    return depth((key + 0.5) / levels) - depth((key - 0.5) / levels);
}

double reversed_z_depth_step(double w, double near, double far) {
    assert(0.0 < near && near < far && near <= w && w < far);
    const float key = static_cast<float>(near * (far - w) / ((far - near) * w));
    const float next = std::nextafter(key, std::numeric_limits<float>::infinity());
    const double above = 0.5 * (double(key) + double(next));
    const double below = 0.5 * (double(key) + double(std::nextafter(key, 0.0f)));
    // d = n (f - w) / ((f - n) w) solved for w: w = f n / (d (f - n) + n).
    const auto depth = [&](double d) { return far * near / (d * (far - near) + near); };
    return depth(below) - depth(above);
}

} // namespace exactpixels
