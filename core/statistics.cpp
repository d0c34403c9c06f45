#include "core/statistics.h"

#include <algorithm>
#include <cmath>

namespace sl {

void collect(NamedSeries& series, const std::vector<std::pair<std::string, double>>& values) {
    for (const auto& named : values) {
        auto same = std::find_if(series.begin(), series.end(),
                                 [&](const auto& s) { return s.first == named.first; });
        if (same == series.end()) {
            series.emplace_back(named.first, std::vector<double>{named.second});
        } else {
            same->second.push_back(named.second);
        }
    }
}

std::vector<std::pair<std::string, double>> medians(const NamedSeries& series) {
    std::vector<std::pair<std::string, double>> out;
    for (const auto& [name, values] : series) {
        out.emplace_back(name, median(values));
    }
    return out;
}

double median(std::vector<double> values) {
    return percentile(std::move(values), 50.0);
}

double percentile(std::vector<double> values, double p) {
    if (values.empty()) {
        return 0.0;
    }
    std::sort(values.begin(), values.end());
    const double position = std::clamp(p, 0.0, 100.0) / 100.0 * double(values.size() - 1);
    const size_t below = size_t(std::floor(position));
    const size_t above = std::min(below + 1, values.size() - 1);
    return values[below] + (position - double(below)) * (values[above] - values[below]);
}

}  // namespace sl
