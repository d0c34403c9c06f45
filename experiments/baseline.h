#pragma once
// A run beside a baseline run of the same experiment (`shaftlab bench --baseline`).

#include <filesystem>
#include <string>

#include "experiments/experiment.h"

namespace sl::experiments {

// This run beside a baseline run of the same experiment (the committed results, another machine):
// per cell, in this run's order, the FPS here and there and their ratio, and the error here and
// there; a cell only one of them has is marked. Markdown, with both machines named. Throws when
// the baseline holds no rows.
std::string baseline_comparison(const Experiment& experiment, const std::filesystem::path& out,
                                const std::filesystem::path& baseline);

}  // namespace sl::experiments
