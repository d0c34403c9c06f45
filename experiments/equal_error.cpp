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
    const Search& search = found->second;
    outcome.parameter = search.parameter;

    auto probe = [&](double value) -> std::optional<bool> {
        const std::string text = format_value(value, search.integer);
        for (const Probe& p : outcome.probes) {
            if (p.value == text) {
                return p.summary.rel_rmse <= target;
            }
        }
        const std::optional<CellSummary> summary =
            measure(with_setting(group, search.parameter, text));
        if (!summary) {
            outcome.complete = false;
            return std::nullopt;
        }
        outcome.probes.push_back({text, *summary});
        return summary->rel_rmse <= target;
    };
    auto record = [&](double value, bool reached) {
        const std::string text = format_value(value, search.integer);
        outcome.value = text;
        outcome.reached = reached;
        for (const Probe& p : outcome.probes) {
            if (p.value == text) {
                outcome.summary = p.summary;
            }
        }
    };

    // The expensive end must reach the target, the cheap end must not; otherwise done.
    const std::optional<bool> expensive = probe(search.expensive);
    if (!expensive) {
        return outcome;
    }
    if (!*expensive) {
        record(search.expensive, false);
        return outcome;
    }
    const std::optional<bool> cheap = probe(search.cheap);
    if (!cheap) {
        return outcome;
    }
    if (*cheap) {
        record(search.cheap, true);
        return outcome;
    }
    // Invariant: `good` reaches the target, `bad` does not. Bisect the log of the parameter.
    double good = search.expensive, bad = search.cheap;
    const double tolerance = experiment.equal_error->tolerance;
    for (int iteration = 0; iteration < 32; ++iteration) {
        const double ratio = std::max(good, bad) / std::min(good, bad);
        if (ratio <= 1.0 + tolerance) {
            break;
        }
        double middle = std::sqrt(good * bad);
        if (search.integer) {
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
            return outcome;
        }
        (*reached ? good : bad) = middle;
    }
    record(good, true);
    return outcome;
}

}  // namespace sl::experiments
