// depth_precision.hpp: the depth step of three ways to store depth (chapter 7,
// @sec:scene-depth): the renderer's float 1/w, OpenGL's conventional z/w in 24-bit
// fixed point, and reversed z in float, for the figure and the exercise that compare
// them.
//
// Usage:
//   double ours = nearness_depth_step(100.0);                  // float 1/w (DepthBuffer)
//   double fixed = fixed_z_depth_step(100.0, 0.1, 1000.0, 24);  // z/w, 24-bit fixed
//   double reversed = reversed_z_depth_step(100.0, 0.1, 1000.0); // 1 - z/w, float
//
// The depth step at depth w is the width, in the units of w, of the range of depths that
// store the same key as w: two surfaces closer than that may tie, two farther apart never
// do. Each is computed from the key's neighbours (the rounding boundaries halfway to the
// next key either side), mapped back to depth in double: exact to about nine digits, the
// steps being at least 2^-25 of w. The keys are the stored values only; a GPU's rounding
// while it computes z/w before storing it is not counted.
#pragma once

namespace exactpixels {

/// The renderer's own key, nearness_key(1 / w) (depth_buffer.hpp): its depth step at
/// depth w > 0, depth_resolution(w) * w.
double nearness_depth_step(double w);

/// OpenGL's conventional depth, d = f (w - n) / ((f - n) w) in [0, 1] (0 at the near
/// plane n, 1 at the far plane f), stored as round(d (2^bits - 1)): the depth step at w
/// in [n, f]. 0 < n < f, 0 < bits < 53.
double fixed_z_depth_step(double w, double near, double far, int bits);

/// Reversed z, d = n (f - w) / ((f - n) w) (1 at the near plane, 0 at the far plane),
/// stored as the nearest float: the depth step at w in [n, f). 0 < n < f.
double reversed_z_depth_step(double w, double near, double far);

} // namespace exactpixels
