// simd.hpp: which of the CPU's vector instruction sets the fast variants use, chosen once
// at run time: the widest the CPU has, or the one EXACTPIXELS_SIMD names.
//
// Usage:
//   const SimdVariant v = chosen_simd();   // EXACTPIXELS_SIMD, else the widest here
//   for (SimdVariant each : available_simd()) { ... }   // every variant this CPU runs
//   choose_simd(SimdVariant::sse2);        // from now on (tests, benchmarks)
//
// One binary carries the fast variants' code for several instruction sets: on x86-64
// baseline SSE2 (two doubles per register), AVX2 (four) and AVX-512 (eight), on ARM64
// NEON (two); `portable` is the plain scalar loop, everywhere. Each set's code is one
// source text compiled once per set with that set's flags (fast/exact_lanes.inl), and
// every one without contraction (-ffp-contract=off), so that every lane does what the
// scalar code does: IEEE division, multiplication and addition round each lane exactly as
// they round a scalar, and every variant gives the same bits (tested per variant).
// EXACTPIXELS_SIMD=sse2|avx2|avx512|neon|portable forces one; a value that is none of
// these, or names a set this CPU or build does not have, is an Error naming the variable
// and the value (the command-line program exits 2 with it).
#pragma once

#include <string_view>
#include <vector>

namespace exactpixels {

// The instruction sets this build compiles variants for: x86-64 and ARM64 under GCC or
// Clang (src/CMakeLists.txt compiles exact_lanes.inl for the same ones). Elsewhere, such
// as WebAssembly, only the portable variant exists.
#if (defined(__x86_64__) || defined(_M_X64)) && (defined(__GNUC__) || defined(__clang__))
#define EXACTPIXELS_SIMD_X86 1
#elif defined(__aarch64__) && (defined(__GNUC__) || defined(__clang__))
#define EXACTPIXELS_SIMD_ARM64 1
#endif

/// A fast variant's instruction set.
enum class SimdVariant {
    portable, ///< the plain scalar loop, any CPU
    sse2,     ///< x86-64 baseline: 128-bit registers, 2 doubles
    avx2,     ///< x86-64 with AVX2: 256-bit registers, 4 doubles
    avx512,   ///< x86-64 with AVX-512F: 512-bit registers, 8 doubles
    neon      ///< ARM64: 128-bit registers, 2 doubles
};

/// The variant's name as EXACTPIXELS_SIMD spells it.
std::string_view simd_name(SimdVariant v);

/// Whether this build carries the variant and this CPU can run it.
bool simd_available(SimdVariant v);

/// Every available variant, portable first, the widest last.
std::vector<SimdVariant> available_simd();

/// The variant EXACTPIXELS_SIMD's value names: empty or null means the widest available.
/// Error ("EXACTPIXELS_SIMD=VALUE: ...") when the value names no variant or one that is
/// not available here.
SimdVariant simd_from_setting(const char* value);

/// The variant the fast paths use: the last choose_simd's, else EXACTPIXELS_SIMD's
/// (read once). Throws simd_from_setting's Error.
SimdVariant chosen_simd();

/// Makes v the variant the fast paths use from now on (for every thread). Error when v is
/// not available.
void choose_simd(SimdVariant v);

} // namespace exactpixels
