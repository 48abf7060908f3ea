// printing.hpp: how a failed check prints the values it compared, for the types the
// chapter tests compare (doctest's StringMaker). Without these, doctest prints a type it
// cannot print as {?}, and a failure reads "CHECK( frame == expected ) is false; values:
// {?} == {?}": no help to a student. Include it in every test file that compares them:
//
//     #include "support/printing.hpp"
//     CHECK(frame.at(3, 4) == rgba(255, 0, 0));   // fails with rgba(0, 0, 0, 255) == ...
//
// Pixels print as rgba(R, G, B, A); frames as their size, their most common colours with
// counts and a hash of every pixel (two frames that print alike differ in the hash);
// glm vectors as (x, y, ...); containers as [a, b, ...] (the first 12 elements and the
// count); pairs as (a, b); optionals as their value or nullopt; a file
// stream as whether it is open and good. Only the base layer's types are
// named here (every kit has it); a kit with the texture layer prints mappers too.
#pragma once

#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/base/framebuffer.hpp"

#include <doctest/doctest.h>
#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#if __has_include("exactpixels/texture/mapper.hpp")
#include "exactpixels/texture/mapper.hpp"
#endif

namespace exactpixels::testing {

/// "[a, b, c]" from the first 12 elements of [first, last), then "... (N in all)".
template <typename Iterator>
doctest::String list_string(Iterator first, Iterator last, std::size_t count) {
    constexpr std::size_t shown = 12;
    std::string text = "[";
    std::size_t i = 0;
    for (; first != last && i < shown; ++first, ++i) {
        // A copy as the element type: a vector<bool> element is a proxy (libc++'s has no
        // printer).
        const typename std::iterator_traits<Iterator>::value_type value = *first;
        text += i == 0 ? "" : ", ";
        text += doctest::toString(value).c_str();
    }
    if (count > shown) {
        text += ", ... (";
        text += std::to_string(count);
        text += " in all)";
    }
    text += ']';
    return text.c_str();
}

/// "(a, b, c)": the numbers, written by appending (GCC 12 warns falsely, -Wrestrict,
/// about "literal" + std::string).
template <typename Number>
std::string tuple_string(std::initializer_list<Number> numbers) {
    std::string text = "(";
    for (const Number n : numbers) {
        text += text.size() == 1 ? "" : ", ";
        text += doctest::toString(n).c_str();
    }
    text += ')';
    return text;
}

/// "rgba(R, G, B, A)".
inline std::string pixel_string(Rgba8 pixel) {
    std::string text = "rgba";
    text += tuple_string<int>({pixel.r, pixel.g, pixel.b, pixel.a});
    return text;
}

} // namespace exactpixels::testing

namespace doctest {

template <> struct StringMaker<exactpixels::Rgba8> {
    static String convert(const exactpixels::Rgba8& pixel) {
        return exactpixels::testing::pixel_string(pixel).c_str();
    }
};

/// "WxH frame: 200 x rgba(0, 0, 0, 255), 56 x rgba(255, 0, 0, 255), ...; hash H".
template <> struct StringMaker<exactpixels::Framebuffer> {
    static String convert(const exactpixels::Framebuffer& frame) {
        std::map<std::uint32_t, std::size_t> counts;
        std::uint64_t hash = 14695981039346656037ull; // FNV-1a over every channel
        for (const auto& p : frame.pixels()) {
            ++counts[(std::uint32_t{p.r} << 24) | (std::uint32_t{p.g} << 16) |
                     (std::uint32_t{p.b} << 8) | p.a];
            for (const std::uint8_t channel : {p.r, p.g, p.b, p.a}) {
                hash = (hash ^ channel) * 1099511628211ull;
            }
        }
        std::vector<std::pair<std::size_t, std::uint32_t>> common;
        for (const auto& [colour, count] : counts) {
            common.emplace_back(count, colour);
        }
        std::sort(common.rbegin(), common.rend());
        std::string text = std::to_string(frame.width());
        text += 'x';
        text += std::to_string(frame.height());
        text += " frame:";
        for (std::size_t i = 0; i < common.size() && i < 3; ++i) {
            const std::uint32_t c = common[i].second;
            text += i == 0 ? " " : ", ";
            text += std::to_string(common[i].first);
            text += " x ";
            text += exactpixels::testing::pixel_string(
                {static_cast<std::uint8_t>(c >> 24), static_cast<std::uint8_t>(c >> 16),
                 static_cast<std::uint8_t>(c >> 8), static_cast<std::uint8_t>(c)});
        }
        if (common.size() > 3) {
            text += ", ";
            text += std::to_string(common.size() - 3);
            text += " more colours";
        }
        char hex[24];
        std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
        text += "; hash ";
        text += hex;
        return text.c_str();
    }
};

template <> struct StringMaker<exactpixels::FixedPoint2> {
    static String convert(const exactpixels::FixedPoint2& point) {
        std::string text =
            exactpixels::testing::tuple_string<std::int64_t>({point.x, point.y});
        text += " /256 px";
        return text.c_str();
    }
};

template <glm::length_t L, typename T, glm::qualifier Q>
struct StringMaker<glm::vec<L, T, Q>> {
    static String convert(const glm::vec<L, T, Q>& v) {
        std::string text = "(";
        for (glm::length_t i = 0; i < L; ++i) {
            text += i == 0 ? "" : ", ";
            text += toString(v[i]).c_str();
        }
        text += ')';
        return text.c_str();
    }
};

template <typename T, typename A> struct StringMaker<std::vector<T, A>> {
    static String convert(const std::vector<T, A>& v) {
        return exactpixels::testing::list_string(v.begin(), v.end(), v.size());
    }
};

template <typename T, std::size_t N> struct StringMaker<std::array<T, N>> {
    static String convert(const std::array<T, N>& v) {
        return exactpixels::testing::list_string(v.begin(), v.end(), N);
    }
};

template <typename T, typename C, typename A> struct StringMaker<std::set<T, C, A>> {
    static String convert(const std::set<T, C, A>& v) {
        return exactpixels::testing::list_string(v.begin(), v.end(), v.size());
    }
};

template <typename A, typename B> struct StringMaker<std::pair<A, B>> {
    static String convert(const std::pair<A, B>& p) {
        return String("(") + toString(p.first) + ", " + toString(p.second) + ")";
    }
};

template <typename T> struct StringMaker<std::optional<T>> {
    static String convert(const std::optional<T>& v) {
        return v ? toString(*v) : String("nullopt");
    }
};

template <typename T> struct StringMaker<std::atomic<T>> {
    static String convert(const std::atomic<T>& v) { return toString(v.load()); }
};

template <> struct StringMaker<std::ifstream> {
    static String convert(const std::ifstream& in) {
        return !in.is_open() ? "a file that did not open"
               : in.good()   ? "an open file"
                             : "an open file past its end or failed";
    }
};

#if __has_include("exactpixels/texture/mapper.hpp")
template <> struct StringMaker<exactpixels::Mapper> {
    static String convert(const exactpixels::Mapper& mapper) {
        return exactpixels::mapper_name(mapper).c_str();
    }
};
#endif

} // namespace doctest
