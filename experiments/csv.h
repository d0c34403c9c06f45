#pragma once
// The harness's CSV files (docs/harness.md, "Outputs"): results.csv, one row per cell and
// repetition in long format, and frames.csv, every frame of every animation row.

#include <string>
#include <vector>

#include "experiments/rows.h"

namespace sl::experiments {

// One value as a CSV field: empty for null, quoted when it holds a comma, a quote or a newline.
std::string csv_field(const nlohmann::ordered_json& value);

// results.csv's text: the union of the rows' columns, fixed ones first.
std::string results_csv(const std::vector<StoredRow>& rows);
// frames.csv's text: every frame of every animation row (its per_frame series), long format.
std::string frames_csv(const std::vector<StoredRow>& rows);

}  // namespace sl::experiments
