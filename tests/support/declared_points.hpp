// declared_points.hpp: what a test case declares about grading in its doctest
// description, "points: N; exercise: ID" (and, rarely, "visibility: V"). The grade
// reporter reads it from the running test case, make-kit from the test's source text:
// one reading for both.
//
// Usage:
//   DeclaredPoints d = parse_declared_points("points: 2; exercise: ch02-edge-bias");
//   // d.points == 2, d.exercise == "ch02-edge-bias", d.bad_points empty
//
// Items are separated by ';', keys and values by ':', spaces around both are ignored,
// unknown keys are ignored, and any item may be missing (0 points, no exercise, no
// visibility). The visibility is Gradescope's ("visible", "hidden", "after_due_date",
// "after_published"); the grade runner gives a test case of tests/hidden/ without one
// "after_published".
#pragma once

#include <string>
#include <string_view>

namespace exactpixels::testing {

/// A test case's declared points and exercise.
struct DeclaredPoints {
    int points = 0;         ///< points earned when the test case passes
    std::string exercise;   ///< the exercise region it checks; empty for none
    std::string bad_points; ///< the `points` value when it is not a whole number
    std::string visibility; ///< Gradescope's visibility; empty when not declared
};

/// `text` without leading and trailing spaces and tabs.
inline std::string_view trimmed_item(std::string_view text) {
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) {
        text.remove_prefix(1);
    }
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) {
        text.remove_suffix(1);
    }
    return text;
}

/// Reads "points: N; exercise: ID" (see the top of the file). A points value that is not
/// a whole number of at most 9 digits counts 0 and is kept in bad_points.
inline DeclaredPoints parse_declared_points(std::string_view description) {
    DeclaredPoints declared;
    while (!description.empty()) {
        const auto end = description.find(';');
        const std::string_view item = trimmed_item(description.substr(0, end));
        description = end == std::string_view::npos ? std::string_view{}
                                                    : description.substr(end + 1);
        const auto colon = item.find(':');
        if (colon == std::string_view::npos) {
            continue;
        }
        const std::string_view key = trimmed_item(item.substr(0, colon));
        const std::string_view value = trimmed_item(item.substr(colon + 1));
        if (key == "points") {
            bool whole = !value.empty() && value.size() <= 9;
            int points = 0;
            for (const char c : value) {
                whole = whole && c >= '0' && c <= '9';
                points = whole ? 10 * points + (c - '0') : 0;
            }
            declared.points = whole ? points : 0;
            declared.bad_points = whole ? "" : std::string(value);
        } else if (key == "exercise") {
            declared.exercise = std::string(value);
        } else if (key == "visibility") {
            declared.visibility = std::string(value);
        }
    }
    return declared;
}

} // namespace exactpixels::testing
