#include "experiments/equal_error_model.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/check.h"
#include "core/statistics.h"

namespace sl::experiments {

bool outside(double value, const std::optional<Interval>& interval) {
    return interval && (value < interval->low || value > interval->high);
}

EqualErrorModel::EqualErrorModel(const Experiment& x, const std::vector<StoredRow>& rows)
    : x_(x), entries_(aggregate(rows, "rel_rmse")) {
    SL_CHECK(x.equal_error.has_value());
    for (const std::string& method : x.methods) {
        if (method != "none") {
            shown_.push_back(method);
        }
    }
    for (const Cell& cell : x.cells()) {
        if (cell.method == "none") {
            measures_none_ = true;
            break;
        }
    }
    const CellMeasure lookup = [&](const Cell& cell) -> std::optional<CellSummary> {
        for (const Entry& e : entries_) {
            if (e.cell == cell && e.error) {
                return CellSummary{*e.error, e.frame_ms, e.volume_ms};
            }
        }
        return std::nullopt;
    };
    const std::vector<Cell> search = search_groups(x);
    // Groups point into their target's outcomes: every target is in place before any group is
    // computed, and neither vector changes afterwards.
    targets_.resize(x.equal_error->targets.size());
    for (size_t t = 0; t < targets_.size(); ++t) {
        EqualErrorTarget& target = targets_[t];
        target.target = x.equal_error->targets[t];
        for (const Cell& group : search) {
            target.outcomes.push_back(search_equal_error(x, group, target.target, lookup));
        }
        for (const std::string& scene : x.scenes) {
            for (const auto& [w, h] : x.sizes) {
                target.groups.push_back(group_at(target, scene, w, h));
            }
        }
    }
}

EqualErrorGroup EqualErrorModel::group_at(const EqualErrorTarget& target, const std::string& scene,
                                          int w, int h) const {
    EqualErrorGroup g;
    g.scene = scene;
    g.width = w;
    g.height = h;
    for (const SearchOutcome& o : target.outcomes) {
        if (o.group.scene != scene || o.group.width != w || o.group.height != h || !o.reached ||
            !o.complete) {
            continue;
        }
        const SearchOutcome*& b = g.best[o.group.method];
        if (!b || o.summary.frame_ms < b->summary.frame_ms) {
            b = &o;
        }
        const SearchOutcome*& v = g.best_volume[o.group.method];
        if (!v || o.summary.volume_ms < v->summary.volume_ms) {
            v = &o;
        }
    }
    // The cheapest of the baselines (or of the other methods) by `cost`.
    const std::vector<std::string>& names = x_.equal_error->baselines;
    auto cheapest = [&](const std::map<std::string, const SearchOutcome*>& of, auto cost,
                        bool baselines) {
        const SearchOutcome* found = nullptr;
        for (const auto& [method, o] : of) {
            const bool is_baseline = std::find(names.begin(), names.end(), method) != names.end();
            if (is_baseline == baselines && (!found || cost(*o) < cost(*found))) {
                found = o;
            }
        }
        return found;
    };
    auto frame = [](const SearchOutcome& o) { return o.summary.frame_ms; };
    auto volume = [](const SearchOutcome& o) { return o.summary.volume_ms; };
    g.baseline = cheapest(g.best, frame, true);
    g.baseline_volume = cheapest(g.best_volume, volume, true);
    g.hybrid = cheapest(g.best, frame, false);
    g.hybrid_volume = cheapest(g.best_volume, volume, false);
    const std::string& plain = x_.equal_error->plain;
    g.plain_frame = g.best.contains(plain) ? g.best.at(plain) : nullptr;
    g.plain_volume = g.best_volume.contains(plain) ? g.best_volume.at(plain) : nullptr;
    g.none = none_entry(scene, w, h);
    return g;
}

Cell EqualErrorModel::probed_cell(const SearchOutcome& o) {
    return o.parameter.empty() ? o.group : with_setting(o.group, o.parameter, o.value);
}

const Entry* EqualErrorModel::entry_of(const Cell& cell) const {
    for (const Entry& e : entries_) {
        if (e.cell == cell) {
            return &e;
        }
    }
    return nullptr;
}

const Entry* EqualErrorModel::none_entry(const std::string& scene, int w, int h) const {
    for (const Entry& e : entries_) {
        if (e.cell.method == "none" && e.cell.scene == scene && e.cell.width == w &&
            e.cell.height == h) {
            return &e;
        }
    }
    return nullptr;
}

double EqualErrorModel::none_shadow_ms(const Entry& none) {
    std::vector<double> values;
    for (const StoredRow* r : none.rows) {
        values.push_back(r->row.value("gpu_ms_shadow", 0.0));
    }
    return median(values);
}

std::optional<VolumeDifference> EqualErrorModel::difference_of(const SearchOutcome& o) const {
    const Entry* e = entry_of(probed_cell(o));
    if (e) {
        // Paired: every repetition kept its per-pair differences.
        std::vector<std::vector<double>> pairs;
        std::vector<double> pooled;
        for (const StoredRow* r : e->rows) {
            const auto it = r->row.find("paired_difference_ms_samples");
            if (it == r->row.end() || !it->is_array()) {
                pairs.clear();
                pooled.clear();
                break;
            }
            pairs.push_back(it->get<std::vector<double>>());
            pooled.insert(pooled.end(), pairs.back().begin(), pairs.back().end());
        }
        if (!pooled.empty()) {
            return VolumeDifference{median(pooled), median_interval(pairs), true};
        }
    }
    const Entry* none = none_entry(o.group.scene, o.group.width, o.group.height);
    if (!none || !e) {
        return std::nullopt;
    }
    VolumeDifference d{e->frame_ms - none->frame_ms, std::nullopt};
    if (e->has_interval && none->has_interval) {
        d.interval = Interval{e->frame_ms_interval.low - none->frame_ms_interval.high,
                              e->frame_ms_interval.high - none->frame_ms_interval.low};
    }
    return d;
}

std::string EqualErrorModel::unresolved(const SearchOutcome& o) const {
    const std::optional<VolumeDifference> d = difference_of(o);
    if (!d || !d->interval) {
        return "no interval";
    }
    if (!(d->interval->low > 0.0)) {
        return fmt::format("{}'s interval holds zero", o.group.method);
    }
    if (outside(o.summary.volume_ms, d->interval)) {
        return fmt::format("{}'s timer and difference disagree", o.group.method);
    }
    return "";
}

bool EqualErrorModel::timer_disagrees(const SearchOutcome& o) const {
    const std::optional<VolumeDifference> d = difference_of(o);
    return d && outside(o.summary.volume_ms, d->interval);
}

bool EqualErrorModel::frame_intervals_overlap(const SearchOutcome* a,
                                              const SearchOutcome& b) const {
    const Entry* ea = a ? entry_of(probed_cell(*a)) : nullptr;
    const Entry* eb = entry_of(probed_cell(b));
    return ea && eb && ea->has_interval && eb->has_interval &&
           ea->frame_ms_interval.overlaps(eb->frame_ms_interval);
}

}  // namespace sl::experiments
