#include "experiments/equal_error_report.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "experiments/csv.h"
#include "experiments/equal_error_model.h"

namespace sl::experiments {

namespace {

double frame_cost(const SearchOutcome& o) {
    return o.summary.frame_ms;
}
double volume_cost(const SearchOutcome& o) {
    return o.summary.volume_ms;
}
using Cost = double (*)(const SearchOutcome&);

std::string introduction(const EqualErrorModel& model) {
    const Experiment& x = model.experiment();
    std::string md = "## Equal error\n\n";
    md += fmt::format(
        "Per method, the cheapest value of its cost parameter whose relative RMSE of I_s reaches "
        "the target (bisection in log space, tolerance {:.0f}%), the median frame time there and "
        "the speed-up against the fastest method that uses no regions ({}) at the same target; "
        "then (vol) the volume cost — the volume pass's GPU time plus the method's CPU work per "
        "frame — of its cheapest variant by that cost, and the speed-up against the method "
        "without regions cheapest by it. The last column names each row's baselines. Methods "
        "without a cost parameter are measured as they are.\n",
        100 * x.equal_error->tolerance, fmt::join(x.equal_error->baselines, ", "));
    if (model.measures_none()) {
        md +=
            "\nThe volume cost is measured a second way too: the median frame time less that of "
            "`none` (no medium) in the same run, with the interval of the difference (from the "
            "two frame-time intervals). GPU timers are not to be trusted on every backend "
            "(llvmpipe books a pass's time in the wrong section when consecutive passes draw to "
            "one framebuffer); the difference holds on every backend, and the headline rests on "
            "it. Where the timer lies outside the difference's interval the row is flagged "
            "(\"Volume cost two ways\").\n";
    }
    return md;
}

// " (×r)" against a baseline, or nothing without one.
std::string ratio_to(const SearchOutcome* baseline, const SearchOutcome& o, Cost cost) {
    return baseline ? fmt::format(" (×{:.2f})", cost(*baseline) / cost(o)) : std::string();
}

// One row of a target's table: each shown method's cheapest variant by frame time and by volume
// cost, each against its baseline.
std::string table_row(const EqualErrorModel& model, const EqualErrorGroup& g) {
    std::string md = fmt::format("| {} | {}x{} |", scene_label(g.scene), g.width, g.height);
    for (const std::string& method : model.shown()) {
        if (!g.best.contains(method)) {
            md += " not reached |";
            continue;
        }
        const SearchOutcome& o = *g.best.at(method);
        const SearchOutcome& v = *g.best_volume.at(method);
        md += fmt::format(" {}{:.1f} ms{} · vol {}{:.1f} ms{} |",
                          o.parameter.empty() ? "" : fmt::format("{}={}: ", o.parameter, o.value),
                          o.summary.frame_ms, ratio_to(g.baseline, o, frame_cost),
                          &v == &o ? "" : fmt::format("at {}={} ", v.parameter, v.value),
                          v.summary.volume_ms, ratio_to(g.baseline_volume, v, volume_cost));
    }
    return md + fmt::format(" {} · {} |\n", g.baseline ? g.baseline->group.method : "none reached",
                            g.baseline_volume ? g.baseline_volume->group.method : "none reached");
}

std::string target_table(const EqualErrorModel& model, const EqualErrorTarget& target) {
    std::string md = fmt::format("\n### Target: relative RMSE {:.3g}%\n\n", 100 * target.target);
    md += fmt::format("| scene | size | {} | baseline (frame · vol) |\n|---|---|",
                      fmt::join(model.shown(), " | "));
    for (size_t i = 0; i < model.shown().size(); ++i) {
        md += "---:|";
    }
    md += "---|\n";
    for (const EqualErrorGroup& g : target.groups) {
        md += table_row(model, g);
    }
    return md;
}

// "12.5 ms [12.0–13.0]": an outcome's volume cost by difference, which must exist.
std::string difference_text(const EqualErrorModel& model, const SearchOutcome& o) {
    const VolumeDifference d = *model.difference_of(o);
    return fmt::format("{:.1f} ms [{:.1f}–{:.1f}]", d.ms, d.interval ? d.interval->low : 0.0,
                       d.interval ? d.interval->high : 0.0);
}

// Rows of "Volume cost two ways": each method's cheapest variant by frame time, by the timers
// and by difference (where `none` ran).
void add_two_ways(const EqualErrorModel& model, double target, const EqualErrorGroup& g,
                  std::vector<std::string>& rows) {
    if (!g.none) {
        return;
    }
    for (const std::string& method : model.shown()) {
        if (!g.best.contains(method)) {
            continue;
        }
        const SearchOutcome& o = *g.best.at(method);
        // The timer's cheapest variant against the difference at the frame's.
        const bool disagree = g.best_volume.at(method) == &o && model.timer_disagrees(o);
        rows.push_back(fmt::format("| {:.3g}% | {} | {}x{} | {} | {} | {:.1f} ms | {} |{}",
                                   100 * target, scene_label(g.scene), g.width, g.height, method,
                                   EqualErrorModel::probed_cell(o).settings_text(),
                                   o.summary.volume_ms, difference_text(model, o),
                                   disagree ? " **disagree** |" : " |"));
    }
}

// "×r against **m** c ms"; a cost at or below zero (a difference within the noise of `none`) has
// no ratio.
std::string against(const SearchOutcome* other, const SearchOutcome& ours, Cost cost) {
    if (!other) {
        return "no plain method";
    }
    if (!(cost(ours) > 0.0) || !(cost(*other) > 0.0)) {
        return fmt::format("against **{}** {:.1f} ms: no ratio (a cost at or below zero)",
                           other->group.method, cost(*other));
    }
    return fmt::format("×{:.2f} against **{}** {:.1f} ms", cost(*other) / cost(ours),
                       other->group.method, cost(*other));
}

// The plain method the same way, unless it is the baseline itself.
std::string and_plain(const SearchOutcome* baseline, const SearchOutcome* plain,
                      const SearchOutcome& ours, Cost cost) {
    if (plain && baseline && plain->group.method == baseline->group.method) {
        return fmt::format(" ({} is the plain method)", plain->group.method);
    }
    return "; " + against(plain, ours, cost);
}

// The frame-time ratio is a tie where the two medians' intervals overlap.
std::string overlap_note(const EqualErrorModel& model, const SearchOutcome* other,
                         const SearchOutcome& ours) {
    return model.frame_intervals_overlap(other, ours)
               ? " (not resolved: the frame times' intervals overlap)"
               : "";
}

// By difference, a ratio only where it is resolved: both differences' intervals above zero and
// each within reach of its timer's volume cost; "not resolved" and why otherwise.
std::string against_by_difference(const EqualErrorModel& model, const SearchOutcome* other,
                                  const SearchOutcome& ours) {
    if (!other) {
        return "no plain method";
    }
    for (const SearchOutcome* o : {&ours, other}) {
        if (const std::string why = model.unresolved(*o); !why.empty()) {
            return fmt::format("against **{}** {}: not resolved ({})", other->group.method,
                               difference_text(model, *other), why);
        }
    }
    return fmt::format("×{:.2f} against **{}** {}",
                       model.difference_of(*other)->ms / model.difference_of(ours)->ms,
                       other->group.method, difference_text(model, *other));
}

// The headline's part by difference, with the passes every frame pays whatever the method.
std::string headline_by_difference(const EqualErrorModel& model, const EqualErrorGroup& g) {
    const SearchOutcome& hybrid = *g.hybrid;
    const bool plain_is_baseline =
        g.plain_frame && g.plain_frame->group.method == g.baseline->group.method;
    return fmt::format(
        " volume cost (frame − none{}) **{}** {}: {}{}. (Fixed passes: `none`'s frame {:.1f} "
        "ms, its shadow map {:.1f} ms.)",
        model.difference_of(hybrid)->paired ? ", paired" : "", hybrid.group.method,
        difference_text(model, hybrid), against_by_difference(model, g.baseline, hybrid),
        plain_is_baseline ? fmt::format(" ({} is the plain method)", g.plain_frame->group.method)
                          : "; " + against_by_difference(model, g.plain_frame, hybrid),
        g.none->frame_ms, EqualErrorModel::none_shadow_ms(*g.none));
}

// The headline: the best region method against the best method without regions at this target,
// and against the plain method; by the volume cost as the frame-time difference (where `none`
// ran), by the frame time, and by the timers' volume cost. "" where a side reached nothing.
std::string headline(const EqualErrorModel& model, double target, const EqualErrorGroup& g) {
    if (!g.hybrid || !g.baseline || !g.hybrid_volume || !g.baseline_volume) {
        return "";
    }
    std::string line = fmt::format("- {:.3g}% on {} {}x{}:", 100 * target, scene_label(g.scene),
                                   g.width, g.height);
    if (g.none) {
        line += headline_by_difference(model, g);
    }
    const bool plain_differs =
        g.plain_frame && g.plain_frame->group.method != g.baseline->group.method;
    line += fmt::format(
        " Frame **{}** {:.1f} ms: {}{}. Volume cost by timers **{}** {:.1f} ms: {}{}.",
        g.hybrid->group.method, frame_cost(*g.hybrid),
        against(g.baseline, *g.hybrid, frame_cost) + overlap_note(model, g.baseline, *g.hybrid),
        and_plain(g.baseline, g.plain_frame, *g.hybrid, frame_cost) +
            (plain_differs ? overlap_note(model, g.plain_frame, *g.hybrid) : std::string()),
        g.hybrid_volume->group.method, volume_cost(*g.hybrid_volume),
        against(g.baseline_volume, *g.hybrid_volume, volume_cost),
        and_plain(g.baseline_volume, g.plain_volume, *g.hybrid_volume, volume_cost));
    return line;
}

constexpr const char* kCsvHeader =
    "target,scene,width,height,method,params,parameter,value,reached,complete,rel_rmse,"
    "frame_ms,fps,best_baseline,speedup_vs_best_baseline,volume_cost_ms,"
    "best_volume_baseline,volume_speedup_vs_best_baseline,volume_by_difference_ms,"
    "volume_by_difference_low,volume_by_difference_high,timer_and_difference_disagree,"
    "probes\n";

// One line of equal_error.csv per outcome of a target.
std::string csv_rows(const EqualErrorModel& model, const EqualErrorTarget& target) {
    auto group_of = [&](const SearchOutcome& o) -> const EqualErrorGroup* {
        for (const EqualErrorGroup& g : target.groups) {
            if (g.scene == o.group.scene && g.width == o.group.width &&
                g.height == o.group.height) {
                return &g;
            }
        }
        return nullptr;
    };
    // The volume cost by difference: value, interval, and the flag.
    auto difference_fields = [&](const SearchOutcome& o) -> std::string {
        const std::optional<VolumeDifference> d =
            o.complete && o.reached ? model.difference_of(o) : std::nullopt;
        if (!d || !d->interval) {
            return ",,,";
        }
        return fmt::format("{},{},{},{}", d->ms, d->interval->low, d->interval->high,
                           outside(o.summary.volume_ms, d->interval) ? 1 : 0);
    };
    auto number_if = [](bool shown, double value) {
        return shown ? fmt::format("{}", value) : std::string();
    };
    std::string csv;
    for (const SearchOutcome& o : target.outcomes) {
        const EqualErrorGroup* g = group_of(o);
        const SearchOutcome* baseline = g ? g->baseline : nullptr;
        const SearchOutcome* volume_baseline = g ? g->baseline_volume : nullptr;
        const bool measured = o.complete && (o.reached || !o.value.empty());
        csv += fmt::format(
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", target.target,
            csv_field(o.group.scene), o.group.width, o.group.height, o.group.method,
            csv_field(o.group.settings_text()), o.parameter, o.value, o.reached ? 1 : 0,
            o.complete ? 1 : 0, number_if(measured, o.summary.rel_rmse),
            number_if(measured, o.summary.frame_ms),
            number_if(measured, 1000.0 / o.summary.frame_ms),
            baseline ? baseline->group.method : "",
            number_if(baseline && o.reached,
                      baseline ? baseline->summary.frame_ms / o.summary.frame_ms : 0.0),
            number_if(measured, o.summary.volume_ms),
            volume_baseline ? volume_baseline->group.method : "",
            number_if(
                volume_baseline && o.reached,
                volume_baseline ? volume_baseline->summary.volume_ms / o.summary.volume_ms : 0.0),
            difference_fields(o), o.probes.size());
    }
    return csv;
}

}  // namespace

std::pair<std::string, std::string> equal_error_report(const Experiment& x,
                                                       const std::vector<StoredRow>& rows) {
    const EqualErrorModel model(x, rows);
    std::string md = introduction(model);
    std::string csv = kCsvHeader;
    std::vector<std::string> headlines, two_ways;
    for (const EqualErrorTarget& target : model.targets()) {
        md += target_table(model, target);
        for (const EqualErrorGroup& g : target.groups) {
            add_two_ways(model, target.target, g, two_ways);
            if (std::string line = headline(model, target.target, g); !line.empty()) {
                headlines.push_back(std::move(line));
            }
        }
        csv += csv_rows(model, target);
    }
    if (!two_ways.empty()) {
        md +=
            "\n### Volume cost two ways\n\nEach method's cheapest variant by frame time: the "
            "volume cost by the GPU timers (the volume pass plus the method's CPU work) and "
            "as its frame time less `none`'s, with the 95% interval of the difference; "
            "**disagree** where the timer lies outside that interval.\n\n"
            "| target | scene | size | method | at | timers | frame − none [95%] | |\n"
            "|---|---|---|---|---|---:|---:|---|\n" +
            fmt::format("{}\n", fmt::join(two_ways, "\n"));
    }
    if (!headlines.empty()) {
        const std::string& plain = x.equal_error->plain;
        md += fmt::format(
            "\n### Headline: the best region method against the best method without regions "
            "({}) and against {}, at equal error\n\n{}\n",
            fmt::join(x.equal_error->baselines, ", "), plain.empty() ? "none" : plain,
            fmt::join(headlines, "\n"));
    }
    return {md, csv};
}

}  // namespace sl::experiments
