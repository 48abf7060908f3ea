#include "exactpixels/lab/pareto_front.hpp"

#include "exactpixels/base/error.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace exactpixels {

//> pareto-front
bool tied_in_time(double t, double t_other, double noise) {
    return std::max(t, t_other) <= (1.0 + noise) * std::min(t, t_other);
}

bool beats(const Setting& b, const Setting& a, double noise) {
    const bool tied = tied_in_time(b.time, a.time, noise);
    const bool faster = b.time < a.time && !tied;
    const bool no_worse =
        (faster || tied) && b.worst <= a.worst && b.wrong_at_ties <= a.wrong_at_ties;
    return no_worse && (faster || b.worst < a.worst || b.wrong_at_ties < a.wrong_at_ties);
}
//< pareto-front

std::vector<int> beaten_by(const std::vector<Setting>& settings, double noise) {
    std::vector<int> count(settings.size(), 0);
    for (std::size_t a = 0; a < settings.size(); ++a) {
        for (const Setting& b : settings) {
            count[a] += beats(b, settings[a], noise);
        }
    }
    return count;
}

double repetition_noise(const std::vector<std::vector<double>>& repetitions) {
    if (repetitions.empty()) {
        throw Error("repetition_noise: no benchmarks");
    }
    std::vector<double> spread;
    for (const std::vector<double>& times : repetitions) {
        if (times.size() < 2) {
            throw Error(
                fmt::format("repetition_noise: a benchmark with {} repetition(s); "
                            "the noise needs at least two",
                            times.size()));
        }
        const auto [fastest, slowest] = std::minmax_element(times.begin(), times.end());
        if (!(*fastest > 0.0)) {
            throw Error(fmt::format("repetition_noise: a time of {}", *fastest));
        }
        spread.push_back(*slowest / *fastest - 1.0);
    }
    std::sort(spread.begin(), spread.end());
    const std::size_t middle = spread.size() / 2;
    return spread.size() % 2 == 1 ? spread[middle]
                                  : (spread[middle - 1] + spread[middle]) / 2.0;
}

} // namespace exactpixels
