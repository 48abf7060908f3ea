#include "exactpixels/base/contraction.hpp"

namespace exactpixels {

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define EXACTPIXELS_FMA_TARGET __attribute__((target("fma")))
#else
#define EXACTPIXELS_FMA_TARGET
#endif

//> multiply-add-as-written
EXACTPIXELS_FMA_TARGET double multiply_add_as_written(double a, double b, double c) {
    return a * b + c; // -ffp-contract=off: the product rounds, then the sum
}
//< multiply-add-as-written

bool multiply_add_runs_here() {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    return __builtin_cpu_supports("fma");
#else
    return true;
#endif
}

} // namespace exactpixels
