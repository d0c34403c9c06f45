#pragma once
// Confidence intervals of the harness's medians (docs/design.md §11). A cell's frame times come in
// repetitions (fresh GL contexts) of frames; the frames of one repetition share its context,
// driver state and machine load, so they are not independent of each other across repetitions.
// The interval is a two-level percentile bootstrap (Davison & Hinkley 1997, §3.8): each resample
// draws the repetitions with replacement, then the frames within each drawn repetition with
// replacement, and takes the median of the pooled draw; the interval is the (1 ± level)/2
// quantiles of those medians. With one repetition it is the plain bootstrap over frames.
// Deterministic: the resampling is seeded.

#include <cstdint>
#include <vector>

namespace sl::experiments {

struct Interval {
    double low = 0.0;
    double high = 0.0;
    bool overlaps(const Interval& other) const { return low <= other.high && other.low <= high; }
};

constexpr double kConfidence = 0.95;
constexpr int kResamples = 2000;

// The bootstrap interval of the median of the pooled samples; groups may differ in size, empty
// groups are ignored; {0, 0} when there are no samples.
Interval median_interval(const std::vector<std::vector<double>>& groups,
                         double confidence = kConfidence, int resamples = kResamples,
                         uint64_t seed = 1);

}  // namespace sl::experiments
