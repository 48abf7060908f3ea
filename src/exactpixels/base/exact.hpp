// exact.hpp: unbounded exact integers and rationals, and the one rounding from an exact
// value to the nearest double. The book's references: whatever a test or a measurement
// compares a double result with is computed here, exactly, and rounded at most once.
//
// Usage:
//   Rational a(1, 3), b = exact(0.25);   // 1/3 and 1/4, exactly (b is the double's
//   value) (a + b) * 12 == 7;                   // true: arithmetic never rounds sign(a -
//   b) == 1;  abs(b - a) == Rational(1, 12); to_double(a) == 1.0 / 3.0;           // the
//   double nearest 1/3: one rounding Integer big = Integer(1) << 200;     // integers
//   never overflow floor_of(Rational(-7, 2)) == -4;
//
// Both types are Boost.Multiprecision's (Debian's libboost-dev, header-only): Integer is
// cpp_int, Rational is cpp_rational, numerator and denominator unbounded integers kept
// reduced with a positive denominator, so == compares values. Expression templates are
// off: `auto x = a + b;` holds a value, as with double. They are slow next to double (a
// microsecond an operation, more as the numbers grow): references and tests only, never
// a pixel loop.
//
// Rational(n, d) needs d > 0: Boost 1.74 (Debian 12's) throws std::domain_error for a
// negative d.
//
// exact(d) is the value of a finite double, exactly. to_double(r) rounds r to the nearest
// double, ties to even, for |r| in the normal range of double (about 2.2e-308 to
// 1.8e308), and so does quotient_to_double(n, d) for n / d without reducing the fraction
// first; tests/ch00_exact_arithmetic.cpp checks them.
#pragma once

#include <cmath>

// GCC 11 and 12 see a maybe-uninitialized limb pointer in cpp_int's destructor that is
// never read (Boost's issue 413, silenced in cpp_int.hpp itself from Boost 1.79); GCC
// judges the warning at the header's own lines, so it is silenced there only.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <boost/multiprecision/cpp_int.hpp>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

namespace exactpixels {

/// An unbounded signed integer (never overflows).
using Integer = boost::multiprecision::number<boost::multiprecision::cpp_int_backend<>,
                                              boost::multiprecision::et_off>;

/// An exact rational number: unbounded numerator and denominator, always reduced.
using Rational =
    boost::multiprecision::number<boost::multiprecision::cpp_rational_backend,
                                  boost::multiprecision::et_off>;

/// The exact value of a finite double.
inline Rational exact(double d) {
    return Rational(d);
}

/// n / d rounded once to the nearest double, ties to even (d != 0), for a quotient in
/// double's normal range: the quotient scaled to 54 or 55 bits by a power of two, then
/// its extra bits and the remainder decide the last bit.
inline double quotient_to_double(Integer n, Integer d) {
    if (d < 0) {
        n = -n;
        d = -d;
    }
    if (n == 0) {
        return 0.0;
    }
    const bool negative = n < 0;
    if (negative) {
        n = -n;
    }
    const int shift = 54 - (static_cast<int>(msb(n)) - static_cast<int>(msb(d)));
    if (shift > 0) {
        n <<= shift; // n 2^shift / d lies in [2^53, 2^55)
    } else {
        d <<= -shift;
    }
    Integer q, r;
    divide_qr(n, d, q, r);
    const int extra = static_cast<int>(msb(q)) - 52; // 1 or 2 bits beyond 53
    const Integer half = Integer(1) << (extra - 1);
    const Integer dropped = q & ((half << 1) - 1);
    q >>= extra;
    if (dropped > half || (dropped == half && (r != 0 || (q & 1) != 0))) {
        ++q; // above the midpoint, or on it with q odd: up (q <= 2^53 stays exact)
    }
    const double magnitude = std::ldexp(q.convert_to<double>(), extra - shift);
    return negative ? -magnitude : magnitude;
}

/// The double nearest r (ties to even): one rounding, for |r| in double's normal range.
inline double to_double(const Rational& r) {
    return quotient_to_double(numerator(r), denominator(r));
}

/// -1, 0 or +1.
inline int sign(const Rational& r) {
    return r.sign();
}

/// -1, 0 or +1.
inline int sign(const Integer& i) {
    return i.sign();
}

/// The largest integer <= r.
inline Integer floor_of(const Rational& r) {
    const Integer n = numerator(r), d = denominator(r); // d > 0
    const Integer q = n / d;                            // truncates towards zero
    return q * d > n ? q - 1 : q;
}

} // namespace exactpixels
