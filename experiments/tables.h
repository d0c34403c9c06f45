#pragma once
// The Markdown tables of table.md, from a bench directory's rows (rows.h): Nilsson Table 6.1's
// layout of a sweep, the animation table, the equal-error search's probes (the report itself is
// equal_error_report.h), the regions and fragments tables, and the line that states the protocol.

#include <string>
#include <utility>
#include <vector>

#include "experiments/aggregate.h"
#include "experiments/experiment.h"
#include "experiments/rows.h"

namespace sl::experiments {

// Nilsson Table 6.1's layout: rows (dz ×) scene × size, columns methods, FPS with the error.
std::string sweep_table(const Experiment& experiment, const std::vector<StoredRow>& rows);
// Animation cells (docs/design.md §11): frame times with intervals, the CPU update, the error per
// frame and the temporal metrics; "" for a still experiment.
std::string animation_table(const Experiment& experiment, const std::vector<Entry>& entries);
// Every probe of an equal-error search, one row each.
std::string probes_table(const Experiment& experiment, const std::vector<StoredRow>& rows);
// The beam tree and the eye-ray fractions of each scene and size; the analytic passes' fragments.
std::string regions_table(const std::vector<StoredRow>& rows);
std::string fragments_table(const std::vector<StoredRow>& rows);
// The measuring protocol in one sentence, for the header of table.md.
std::string protocol_text(const Experiment& experiment);

}  // namespace sl::experiments
