// Chapter 6: the error of u along a 4096-pixel span in float, stepped (u += du) and
// evaluated afresh (u0 + k du), against the same u0 and du in double.
// Usage: fig_ch06_drift FIGURE_DIR  (writes ch06_drift.dat; ch06_drift.gp plots it)
#include "exactpixels/base/error.hpp"
#include "exactpixels/texture/span_mappers.hpp"
#include "support/figure_file.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

using namespace exactpixels;

int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    const int n = 4096;
    const float u0 = 0.3f, du = 1.0001f; // the case of the test "long spans in float"
    std::ostringstream out;
    out << "# pixel  stepped_error  fresh_error  (texels)\n";
    map_span_affine(AffineSpan<float>{u0, 0.0f, du, 0.0f, n}, [&](int k, float u, float) {
        const double truth = double(u0) + k * double(du);
        const float fresh = u0 + float(k) * du;
        if (k % 8 == 0) {
            out << k << ' ' << std::abs(double(u) - truth) << ' '
                << std::abs(double(fresh) - truth) << '\n';
        }
    });
    try {
        write_figure_file(folder / "ch06_drift.dat", out.str());
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch06_drift: %s\n", error.what());
        return 1;
    }
    std::printf("wrote ch06_drift.dat\n");
}
