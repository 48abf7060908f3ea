// texture.hpp: an image read by texel coordinates, with nearest-texel sampling.
//
// Usage:
//   Texture t = checkerboard_texture(64, 64, 8);      // 64 x 64 texels, 8-texel squares
//   Texture f = f_texture(4);                         // the book's "F", 20 x 28 texels
//   Texture p = load_texture("wood.png");             // throws Error naming the path
//   Rgba8 c = sample_nearest(t, TexCoord{3.7, 70.2}, Wrap::repeat); // texel (3, 6)
//
// Texel units and centres (chapters 3 and 4): texel (i, j) covers [i, i+1) x [j, j+1)
// in texel units; its centre is (i + 0.5, j + 0.5). u grows to the right along a row,
// v grows down the image (row 0 is the top row, as in a PNG file). Nearest-texel
// sampling picks texel floor(u), floor(v) (rule 1); chapter 4 discusses the other rule,
// ceil(u) - 1, which differs only when u is exactly an integer. Indices outside
// [0, width) x [0, height) are brought inside by the Wrap mode: repeat tiles the plane,
// clamp uses the nearest edge texel.
#pragma once

#include "exactpixels/base/framebuffer.hpp"
#include "exactpixels/base/types.hpp"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <vector>

namespace exactpixels {

/// How a texel index outside the texture is brought inside it.
enum class Wrap {
    repeat, ///< the texture tiles the plane: index i stands for i mod size
    clamp,  ///< the edge texels extend forever: i is clamped to [0, size - 1]
};

/// A width x height grid of texels (RGBA8), row-major, row 0 at the top. Never empty.
class Texture {
  public:
    /// A texture from its texels, row after row from the top (width * height of them).
    /// Throws Error when a size is < 1 or the texel count does not match.
    Texture(int width, int height, std::vector<Rgba8> texels);

    /// The texels of an image (a PNG read by read_png, a procedural pattern).
    /// Throws Error when the image has zero size.
    explicit Texture(const Framebuffer& image);

    /// Width in texels (>= 1).
    int width() const { return width_; }
    /// Height in texels (>= 1).
    int height() const { return height_; }
    /// Texel (i, j): column i, row j, both inside the texture.
    const Rgba8& texel(int i, int j) const;
    /// All texels, row after row from the top.
    const std::vector<Rgba8>& texels() const { return texels_; }

  private:
    int width_;
    int height_;
    std::vector<Rgba8> texels_;
};

/// The index in [0, size) that texel index i stands for under `wrap`. size >= 1.
int wrap_index(int i, int size, Wrap wrap);

/// wrap_index for Wrap::repeat on a power-of-two size: i mod size as a bit mask,
/// i & (size - 1), which two's complement makes right for negative i too. A fast variant
/// beside wrap_index (chapter 5's exercise on the cost of wrapping); the two agree for
/// every int i and every power of two size (tests/ch05_accuracy.cpp).
inline int wrap_index_masked(int i, int size) {
    return i & (size - 1);
}

/// Texel (i, j) of the texture after wrapping each index: the nearest-texel fetch that
/// every mapper ends in.
Rgba8 fetch_texel(const Texture& texture, int i, int j, Wrap wrap);

/// Whether fetch_texel_masked may stand in for fetch_texel: the wrap is repeat and the
/// width and the height are both powers of two.
bool can_fetch_masked(const Texture& texture, Wrap wrap);

/// The fast variant of fetch_texel for a texture that can_fetch_masked allows: inline,
/// each index wrapped by wrap_index_masked, one bit mask in place of an integer
/// remainder and a compare. The same texel as fetch_texel(texture, i, j, Wrap::repeat)
/// for every int i and j (tests/ch07_fast_paths.cpp).
inline const Rgba8& fetch_texel_masked(const Texture& texture, int i, int j) {
    const auto column = static_cast<std::size_t>(wrap_index_masked(i, texture.width()));
    const auto row = static_cast<std::size_t>(wrap_index_masked(j, texture.height()));
    return texture.texels()[row * static_cast<std::size_t>(texture.width()) + column];
}

/// Nearest-texel sampling at (u, v) in texels: texel (floor(u), floor(v)), wrapped.
Rgba8 sample_nearest(const Texture& texture, TexCoord uv, Wrap wrap);

/// A width x height checkerboard of `square`-texel squares; texel (0, 0) has colour
/// `even`. Sizes and square must be >= 1 (Error otherwise).
Texture checkerboard_texture(int width, int height, int square,
                             Rgba8 even = rgba(235, 235, 235),
                             Rgba8 odd = rgba(40, 40, 40));

/// The book's asymmetric "F" (red on blue, see test_pattern.hpp), `cell` texels per
/// glyph cell: (5 * cell) x (7 * cell) texels. cell must be >= 1 (Error otherwise).
Texture f_texture(int cell);

/// Reads a PNG file as a texture (read_png: the header's size is passed to
/// `check_size`, which may throw, before any texel is decoded). Textures are opaque: the
/// file's alpha is dropped, every texel's alpha is 255. Throws Error naming the path
/// when the file is missing, not a regular file, not a PNG, corrupt or too large.
Texture load_texture(const std::filesystem::path& path,
                     const std::function<void(int width, int height)>& check_size = {});

} // namespace exactpixels
