#pragma once
// env.json: where a run was measured, so that its numbers can be read later: machine, OS, CPU,
// GL, compiler and flags, library versions, git state, and the experiment (file verbatim,
// overrides, the effective document).

#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/experiment.h"
#include "experiments/rows.h"

namespace sl::experiments {

nlohmann::ordered_json environment(const Experiment& experiment,
                                   const std::vector<StoredRow>& rows);

}  // namespace sl::experiments
