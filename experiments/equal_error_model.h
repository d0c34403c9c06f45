#pragma once
// What the equal-error report states, computed before any of it is formatted
// (equal_error_report.cpp writes it): per target, every search group's outcome; per target,
// scene and size, each method's cheapest variant reaching the target, the baselines (the best
// methods without regions), the best region method and the plain method, by frame time and by
// the timers' volume cost; and the volume cost by difference (frame − none), paired where the
// cells were (docs/harness.md, "Paired").

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "experiments/aggregate.h"
#include "experiments/equal_error.h"
#include "experiments/experiment.h"
#include "experiments/rows.h"

namespace sl::experiments {

// A volume cost as the frame time less `none`'s: the median of the per-pair differences with its
// bootstrap interval (paired cells), or the difference of the two cells' medians with the interval
// from their two intervals (which does not hold the drift between the cells).
struct VolumeDifference {
    double ms = 0.0;
    std::optional<Interval> interval;
    bool paired = false;
};

// One scene and size at one target. Pointers point into EqualErrorTarget::outcomes; null where no
// such variant reached the target.
struct EqualErrorGroup {
    std::string scene;
    int width = 0;
    int height = 0;
    // Each method's cheapest reached (and completely measured) variant, by frame time and by the
    // timers' volume cost.
    std::map<std::string, const SearchOutcome*> best, best_volume;
    const SearchOutcome* baseline = nullptr;  // the cheapest method without regions, by frame
    const SearchOutcome* baseline_volume = nullptr;  // ... by volume cost
    const SearchOutcome* hybrid = nullptr;  // the cheapest region method (not a baseline), by frame
    const SearchOutcome* hybrid_volume = nullptr;  // ... by volume cost
    const SearchOutcome* plain_frame = nullptr;    // the plain method's cheapest variant
    const SearchOutcome* plain_volume = nullptr;
    const Entry* none = nullptr;  // `none` at this scene and size, when it ran
};

struct EqualErrorTarget {
    double target = 0.0;
    std::vector<SearchOutcome> outcomes;  // one per search group, in search_groups() order
    std::vector<EqualErrorGroup> groups;  // per scene, then size, in the experiment's order
};

class EqualErrorModel {
public:
    EqualErrorModel(const Experiment& experiment, const std::vector<StoredRow>& rows);
    EqualErrorModel(const EqualErrorModel&) = delete;  // groups point into targets' outcomes
    EqualErrorModel& operator=(const EqualErrorModel&) = delete;

    const Experiment& experiment() const { return x_; }
    // The methods shown as columns: every method but `none`, which is the frame the volume cost
    // by difference is measured against.
    const std::vector<std::string>& shown() const { return shown_; }
    const std::vector<EqualErrorTarget>& targets() const { return targets_; }
    bool measures_none() const { return measures_none_; }

    // The cell an outcome measured: its group with the searched parameter at the value found.
    static Cell probed_cell(const SearchOutcome& outcome);
    const Entry* entry_of(const Cell& cell) const;
    std::optional<VolumeDifference> difference_of(const SearchOutcome& outcome) const;
    // `none`'s shadow-map pass (with a VSM's blur), the median over its repetitions.
    static double none_shadow_ms(const Entry& none);
    // Why a difference gives no ratio ("" when it does): no interval, an interval that holds
    // zero, or a timer outside the difference's interval (the two measures disagree).
    std::string unresolved(const SearchOutcome& outcome) const;
    // Whether the timers' volume cost lies outside the difference's interval.
    bool timer_disagrees(const SearchOutcome& outcome) const;
    // Whether the frame-time intervals of two outcomes' cells overlap (a tie).
    bool frame_intervals_overlap(const SearchOutcome* a, const SearchOutcome& b) const;

private:
    const Entry* none_entry(const std::string& scene, int width, int height) const;
    EqualErrorGroup group_at(const EqualErrorTarget& target, const std::string& scene, int width,
                             int height) const;

    const Experiment& x_;
    std::vector<Entry> entries_;
    std::vector<std::string> shown_;
    std::vector<EqualErrorTarget> targets_;
    bool measures_none_ = false;
};

// An interval's exclusion of a value (false without an interval).
bool outside(double value, const std::optional<Interval>& interval);

}  // namespace sl::experiments
