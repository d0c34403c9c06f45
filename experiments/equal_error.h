#pragma once
// Equal-error comparison (docs/design.md §6): per method, the cheapest value of its cost parameter
// (dz, samples, ...) whose relative RMSE of I_s reaches a target, found by bisection in log space
// between the search's cheap and expensive ends (the error is taken as monotone in the parameter;
// every probe is a cell of the experiment, so probes are resumable and land in results.csv).

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "experiments/experiment.h"

namespace sl::experiments {

// What the search needs of a measured cell: its error and frame time, and for the report its
// volume cost (volume pass GPU time + per-frame CPU work), over the repetitions.
struct CellSummary {
    double rel_rmse = 0.0;
    double frame_ms = 0.0;
    double volume_ms = 0.0;
};
// Measures (or loads) a cell; nullopt when it is not available (a failed cell, or a summary of
// shards that lack it).
using CellMeasure = std::function<std::optional<CellSummary>(const Cell&)>;

struct Probe {
    std::string value;
    CellSummary summary;
};

struct SearchOutcome {
    Cell group;             // the cell without the searched parameter
    std::string parameter;  // empty: the method has no search and was measured as is
    double target = 0.0;
    bool complete = true;  // false when a probe was unavailable
    bool reached = false;
    std::string value;    // the cheapest value reaching the target (or the most expensive tried)
    CellSummary summary;  // at `value`
    std::vector<Probe> probes;
};

// The experiment's cells with each method's searched parameter removed, deduplicated, in sweep
// order: one search per group and target.
std::vector<Cell> search_groups(const Experiment& experiment);

// The group with its searched parameter set to `value`.
Cell with_setting(const Cell& group, const std::string& name, const std::string& value);

SearchOutcome search_equal_error(const Experiment& experiment, const Cell& group, double target,
                                 const CellMeasure& measure);

}  // namespace sl::experiments
