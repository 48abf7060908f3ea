// depth_buffer.hpp: the depth stage of the scene renderer (chapter 7): per pixel, the
// nearness of the nearest surface drawn so far, and the test that decides whether a new
// surface is seen.
//
// Usage:
//   DepthBuffer depth(320, 240);                     // every pixel: nothing drawn yet
//   float q = nearness_key(1.0 / w);                 // perspective: 1/w, larger = nearer
//   if (depth.test_and_write(x, y, q)) { /* write the pixel */ }
//
// The quantity is the nearness q, larger when nearer: 1/w under a perspective camera
// (w the view-space depth, >= near > 0 after clipping), -z under an orthographic one.
// Both are linear on screen (chapter 3, @eq:linear-in-screen; z itself is linear under
// a parallel projection), so the renderer sets q up per triangle as a ScreenPlane and
// evaluates it at each pixel centre. The buffer stores q rounded to float: a float's
// spacing is relative, so two depths w and w (1 + e) are told apart at every distance
// once e exceeds about 2^-23 (@eq:scene-depth-resolution). Test rule: a surface is drawn
// when q >= the stored value; a tie goes to the triangle drawn later, the order the
// renderer already draws in (file order, later on top).
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

namespace exactpixels {

/// The value the depth buffer stores for a nearness q (1/w or -z): q rounded to the
/// nearest float.
inline float nearness_key(double q) {
    return static_cast<float>(q);
}

/// The relative depth resolution of the buffer at depth w > 0 (perspective): the width,
/// divided by w, of the range of depths that store the same key as w. Two surfaces
/// farther apart than that, relative to their depth, always store different keys.
double depth_resolution(double w);

/// The same for a fixed-point buffer storing round(2^bits * near / w)
/// (1/w scaled so that the near plane is the largest value): the comparison that
/// explains the float choice. near <= w.
double fixed_depth_resolution(double w, double near, int bits);

//> depth-buffer
/// One nearness key per pixel, row-major, origin top-left.
class DepthBuffer {
  public:
    /// A buffer of width x height pixels, each holding -infinity (nothing drawn).
    DepthBuffer(int width, int height)
        : width_(width),
          keys_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height),
                -std::numeric_limits<float>::infinity()) {}

    /// The depth test at pixel (x, y): true, and q stored, when q is at least as near
    /// as what is there (ties go to the later surface); false, and nothing changed,
    /// when the pixel already shows something nearer.
    bool test_and_write(int x, int y, float q) { return test_and_write(row(y)[x], q); }

    /// The same test on one stored key (of a row()).
    static bool test_and_write(float& stored, float q) {
        if (q < stored) {
            return false;
        }
        stored = q;
        return true;
    }

    /// Row y's keys, left to right: a stage that tests a span of pixels finds them once.
    float* row(int y) {
        return keys_.data() +
               static_cast<std::size_t>(y) * static_cast<std::size_t>(width_);
    }

    /// The key stored at pixel (x, y).
    float at(int x, int y) const {
        return keys_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                     static_cast<std::size_t>(x)];
    }

  private:
    int width_;
    std::vector<float> keys_;
};
//< depth-buffer

} // namespace exactpixels
