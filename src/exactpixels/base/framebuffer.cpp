#include "exactpixels/base/framebuffer.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace exactpixels {

Rgba8 to_rgba8(const Colour& colour) {
    auto channel = [](double c) {
        return static_cast<std::uint8_t>(std::lround(std::clamp(c, 0.0, 1.0) * 255.0));
    };
    return {channel(colour.r), channel(colour.g), channel(colour.b), 255};
}

Framebuffer::Framebuffer(int width, int height, Rgba8 fill)
    : width_(width), height_(height),
      pixels_(static_cast<std::size_t>(std::max(width, 0)) *
                  static_cast<std::size_t>(std::max(height, 0)),
              fill) {
    assert(width >= 0 && height >= 0);
}

void Framebuffer::fill(Rgba8 colour) {
    std::fill(pixels_.begin(), pixels_.end(), colour);
}

std::size_t Framebuffer::index(int x, int y) const {
    assert(contains(x, y));
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(x);
}

} // namespace exactpixels
