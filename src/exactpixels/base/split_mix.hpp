// split_mix.hpp: deterministic pseudo-random numbers for test scenes and measurements.
//
// Usage:
//   SplitMix random(20240605);           // a seed: the same sequence on every platform
//   std::uint64_t bits = random.next();  // 64 random bits
//   double x = random.uniform(10, 1000); // uniform in [10, 1000)
//
// SplitMix64 (Steele, Lea and Flood 2014): one add and three xor-shift-multiplies per
// number, the same sequence for the same seed with every compiler and library, unlike
// the distributions of <random>. Not for anything that must be unpredictable.
#pragma once

#include <cstdint>

namespace exactpixels {

/// SplitMix64: a tiny generator with the same sequence on every platform.
class SplitMix {
  public:
    /// A generator whose sequence is fixed by `seed`.
    explicit SplitMix(std::uint64_t seed) : state_(seed) {}
    /// The next 64 random bits.
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    /// The next number, uniform in [0, 1) (53 random bits).
    double uniform() { return double(next() >> 11) * 0x1p-53; }
    /// The next number, uniform in [lo, hi).
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

  private:
    std::uint64_t state_;
};

} // namespace exactpixels
