#include "exactpixels/fast/simd.hpp"

#include "exactpixels/base/error.hpp"

#include <array>
#include <atomic>
#include <cstdlib>
#include <string>

namespace exactpixels {

namespace {

constexpr std::array all_variants{SimdVariant::portable, SimdVariant::sse2,
                                  SimdVariant::avx2, SimdVariant::avx512,
                                  SimdVariant::neon};

/// The chosen variant plus one; 0 while none is chosen yet.
std::atomic<int> chosen{0};

} // namespace

std::string_view simd_name(SimdVariant v) {
    switch (v) {
    case SimdVariant::portable:
        return "portable";
    case SimdVariant::sse2:
        return "sse2";
    case SimdVariant::avx2:
        return "avx2";
    case SimdVariant::avx512:
        return "avx512";
    case SimdVariant::neon:
        return "neon";
    }
    return "unknown";
}

bool simd_available(SimdVariant v) {
    switch (v) {
    case SimdVariant::portable:
        return true;
#if defined(EXACTPIXELS_SIMD_X86)
    case SimdVariant::sse2:
        return true; // every x86-64 CPU
    case SimdVariant::avx2:
        return __builtin_cpu_supports("avx2"); // and the OS saves its registers
    case SimdVariant::avx512:
        return __builtin_cpu_supports("avx512f");
#elif defined(EXACTPIXELS_SIMD_ARM64)
    case SimdVariant::neon:
        return true; // every ARM64 CPU
#endif
    default:
        return false;
    }
}

std::vector<SimdVariant> available_simd() {
    std::vector<SimdVariant> out;
    for (const SimdVariant v : all_variants) {
        if (simd_available(v)) {
            out.push_back(v);
        }
    }
    return out;
}

SimdVariant simd_from_setting(const char* value) {
    if (value == nullptr || *value == '\0') {
        return available_simd().back();
    }
    const std::string_view wanted = value;
    for (const SimdVariant v : all_variants) {
        if (simd_name(v) == wanted) {
            if (!simd_available(v)) {
                throw Error("EXACTPIXELS_SIMD=" + std::string(wanted) +
                            ": this CPU or build has no such instructions");
            }
            return v;
        }
    }
    throw Error("EXACTPIXELS_SIMD=" + std::string(wanted) +
                ": unknown; one of sse2, avx2, avx512, neon, portable");
}

SimdVariant chosen_simd() {
    const int now = chosen.load(std::memory_order_relaxed);
    if (now != 0) {
        return static_cast<SimdVariant>(now - 1);
    }
    const SimdVariant v = simd_from_setting(std::getenv("EXACTPIXELS_SIMD"));
    chosen.store(static_cast<int>(v) + 1, std::memory_order_relaxed);
    return v;
}

void choose_simd(SimdVariant v) {
    if (!simd_available(v)) {
        throw Error("SIMD variant " + std::string(simd_name(v)) +
                    ": this CPU or build has no such instructions");
    }
    chosen.store(static_cast<int>(v) + 1, std::memory_order_relaxed);
}

} // namespace exactpixels
