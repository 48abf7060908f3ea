#include "exactpixels/texture/texture.hpp"

#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/base/test_pattern.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>

namespace exactpixels {

Texture::Texture(int width, int height, std::vector<Rgba8> texels)
    : width_(width), height_(height), texels_(std::move(texels)) {
    if (width < 1 || height < 1) {
        throw Error(fmt::format("texture: size {}x{} is empty (both sizes must be >= 1)",
                                width, height));
    }
    if (texels_.size() !=
        static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
        throw Error(fmt::format("texture: {} texels given for a {}x{} texture",
                                texels_.size(), width, height));
    }
}

Texture::Texture(const Framebuffer& image)
    : Texture(image.width(), image.height(), image.pixels()) {
}

const Rgba8& Texture::texel(int i, int j) const {
    assert(i >= 0 && j >= 0 && i < width_ && j < height_);
    return texels_[static_cast<std::size_t>(j) * static_cast<std::size_t>(width_) +
                   static_cast<std::size_t>(i)];
}

//> wrap-index
int wrap_index(int i, int size, Wrap wrap) {
    assert(size >= 1);
    if (wrap == Wrap::clamp) {
        return std::clamp(i, 0, size - 1);
    }
    const int r = i % size;      // in (-size, size): C++ rounds the quotient to zero
    return r < 0 ? r + size : r; // i mod size, in [0, size)
}
//< wrap-index

Rgba8 fetch_texel(const Texture& texture, int i, int j, Wrap wrap) {
    return texture.texel(wrap_index(i, texture.width(), wrap),
                         wrap_index(j, texture.height(), wrap));
}

bool can_fetch_masked(const Texture& texture, Wrap wrap) {
    const auto power_of_two = [](int n) { return n > 0 && (n & (n - 1)) == 0; };
    return wrap == Wrap::repeat && power_of_two(texture.width()) &&
           power_of_two(texture.height());
}

//> sample-nearest
Rgba8 sample_nearest(const Texture& texture, TexCoord uv, Wrap wrap) {
    // Texel i covers [i, i+1): the texel holding u is floor(u) (rule 1).
    const int i = static_cast<int>(std::floor(uv.x));
    const int j = static_cast<int>(std::floor(uv.y));
    return fetch_texel(texture, i, j, wrap);
}
//< sample-nearest

Texture checkerboard_texture(int width, int height, int square, Rgba8 even, Rgba8 odd) {
    if (width < 1 || height < 1 || square < 1) {
        throw Error(fmt::format("checkerboard: size {}x{} with squares of {} texels "
                                "(all must be >= 1)",
                                width, height, square));
    }
    std::vector<Rgba8> texels;
    texels.reserve(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    for (int j = 0; j < height; ++j) {
        for (int i = 0; i < width; ++i) {
            texels.push_back((i / square + j / square) % 2 == 0 ? even : odd);
        }
    }
    return Texture(width, height, std::move(texels));
}

Texture f_texture(int cell) {
    if (cell < 1) {
        throw Error(fmt::format("F texture: cell size {} (must be >= 1)", cell));
    }
    return Texture(draw_f_pattern(cell));
}

Texture load_texture(const std::filesystem::path& path,
                     const std::function<void(int width, int height)>& check_size) {
    Framebuffer image = read_png(path, check_size); // throws Error naming the path
    if (image.width() < 1 || image.height() < 1) {
        throw Error(fmt::format("{}: texture has zero size", path.string()));
    }
    // A textured surface is opaque: nothing is drawn behind it to show through, and the
    // frame stays opaque. A texel's colour is kept as stored, its alpha is dropped.
    for (int y = 0; y < image.height(); ++y) {
        for (int x = 0; x < image.width(); ++x) {
            image.at(x, y).a = 255;
        }
    }
    return Texture(image);
}

} // namespace exactpixels
