// contraction.hpp: a*b + c as the source writes it, compiled like the rest of the
// library, to prove that the build never fuses a multiply and an add.
//
// Usage:
//   if (multiply_add_runs_here()) {
//       double r = multiply_add_as_written(1 + 0x1p-30, 1 - 0x1p-30, -1.0);
//       // r == 0: the product 1 - 2^-60 rounds to 1 before the add. A fused
//       // multiply-add rounds once, and gives -2^-60 instead.
//   }
//
// Every exact result of the book assumes IEEE double, round to nearest, no
// -ffast-math and no contraction: each operation the source writes rounds once, by
// itself. A compiler may otherwise contract a*b + c into one fused multiply-add (FMA),
// which rounds once for both (GCC's default in C++ is -ffp-contract=fast, Clang's is on);
// the project's CMakeLists.txt passes -ffp-contract=off to every target. The build is
// for baseline x86-64, which has no FMA instruction, so there the compiler could not
// fuse anyway: on x86-64 with GCC or Clang this one function is compiled for CPUs with
// FMA, so that it would be fused if the flag were missing, and may only be called where
// the CPU has FMA (multiply_add_runs_here). On ARM64, where every CPU has FMA, it is
// compiled like any other function.
#pragma once

namespace exactpixels {

/// a * b + c, two roundings unless the compiler contracts it into one fused
/// multiply-add (which the build forbids).
double multiply_add_as_written(double a, double b, double c);

/// Whether multiply_add_as_written can run on this CPU (false on an x86-64 CPU without
/// FMA, true elsewhere).
bool multiply_add_runs_here();

} // namespace exactpixels
