#pragma once
// A sweep's cells aggregated over their repetitions, as the tables and the baseline comparison
// show them: the median frame time with its bootstrap interval (statistics.h), the mean error,
// the volume cost; and how one is written.

#include <optional>
#include <string>
#include <vector>

#include "experiments/rows.h"
#include "experiments/statistics.h"

namespace sl::experiments {

// Per cell, over its repetitions: the median frame time with its confidence interval (the
// bootstrap over repetitions and frames, statistics.h) and the mean error.
struct Entry {
    Cell cell;
    double frame_ms = 0.0;
    std::optional<double> error;
    double volume_ms = 0.0;  // volume_cost_ms
    Interval frame_ms_interval;
    bool has_interval = false;  // rows written before the frames were kept have none
    std::vector<const StoredRow*> rows;
};

// A row's frame times: its per-frame samples, or its median alone (an older row; `complete` is
// then set false).
std::vector<double> frame_samples(const nlohmann::ordered_json& row, bool& complete);
std::vector<Entry> aggregate(const std::vector<StoredRow>& rows, const std::string& metric);
// "30.9 [29.8–31.5]": the FPS with its interval.
std::string fps_text(const Entry& entry);
// The fastest cell when its interval does not overlap the runner-up's; null for a tie.
const Entry* significant_fastest(const std::vector<const Entry*>& cells);
// The error in the metric's own unit (rel_rmse as a percentage, psnr in dB).
std::string format_error(const std::string& metric, double value);

}  // namespace sl::experiments
