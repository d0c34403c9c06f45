#include "experiments/aggregate.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/statistics.h"

namespace sl::experiments {

using Json = nlohmann::ordered_json;

// A row's frame times: its per-frame samples, or its median alone (an older row).
std::vector<double> frame_samples(const Json& row, bool& complete) {
    std::vector<double> samples;
    if (row.contains("frame_ms_samples") && row["frame_ms_samples"].is_array()) {
        for (const Json& v : row["frame_ms_samples"]) {
            samples.push_back(v.get<double>());
        }
    }
    if (samples.empty()) {
        complete = false;
        samples.push_back(row.at("frame_ms_median").get<double>());
    }
    return samples;
}

std::vector<Entry> aggregate(const std::vector<StoredRow>& rows, const std::string& metric) {
    std::vector<Entry> entries;
    std::vector<std::vector<double>> times, errors, volume_times;
    std::vector<std::vector<std::vector<double>>> samples;
    std::vector<bool> complete;
    for (const StoredRow& r : rows) {
        auto found = std::find_if(entries.begin(), entries.end(),
                                  [&](const Entry& e) { return e.cell == r.cell; });
        size_t i = size_t(found - entries.begin());
        if (found == entries.end()) {
            Entry entry;
            entry.cell = r.cell;
            entries.push_back(std::move(entry));
            times.emplace_back();
            errors.emplace_back();
            volume_times.emplace_back();
            samples.emplace_back();
            complete.push_back(true);
        }
        entries[i].rows.push_back(&r);
        times[i].push_back(r.row.at("frame_ms_median").get<double>());
        bool whole = true;
        samples[i].push_back(frame_samples(r.row, whole));
        complete[i] = complete[i] && whole;
        volume_times[i].push_back(r.row.value("volume_cost_ms", 0.0));
        if (!metric.empty() && r.row.contains(metric) && r.row.at(metric).is_number()) {
            errors[i].push_back(r.row.at(metric).get<double>());
        }
    }
    for (size_t i = 0; i < entries.size(); ++i) {
        entries[i].volume_ms = median(volume_times[i]);
        if (complete[i]) {
            // The pooled median of every frame, and its interval.
            std::vector<double> pooled;
            for (const auto& group : samples[i]) {
                pooled.insert(pooled.end(), group.begin(), group.end());
            }
            entries[i].frame_ms = median(pooled);
            entries[i].frame_ms_interval = median_interval(samples[i]);
            entries[i].has_interval = true;
        } else {
            entries[i].frame_ms = median(times[i]);
        }
        if (!errors[i].empty()) {
            double sum = 0.0;
            for (const double e : errors[i]) {
                sum += e;
            }
            entries[i].error = sum / double(errors[i].size());
        }
    }
    return entries;
}

// FPS with its interval ("30.9 [29.8–31.5]"; the interval of the median frame time inverted).
std::string fps_text(const Entry& e) {
    const std::string fps = fmt::format("{:.1f}", 1000.0 / e.frame_ms);
    if (!e.has_interval) {
        return fps;
    }
    return fmt::format("{} [{:.1f}–{:.1f}]", fps, 1000.0 / e.frame_ms_interval.high,
                       1000.0 / e.frame_ms_interval.low);
}

// The fastest of a row's entries when it is significantly faster than the next: its interval
// does not overlap the runner-up's (a row of one is its own fastest); null otherwise.
const Entry* significant_fastest(const std::vector<const Entry*>& cells) {
    std::vector<const Entry*> present;
    for (const Entry* e : cells) {
        if (e) {
            present.push_back(e);
        }
    }
    if (present.empty()) {
        return nullptr;
    }
    std::sort(present.begin(), present.end(),
              [](const Entry* a, const Entry* b) { return a->frame_ms < b->frame_ms; });
    if (present.size() == 1) {
        return present.front();
    }
    const Entry& first = *present[0];
    const Entry& second = *present[1];
    if (!first.has_interval || !second.has_interval ||
        first.frame_ms_interval.overlaps(second.frame_ms_interval)) {
        return nullptr;
    }
    return &first;
}

std::string format_error(const std::string& metric, double value) {
    return metric == "psnr"       ? fmt::format("{:.1f} dB", value)
           : metric == "rel_rmse" ? fmt::format("{:.2f}%", 100.0 * value)
                                  : fmt::format("{:.3g}", value);
}

}  // namespace sl::experiments
