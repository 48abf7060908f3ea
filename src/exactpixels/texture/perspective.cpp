#include "exactpixels/texture/perspective.hpp"

#include "exactpixels/base/error.hpp"
#include "exactpixels/base/printable.hpp"

#include <fmt/format.h>

#include <cmath>

namespace exactpixels {

//> project
TexturedVertex project(const Pinhole& camera, glm::dvec3 view_point, TexCoord uv) {
    const double x = view_point.x, y = view_point.y, z = view_point.z;
    if (!(z > 0.0) || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
        throw Error(
            fmt::format("project: view-space point ({}, {}, {}) is not finite and "
                        "in front of the eye (z must be > 0)",
                        unsigned_nan(x), unsigned_nan(y), unsigned_nan(z)));
    }
    const Point2 screen{camera.centre.x + camera.focal * x / z,
                        camera.centre.y -
                            camera.focal * y / z}; // y up in view, down on screen
    return {screen, z, uv};
}
//< project

} // namespace exactpixels
