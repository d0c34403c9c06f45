#include "experiments/statistics.h"

#include <algorithm>
#include <random>

#include "core/error.h"
#include "core/statistics.h"

namespace sl::experiments {

Interval median_interval(const std::vector<std::vector<double>>& groups, double confidence,
                         int resamples, uint64_t seed) {
    if (!(confidence > 0.0 && confidence < 1.0) || resamples < 1) {
        fail("median_interval: confidence {} must be in (0, 1) and resamples {} at least 1",
             confidence, resamples);
    }
    std::vector<const std::vector<double>*> present;
    for (const auto& g : groups) {
        if (!g.empty()) {
            present.push_back(&g);
        }
    }
    if (present.empty()) {
        return {};
    }
    std::mt19937_64 random(seed);
    std::vector<double> medians, draw;
    medians.reserve(size_t(resamples));
    for (int b = 0; b < resamples; ++b) {
        draw.clear();
        for (size_t i = 0; i < present.size(); ++i) {
            const std::vector<double>& group = *present[random() % present.size()];
            for (size_t j = 0; j < group.size(); ++j) {
                draw.push_back(group[random() % group.size()]);
            }
        }
        // The median of the draw (nth_element: the sample median, averaging the middle two).
        const size_t m = draw.size() / 2;
        std::nth_element(draw.begin(), draw.begin() + std::ptrdiff_t(m), draw.end());
        double value = draw[m];
        if (draw.size() % 2 == 0) {
            value =
                0.5 * (value + *std::max_element(draw.begin(), draw.begin() + std::ptrdiff_t(m)));
        }
        medians.push_back(value);
    }
    const double tail = 100.0 * (1.0 - confidence) / 2.0;
    return {percentile(medians, tail), percentile(medians, 100.0 - tail)};
}

}  // namespace sl::experiments
