#include "exactpixels/texture/bilinear.hpp"

#include <cassert>
#include <cmath>

namespace exactpixels {

std::int32_t to_texel_fixed(double u) {
    assert(std::abs(u) < 16384.0);
    return static_cast<std::int32_t>(std::floor(u * texel_scale + 0.5));
}

//> sample-bilinear
LinearTexel sample_bilinear(const LinearImage& image, std::int32_t U, std::int32_t V,
                            Wrap wrap) {
    const BilinearTaps t = bilinear_taps(U, V);
    const std::array<std::int64_t, 4> w = bilinear_weights(t);
    const int i0 = wrap_index(t.i, image.width, wrap);
    const int i1 = wrap_index(t.i + 1, image.width, wrap);
    const int j0 = wrap_index(t.j, image.height, wrap);
    const int j1 = wrap_index(t.j + 1, image.height, wrap);
    // Integer weights times whole linear units: every product and sum is exact in a
    // double (below 2^50), so the order of the four terms does not matter.
    const LinearTexel sum =
        double(w[0]) * image.at(i0, j0) + double(w[1]) * image.at(i1, j0) +
        double(w[2]) * image.at(i0, j1) + double(w[3]) * image.at(i1, j1);
    return sum * 0x1p-32; // divide by D^2: exact, a power of two
}
//< sample-bilinear

LinearTexel sample_bilinear(const LinearImage& image, TexCoord uv, Wrap wrap) {
    return sample_bilinear(image, to_texel_fixed(uv.x), to_texel_fixed(uv.y), wrap);
}

LinearTexel sample_nearest(const LinearImage& image, TexCoord uv, Wrap wrap) {
    const int i = static_cast<int>(std::floor(uv.x));
    const int j = static_cast<int>(std::floor(uv.y));
    return image.at(wrap_index(i, image.width, wrap), wrap_index(j, image.height, wrap));
}

} // namespace exactpixels
