#pragma once
// Order statistics of measured series: medians and percentiles of frame times, and named series
// (per-frame counters and GPU sections) gathered frame by frame and reduced to their medians.

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace sl {

double median(std::vector<double> values);
// The p-th percentile (p in [0, 100]) with linear interpolation between order statistics.
double percentile(std::vector<double> values, double p);

// Named values per frame, each name's series in first-seen order: collect() appends one frame's
// values, medians() reduces each series.
using NamedSeries = std::vector<std::pair<std::string, std::vector<double>>>;
void collect(NamedSeries& series, const std::vector<std::pair<std::string, double>>& values);
std::vector<std::pair<std::string, double>> medians(const NamedSeries& series);

// Milliseconds of wall time since `start`, for stage timings.
inline double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

}  // namespace sl
