// render_time.hpp: how the scene figures time a render (chapters 7 to 9).
//
// Usage:
//   double ms = best_ms(scene, 7);   // the fastest of 7 renders, in milliseconds
//
// Header only: it calls the scene layer, which figure_file.cpp and svg.cpp do not link.
// The times are this build's quick figures, never a verdict (book/AUTHORING.md).
#pragma once

#include "exactpixels/scene/scene_renderer.hpp"

#include <algorithm>

namespace exactpixels {

/// The fastest of `runs` renders of `scene`, in milliseconds (the least disturbed by
/// other work).
inline double best_ms(const Scene& scene, int runs) {
    double best = 1e300;
    for (int k = 0; k < runs; ++k) {
        best = std::min(best, 1e3 * render_scene(scene).report.seconds);
    }
    return best;
}

} // namespace exactpixels
