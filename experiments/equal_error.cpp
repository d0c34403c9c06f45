#include "experiments/equal_error.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace sl::experiments {

namespace {

// Probe values as short text: integers exactly, reals to three significant digits (the cell id
// and the CSV carry them; the bisection stops long before the fourth digit matters).
std::string format_value(double value, bool integer) {
    return integer ? std::to_string(std::llround(value)) : fmt::format("{:.3g}", value);
}

}  // namespace

Cell with_setting(const Cell& group, const std::string& name, const std::string& value) {
    Cell cell = group;
    cell.settings.push_back({name, value});
    std::sort(cell.settings.begin(), cell.settings.end(),
              [](const Setting& a, const Setting& b) { return a.name < b.name; });
    return cell;
}

std::vector<Cell> search_groups(const Experiment& experiment) {
    std::vector<Cell> groups;
    for (Cell cell : experiment.cells()) {
        if (auto s = experiment.equal_error->search.find(cell.method);
            s != experiment.equal_error->search.end()) {
            std::erase_if(cell.settings,
                          [&](const Setting& x) { return x.name == s->second.parameter; });
        }
        if (std::find(groups.begin(), groups.end(), cell) == groups.end()) {
            groups.push_back(std::move(cell));
        }
    }
    return groups;
}

namespace {

// The bisection of one group's search parameter: every probe measured once, the outcome filled
// as it goes.
class Bisection {
public:
    Bisection(SearchOutcome& outcome, const Search& search, const CellMeasure& measure)
        : outcome_(outcome), search_(search), measure_(measure) {}

    // Invariant: `good` reaches the target, `bad` does not. Bisects the log of the parameter
    // until the two are within `tolerance` (relative) or adjacent as printed.
    void run(double tolerance) {
        // The expensive end must reach the target, the cheap end must not; otherwise done.
        const std::optional<bool> expensive = probe(search_.expensive);
        if (!expensive) {
            return;
        }
        if (!*expensive) {
            return record(search_.expensive, false);
        }
        const std::optional<bool> cheap = probe(search_.cheap);
        if (!cheap) {
            return;
        }
        if (*cheap) {
            return record(search_.cheap, true);
        }
        double good = search_.expensive, bad = search_.cheap;
        for (int iteration = 0; iteration < 32; ++iteration) {
            const double ratio = std::max(good, bad) / std::min(good, bad);
            if (ratio <= 1.0 + tolerance) {
                break;
            }
            double middle = std::sqrt(good * bad);
            if (search_.integer) {
                middle = std::round(middle);
                if (middle == std::round(good) || middle == std::round(bad)) {
                    break;
                }
            } else if (format_value(middle, false) == format_value(good, false) ||
                       format_value(middle, false) == format_value(bad, false)) {
                break;
            }
            const std::optional<bool> reached = probe(middle);
            if (!reached) {
                return;
            }
            (*reached ? good : bad) = middle;
        }
        record(good, true);
    }

private:
    // Whether the setting reaches the target (measured at most once); nothing when the
    // measurement did not complete.
    std::optional<bool> probe(double value) {
        const std::string text = format_value(value, search_.integer);
        for (const Probe& p : outcome_.probes) {
            if (p.value == text) {
                return p.summary.rel_rmse <= outcome_.target;
            }
        }
        const std::optional<CellSummary> summary =
            measure_(with_setting(outcome_.group, search_.parameter, text));
        if (!summary) {
            outcome_.complete = false;
            return std::nullopt;
        }
        outcome_.probes.push_back({text, *summary});
        return summary->rel_rmse <= outcome_.target;
    }

    void record(double value, bool reached) {
        const std::string text = format_value(value, search_.integer);
        outcome_.value = text;
        outcome_.reached = reached;
        for (const Probe& p : outcome_.probes) {
            if (p.value == text) {
                outcome_.summary = p.summary;
            }
        }
    }

    SearchOutcome& outcome_;
    const Search& search_;
    const CellMeasure& measure_;
};

}  // namespace

SearchOutcome search_equal_error(const Experiment& experiment, const Cell& group, double target,
                                 const CellMeasure& measure) {
    SearchOutcome outcome;
    outcome.group = group;
    outcome.target = target;
    const auto found = experiment.equal_error->search.find(group.method);
    if (found == experiment.equal_error->search.end()) {
        // Nothing to trade: the method's one setting reaches the target or it does not.
        const std::optional<CellSummary> summary = measure(group);
        outcome.complete = summary.has_value();
        if (summary) {
            outcome.summary = *summary;
            outcome.reached = summary->rel_rmse <= target;
        }
        return outcome;
    }
    outcome.parameter = found->second.parameter;
    Bisection(outcome, found->second, measure).run(experiment.equal_error->tolerance);
    return outcome;
}

}  // namespace sl::experiments
