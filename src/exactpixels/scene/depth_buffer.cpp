#include "exactpixels/scene/depth_buffer.hpp"

#include <cassert>
#include <cmath>
#include <limits>

namespace exactpixels {

double depth_resolution(double w) {
    assert(w > 0.0);
    const float q = nearness_key(1.0 / w);
    const float nearer = std::nextafter(q, std::numeric_limits<float>::infinity());
    const float farther = std::nextafter(q, 0.0f);
    // Every 1/w between the midpoints to the neighbouring floats rounds to q: the depths
    // from 1 / (upper midpoint) to 1 / (lower midpoint) share one key.
    const double w_near = 1.0 / (0.5 * (double(q) + double(nearer)));
    const double w_far = 1.0 / (0.5 * (double(q) + double(farther)));
    return (w_far - w_near) / w;
}

double fixed_depth_resolution(double w, double near, int bits) {
    assert(near > 0.0 && near <= w && bits > 0 && bits < 53);
    const double scale = std::ldexp(near, bits); // key = round(scale / w)
    const double key = std::nearbyint(scale / w);
    // The depths whose scale / w rounds to the same key.
    return (scale / (key - 0.5) - scale / (key + 0.5)) / w;
}

} // namespace exactpixels
