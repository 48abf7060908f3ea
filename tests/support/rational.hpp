// rational.hpp: an exact rational number for tests that check identities exactly.
//
// Usage:
//   Rational a(1, 3), b = Rational::from_double(0.25);   // 1/3 and 1/4, exactly
//   CHECK((a + b) * Rational(12) == Rational(7));
//   CHECK(sign(a - b) == 1);
//
// Numerator and denominator are __int128 (GCC/Clang), kept reduced with a positive
// denominator, so == compares values. Every operation checks for overflow and throws
// std::overflow_error instead of wrapping: a test built on Rational either gets the
// exact answer or stops loudly. Keep inputs modest (dyadic values with a few dozen
// significant bits, small integers); from_double accepts any finite double whose
// exact value fits.
#pragma once

#include <cmath>
#include <cstdint>
#include <ostream>
#include <stdexcept>
#include <string>

namespace exactpixels::testing {

/// A signed 128-bit integer (a GCC/Clang extension; __extension__ keeps -Wpedantic
/// quiet).
__extension__ typedef __int128 Int128;

/// An exact rational number num/den over __int128, always reduced, den > 0.
class Rational {
  public:
    /// The integer 128-bit type both parts are stored in.
    using Int = Int128;

    /// Zero.
    constexpr Rational() = default;
    /// The integer n.
    constexpr Rational(std::int64_t n) : num_(n) {} // NOLINT: implicit by design
    /// num / den; den must not be zero (std::domain_error otherwise).
    Rational(Int num, Int den) : num_(num), den_(den) {
        if (den_ == 0) {
            throw std::domain_error("Rational: zero denominator");
        }
        normalise();
    }

    /// The exact value of a finite double (std::overflow_error if it does not fit).
    static Rational from_double(double value) {
        if (!std::isfinite(value)) {
            throw std::domain_error("Rational::from_double: not finite");
        }
        int exponent = 0;
        const double mantissa = std::frexp(value, &exponent); // value = m * 2^exponent
        // 53 bits of mantissa as an integer: value = M * 2^(exponent - 53), exactly.
        auto m = static_cast<std::int64_t>(std::ldexp(mantissa, 53));
        int shift = exponent - 53;
        while (m != 0 && m % 2 == 0 && shift < 0) { // drop factors of 2 both sides share
            m /= 2;
            ++shift;
        }
        if (m == 0) {
            return Rational();
        }
        if (shift > 62 || shift < -126) {
            throw std::overflow_error("Rational::from_double: exponent out of range");
        }
        if (shift >= 0) {
            return {mul(m, Int(1) << shift), 1};
        }
        return {m, Int(1) << -shift};
    }

    /// The numerator (carries the sign).
    constexpr Int num() const { return num_; }
    /// The denominator (> 0).
    constexpr Int den() const { return den_; }

    /// The nearest double (to within a couple of roundings; for messages and bounds).
    double to_double() const {
        return static_cast<double>(static_cast<long double>(num_) /
                                   static_cast<long double>(den_));
    }

    /// Sum.
    friend Rational operator+(const Rational& a, const Rational& b) {
        return {add(mul(a.num_, b.den_), mul(b.num_, a.den_)), mul(a.den_, b.den_)};
    }
    /// Difference.
    friend Rational operator-(const Rational& a, const Rational& b) {
        return {sub(mul(a.num_, b.den_), mul(b.num_, a.den_)), mul(a.den_, b.den_)};
    }
    /// Negation.
    friend Rational operator-(const Rational& a) { return {sub(0, a.num_), a.den_}; }
    /// Product.
    friend Rational operator*(const Rational& a, const Rational& b) {
        // Cross-reduce first so that products stay as small as possible.
        const Int g1 = gcd(a.num_, b.den_), g2 = gcd(b.num_, a.den_);
        return {mul(a.num_ / g1, b.num_ / g2), mul(a.den_ / g2, b.den_ / g1)};
    }
    /// Quotient; b must not be zero (std::domain_error otherwise).
    friend Rational operator/(const Rational& a, const Rational& b) {
        if (b.num_ == 0) {
            throw std::domain_error("Rational: division by zero");
        }
        return a * Rational(b.den_, b.num_);
    }
    /// a += b.
    Rational& operator+=(const Rational& b) { return *this = *this + b; }
    /// a -= b.
    Rational& operator-=(const Rational& b) { return *this = *this - b; }
    /// a *= b.
    Rational& operator*=(const Rational& b) { return *this = *this * b; }
    /// a /= b.
    Rational& operator/=(const Rational& b) { return *this = *this / b; }

    /// Equal values (both sides are reduced, so the parts are equal).
    friend bool operator==(const Rational& a, const Rational& b) {
        return a.num_ == b.num_ && a.den_ == b.den_;
    }
    /// Order by value.
    friend bool operator<(const Rational& a, const Rational& b) {
        return mul(a.num_, b.den_) < mul(b.num_, a.den_);
    }
    /// Order by value.
    friend bool operator>(const Rational& a, const Rational& b) { return b < a; }
    /// Order by value.
    friend bool operator<=(const Rational& a, const Rational& b) { return !(b < a); }
    /// Order by value.
    friend bool operator>=(const Rational& a, const Rational& b) { return !(a < b); }

    /// -1, 0 or +1.
    friend int sign(const Rational& a) { return a.num_ > 0 ? 1 : (a.num_ < 0 ? -1 : 0); }
    /// |a|.
    friend Rational abs(const Rational& a) { return a.num_ < 0 ? -a : a; }

    /// num/den in decimal, for test messages.
    friend std::ostream& operator<<(std::ostream& out, const Rational& a) {
        out << to_string(a.num_);
        if (a.den_ != 1) {
            out << '/' << to_string(a.den_);
        }
        return out;
    }

  private:
    static Int mul(Int a, Int b) {
        Int r = 0;
        if (__builtin_mul_overflow(a, b, &r)) {
            throw std::overflow_error("Rational: 128-bit overflow in a product");
        }
        return r;
    }
    static Int add(Int a, Int b) {
        Int r = 0;
        if (__builtin_add_overflow(a, b, &r)) {
            throw std::overflow_error("Rational: 128-bit overflow in a sum");
        }
        return r;
    }
    static Int sub(Int a, Int b) {
        Int r = 0;
        if (__builtin_sub_overflow(a, b, &r)) {
            throw std::overflow_error("Rational: 128-bit overflow in a difference");
        }
        return r;
    }
    static Int gcd(Int a, Int b) {
        a = a < 0 ? -a : a;
        b = b < 0 ? -b : b;
        while (b != 0) {
            const Int t = a % b;
            a = b;
            b = t;
        }
        return a == 0 ? 1 : a;
    }
    static std::string to_string(Int v) {
        if (v == 0) {
            return "0";
        }
        const bool negative = v < 0;
        std::string digits;
        while (v != 0) {
            const int d = static_cast<int>(v % 10);
            digits.insert(digits.begin(), static_cast<char>('0' + (d < 0 ? -d : d)));
            v /= 10;
        }
        return negative ? "-" + digits : digits;
    }
    void normalise() {
        if (den_ < 0) {
            num_ = sub(0, num_);
            den_ = sub(0, den_);
        }
        const Int g = gcd(num_, den_);
        num_ /= g;
        den_ /= g;
    }

    Int num_ = 0;
    Int den_ = 1;
};

} // namespace exactpixels::testing
