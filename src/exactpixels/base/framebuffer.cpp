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
    : width_(width), height_(height) {
    assert(width >= 0 && height >= 0);
    // One row filled pixel by pixel, then copied whole into every row: a copy of whole
    // rows moves many pixels per instruction, the fill one (the frame's clear was 3.7M
    // instructions of the big torus's frame, 4 per pixel).
    const std::vector<Rgba8> row(static_cast<std::size_t>(std::max(width, 0)), fill);
    pixels_.reserve(row.size() * static_cast<std::size_t>(std::max(height, 0)));
    for (int y = 0; y < height; ++y) {
        pixels_.insert(pixels_.end(), row.begin(), row.end());
    }
}

void Framebuffer::fill(Rgba8 colour) {
    std::fill(pixels_.begin(), pixels_.end(), colour);
}

} // namespace exactpixels
