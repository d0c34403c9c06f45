#pragma once
// The summary outputs of a bench directory, from the rows in cells/ (rows.h): results.csv and
// frames.csv (csv.h), table.md and equal_error.csv (report.h), env.json (environment.h), written
// together and atomically, then plots/ by experiments/plots.py.

#include <filesystem>

#include "experiments/experiment.h"

namespace sl::experiments {

void write_summary(const Experiment& experiment, const std::filesystem::path& out);

}  // namespace sl::experiments
