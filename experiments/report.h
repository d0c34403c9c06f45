#pragma once
// The Markdown reports of a bench directory, from its rows (rows.h): Nilsson Table 6.1's layout
// of a sweep, the baseline comparison, and how tables name scenes. The CSV files are csv.h,
// env.json environment.h; bench.h's write_summary writes them all.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/experiment.h"
#include "experiments/rows.h"

namespace sl::experiments {

// This run beside a baseline run of the same experiment (the committed results, another machine):
// per cell, in this run's order, the FPS here and there and their ratio, and the error here and
// there; a cell only one of them has is marked. Markdown, with both machines named. Throws when
// the baseline holds no rows.
std::string baseline_comparison(const Experiment& experiment, const std::filesystem::path& out,
                                const std::filesystem::path& baseline);

// table.md: the sweep's table (or the equal-error report and its probes), the animation table,
// the regions and fragments tables, under a header naming the machine (`env`, environment.h);
// and equal_error.csv's text when the experiment has [equal_error].
struct Report {
    std::string markdown;
    std::string equal_error_csv;
};
Report make_report(const Experiment& experiment, const std::vector<StoredRow>& rows,
                   const nlohmann::ordered_json& env);

// Nilsson Table 6.1's layout: rows (dz ×) scene × size, columns methods, FPS with the error.
std::string sweep_table(const Experiment& experiment, const std::vector<StoredRow>& rows);

}  // namespace sl::experiments
