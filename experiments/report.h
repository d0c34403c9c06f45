#pragma once
// table.md of a bench directory: its header (the experiment, the machine, the protocol) over the
// tables of tables.h; and equal_error.csv. summary.h writes them with the CSV files and env.json.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/experiment.h"
#include "experiments/rows.h"

namespace sl::experiments {

// table.md: the sweep's table (or the equal-error report and its probes), the animation table,
// the regions and fragments tables, under a header naming the machine (`env`, environment.h);
// and equal_error.csv's text when the experiment has [equal_error].
struct Report {
    std::string markdown;
    std::string equal_error_csv;
};
Report make_report(const Experiment& experiment, const std::vector<StoredRow>& rows,
                   const nlohmann::ordered_json& env);

}  // namespace sl::experiments
