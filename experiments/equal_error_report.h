#pragma once
// The equal-error report of table.md and equal_error.csv, written from the computed model
// (equal_error_model.h): per target, a table of each method's cheapest variant reaching it; the
// volume cost two ways; the headline, with a ratio only where the measures resolve it.

#include <string>
#include <utility>
#include <vector>

#include "experiments/experiment.h"
#include "experiments/rows.h"

namespace sl::experiments {

// The report (Markdown) and equal_error.csv's text.
std::pair<std::string, std::string> equal_error_report(const Experiment& experiment,
                                                       const std::vector<StoredRow>& rows);

}  // namespace sl::experiments
