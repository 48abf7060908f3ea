// framebuffer.hpp: the image every rasterizer in the book draws into.
//
// Usage:
//   Framebuffer fb(64, 48, rgba(0, 0, 255));   // 64 x 48 pixels, filled blue
//   fb.at(3, 2) = rgba(255, 0, 0);             // pixel x = 3, y = 2 made red
//
// Layout: RGBA, 8 bits per channel, channels in the order r, g, b, a; rows stored top to
// bottom (row-major), so pixel (x, y) is element y * width + x. The origin is the
// top-left corner and y grows down, exactly as the PNG file stores it.
#pragma once

#include "exactpixels/base/types.hpp"

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace exactpixels {

/// One pixel: 8-bit red, green, blue and alpha, in that order in memory.
struct Rgba8 {
    std::uint8_t r = 0;   ///< red
    std::uint8_t g = 0;   ///< green
    std::uint8_t b = 0;   ///< blue
    std::uint8_t a = 255; ///< alpha (255 = opaque)
    /// Pixels are equal when all four channels are.
    friend constexpr bool operator==(Rgba8, Rgba8) = default;
};

/// An opaque pixel from 8-bit channel values.
constexpr Rgba8 rgba(std::uint8_t r, std::uint8_t g, std::uint8_t b,
                     std::uint8_t a = 255) {
    return {r, g, b, a};
}

/// The opaque 8-bit pixel nearest a linear colour; channels are clamped to [0, 1].
Rgba8 to_rgba8(const Colour& colour);

/// A width x height grid of Rgba8 pixels, row-major, origin top-left, y down.
class Framebuffer {
  public:
    /// A width x height frame filled with `fill`. Sizes must be >= 0.
    Framebuffer(int width, int height, Rgba8 fill = {});

    /// Width in pixels.
    int width() const { return width_; }
    /// Height in pixels.
    int height() const { return height_; }
    /// True when (x, y) names a pixel of the frame.
    bool contains(int x, int y) const {
        return x >= 0 && y >= 0 && x < width_ && y < height_;
    }

    //> framebuffer-at
    /// The pixel at column x, row y (row 0 is the top). (x, y) must be inside.
    Rgba8& at(int x, int y) { return pixels_[index(x, y)]; }
    /// The pixel at column x, row y (row 0 is the top). (x, y) must be inside.
    const Rgba8& at(int x, int y) const { return pixels_[index(x, y)]; }
    //< framebuffer-at

    /// Sets every pixel to `colour`.
    void fill(Rgba8 colour);
    /// The pixels, row after row from the top: width() * height() of them.
    const std::vector<Rgba8>& pixels() const { return pixels_; }

    /// Frames are equal when they have the same size and the same pixels.
    friend bool operator==(const Framebuffer&, const Framebuffer&) = default;

  private:
    /// The element of pixel (x, y). (Inline: called once per span, out of line it cost
    /// the big torus's frame 0.8M instructions.)
    std::size_t index(int x, int y) const {
        assert(contains(x, y));
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
               static_cast<std::size_t>(x);
    }

    int width_;
    int height_;
    std::vector<Rgba8> pixels_;
};

} // namespace exactpixels
