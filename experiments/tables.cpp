#include "experiments/tables.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.h"
#include "core/statistics.h"
#include "experiments/aggregate.h"
#include "experiments/csv.h"
#include "experiments/equal_error.h"

namespace sl::experiments {

using Json = nlohmann::ordered_json;

namespace {

template <typename T>
size_t rank(const std::vector<T>& list, const T& value) {
    return size_t(std::find(list.begin(), list.end(), value) - list.begin());
}

}  // namespace

std::string protocol_text(const Experiment& x) {
    if (x.protocol.animated()) {
        return fmt::format(
            "Animation cells: {} warm-up frames, then each scene's animation played ({}; "
            "frames = {}), {} repetition(s) in fresh GL {}s, {} frame mode; shadow maps {} {}² "
            "(r = {}) unless a method's `shadow` parameter says otherwise",
            x.protocol.warmup,
            x.protocol.step > 0.0 ? fmt::format("{} s per frame", x.protocol.step)
                                  : std::string("at its own fps; a scene without one orbits"),
            x.protocol.frames == 0 ? std::string("all") : std::to_string(x.protocol.frames),
            x.protocol.repetitions,
            x.protocol.isolation == Isolation::process ? "process" : "context",
            x.protocol.pipelined ? "pipelined" : "serial", x.render.shadow,
            x.render.shadow_map_size, x.render.pcf_radius);
    }
    return fmt::format(
        "{} warm-up and {} measured frames per repetition, {} repetition(s) in fresh GL {}s; "
        "shadow maps {} {}² (r = {}) unless a method's `shadow` parameter says otherwise",
        x.protocol.warmup, x.protocol.frames, x.protocol.repetitions,
        x.protocol.isolation == Isolation::process ? "process" : "context", x.render.shadow,
        x.render.shadow_map_size, x.render.pcf_radius);
}

// The equal-error report (markdown) and equal_error.csv from the rows at hand.
std::pair<std::string, std::string> equal_error_report(const Experiment& x,
                                                       const std::vector<StoredRow>& rows) {
    const std::vector<Entry> entries = aggregate(rows, "rel_rmse");
    const CellMeasure lookup = [&](const Cell& cell) -> std::optional<CellSummary> {
        for (const Entry& e : entries) {
            if (e.cell == cell && e.error) {
                return CellSummary{*e.error, e.frame_ms, e.volume_ms};
            }
        }
        return std::nullopt;
    };
    // The entry of a cell, for its frame-time interval.
    auto entry_of = [&](const Cell& cell) -> const Entry* {
        for (const Entry& e : entries) {
            if (e.cell == cell) {
                return &e;
            }
        }
        return nullptr;
    };
    auto probed_cell = [](const SearchOutcome& o) {
        return o.parameter.empty() ? o.group : with_setting(o.group, o.parameter, o.value);
    };
    // `none` renders no medium: it is the frame every other frame's volume cost is measured
    // against (the difference), not a column.
    std::vector<std::string> shown;
    for (const std::string& method : x.methods) {
        if (method != "none") {
            shown.push_back(method);
        }
    }
    const std::string& plain = x.equal_error->plain;
    // The volume cost by difference: an outcome's frame time less that of `none`, with an
    // interval. Paired cells (harness.md, "Paired") give the median of their per-pair differences
    // and its bootstrap interval; otherwise the difference of the two cells' medians, with the
    // interval from their two intervals (which does not hold the drift between the cells).
    // nullopt without `none` (or pairs).
    struct Difference {
        double ms;
        std::optional<Interval> interval;
        bool paired = false;
    };
    auto none_entry = [&](const std::string& scene, int w, int h) -> const Entry* {
        for (const Entry& e : entries) {
            if (e.cell.method == "none" && e.cell.scene == scene && e.cell.width == w &&
                e.cell.height == h) {
                return &e;
            }
        }
        return nullptr;
    };
    // `none`'s shadow-map pass (with a VSM's blur), the median over its repetitions.
    auto none_shadow_ms = [](const Entry& none) {
        std::vector<double> values;
        for (const StoredRow* r : none.rows) {
            values.push_back(r->row.value("gpu_ms_shadow", 0.0));
        }
        return median(values);
    };
    auto difference_of = [&](const SearchOutcome& o) -> std::optional<Difference> {
        const Entry* e = entry_of(probed_cell(o));
        if (e) {
            std::vector<std::vector<double>> pairs;
            std::vector<double> pooled;
            for (const StoredRow* r : e->rows) {
                const auto it = r->row.find("paired_difference_ms_samples");
                if (it == r->row.end() || !it->is_array()) {
                    pairs.clear();
                    break;
                }
                pairs.push_back(it->get<std::vector<double>>());
                pooled.insert(pooled.end(), pairs.back().begin(), pairs.back().end());
            }
            if (!pooled.empty()) {
                return Difference{median(pooled), median_interval(pairs), true};
            }
        }
        const Entry* none = none_entry(o.group.scene, o.group.width, o.group.height);
        if (!none || !e) {
            return std::nullopt;
        }
        Difference d{e->frame_ms - none->frame_ms, std::nullopt};
        if (e->has_interval && none->has_interval) {
            d.interval = Interval{e->frame_ms_interval.low - none->frame_ms_interval.high,
                                  e->frame_ms_interval.high - none->frame_ms_interval.low};
        }
        return d;
    };
    auto outside = [](double ms, const std::optional<Interval>& i) {
        return i && (ms < i->low || ms > i->high);
    };
    std::string csv =
        "target,scene,width,height,method,params,parameter,value,reached,complete,rel_rmse,"
        "frame_ms,fps,best_baseline,speedup_vs_best_baseline,volume_cost_ms,"
        "best_volume_baseline,volume_speedup_vs_best_baseline,volume_by_difference_ms,"
        "volume_by_difference_low,volume_by_difference_high,timer_and_difference_disagree,"
        "probes\n";
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
    const Cell* none_probe = nullptr;
    for (const Cell& cell : x.cells()) {
        if (cell.method == "none") {
            none_probe = &cell;
            break;
        }
    }
    if (none_probe) {
        md +=
            "\nThe volume cost is measured a second way too: the median frame time less that of "
            "`none` (no medium) in the same run, with the interval of the difference (from the "
            "two frame-time intervals). GPU timers are not to be trusted on every backend "
            "(llvmpipe books a pass's time in the wrong section when consecutive passes draw to "
            "one framebuffer); the difference holds on every backend, and the headline rests on "
            "it. Where the timer lies outside the difference's interval the row is flagged "
            "(\"Volume cost two ways\").\n";
    }

    const std::vector<Cell> groups = search_groups(x);
    std::vector<std::string> headlines, two_ways;
    for (const double target : x.equal_error->targets) {
        std::vector<SearchOutcome> outcomes;
        for (const Cell& group : groups) {
            outcomes.push_back(search_equal_error(x, group, target, lookup));
        }
        md += fmt::format("\n### Target: relative RMSE {:.3g}%\n\n", 100 * target);
        md += fmt::format("| scene | size | {} | baseline (frame · vol) |\n|---|---|",
                          fmt::join(shown, " | "));
        for (size_t i = 0; i < shown.size(); ++i) {
            md += "---:|";
        }
        md += "---|\n";
        std::map<std::tuple<std::string, int, int>, const SearchOutcome*> baselines,
            volume_baselines;
        for (const std::string& scene : x.scenes) {
            for (const auto& [w, h] : x.sizes) {
                // Each method's cheapest reached variant, by frame time and by volume cost.
                std::map<std::string, const SearchOutcome*> best, best_volume;
                for (const SearchOutcome& o : outcomes) {
                    if (o.group.scene != scene || o.group.width != w || o.group.height != h ||
                        !o.reached || !o.complete) {
                        continue;
                    }
                    const SearchOutcome*& b = best[o.group.method];
                    if (!b || o.summary.frame_ms < b->summary.frame_ms) {
                        b = &o;
                    }
                    const SearchOutcome*& v = best_volume[o.group.method];
                    if (!v || o.summary.volume_ms < v->summary.volume_ms) {
                        v = &o;
                    }
                }
                auto best_of = [&](std::map<std::string, const SearchOutcome*>& of, auto cost,
                                   bool baseline_methods) {
                    const SearchOutcome* found = nullptr;
                    const auto& names = x.equal_error->baselines;
                    for (const auto& [method, o] : of) {
                        const bool is_baseline =
                            std::find(names.begin(), names.end(), method) != names.end();
                        if (is_baseline == baseline_methods &&
                            (!found || cost(*o) < cost(*found))) {
                            found = o;
                        }
                    }
                    return found;
                };
                auto frame = [](const SearchOutcome& o) { return o.summary.frame_ms; };
                auto volume = [](const SearchOutcome& o) { return o.summary.volume_ms; };
                const SearchOutcome* baseline = best_of(best, frame, true);
                const SearchOutcome* baseline_volume = best_of(best_volume, volume, true);
                baselines[{scene, w, h}] = baseline;
                volume_baselines[{scene, w, h}] = baseline_volume;
                md += fmt::format("| {} | {}x{} |", scene_label(scene), w, h);
                for (const std::string& method : shown) {
                    if (!best.contains(method)) {
                        md += " not reached |";
                        continue;
                    }
                    const SearchOutcome& o = *best[method];
                    const SearchOutcome& v = *best_volume[method];
                    md += fmt::format(
                        " {}{:.1f} ms{} · vol {}{:.1f} ms{} |",
                        o.parameter.empty() ? "" : fmt::format("{}={}: ", o.parameter, o.value),
                        o.summary.frame_ms,
                        baseline ? fmt::format(" (×{:.2f})", frame(*baseline) / frame(o))
                                 : std::string(),
                        &v == &o ? "" : fmt::format("at {}={} ", v.parameter, v.value),
                        v.summary.volume_ms,
                        baseline_volume
                            ? fmt::format(" (×{:.2f})", volume(*baseline_volume) / volume(v))
                            : std::string());
                }
                md +=
                    fmt::format(" {} · {} |\n", baseline ? baseline->group.method : "none reached",
                                baseline_volume ? baseline_volume->group.method : "none reached");
                // The volume cost by difference; the cheapest variant by it is the cheapest by
                // frame time.
                auto difference_text = [&](const SearchOutcome& o) {
                    const Difference d = *difference_of(o);
                    return fmt::format("{:.1f} ms [{:.1f}–{:.1f}]", d.ms,
                                       d.interval ? d.interval->low : 0.0,
                                       d.interval ? d.interval->high : 0.0);
                };
                const Entry* none = none_entry(scene, w, h);
                if (none) {
                    for (const std::string& method : shown) {
                        if (!best.contains(method)) {
                            continue;
                        }
                        const SearchOutcome& o = *best[method];
                        const SearchOutcome& v = *best_volume[method];
                        // The timer's cheapest variant against the difference at the frame's.
                        const bool disagree =
                            &v == &o && outside(v.summary.volume_ms, difference_of(o)->interval);
                        two_ways.push_back(
                            fmt::format("| {:.3g}% | {} | {}x{} | {} | {} | {:.1f} ms | {} |{}",
                                        100 * target, scene_label(scene), w, h, method,
                                        probed_cell(o).settings_text(), o.summary.volume_ms,
                                        difference_text(o), disagree ? " **disagree** |" : " |"));
                    }
                }
                // The headline: the best region method (every method that is not a baseline)
                // against the best method without regions at this target, and against the plain
                // method; by the volume cost as the frame-time difference (where `none` ran), by
                // the frame time, and by the timers' volume cost.
                const SearchOutcome* hybrid = best_of(best, frame, false);
                const SearchOutcome* hybrid_volume = best_of(best_volume, volume, false);
                const SearchOutcome* plain_frame = best.contains(plain) ? best[plain] : nullptr;
                const SearchOutcome* plain_volume =
                    best_volume.contains(plain) ? best_volume[plain] : nullptr;
                // "×r against **m** c ms", and the plain method's the same way unless it is the
                // baseline itself; a cost at or below zero (a difference within the noise of
                // `none`) has no ratio.
                auto against = [&](const SearchOutcome* other, const SearchOutcome& ours,
                                   auto cost) -> std::string {
                    if (!other) {
                        return "no plain method";
                    }
                    if (!(cost(ours) > 0.0) || !(cost(*other) > 0.0)) {
                        return fmt::format(
                            "against **{}** {:.1f} ms: no ratio (a cost at or "
                            "below zero)",
                            other->group.method, cost(*other));
                    }
                    return fmt::format("×{:.2f} against **{}** {:.1f} ms",
                                       cost(*other) / cost(ours), other->group.method,
                                       cost(*other));
                };
                // The frame-time ratio is a tie where the two medians' intervals overlap.
                auto overlapping = [&](const SearchOutcome* other,
                                       const SearchOutcome& ours) -> std::string {
                    const Entry* a = other ? entry_of(probed_cell(*other)) : nullptr;
                    const Entry* b = entry_of(probed_cell(ours));
                    if (!a || !b || !a->has_interval || !b->has_interval ||
                        !a->frame_ms_interval.overlaps(b->frame_ms_interval)) {
                        return "";
                    }
                    return " (not resolved: the frame times' intervals overlap)";
                };
                auto and_plain = [&](const SearchOutcome* base, const SearchOutcome* other,
                                     const SearchOutcome& ours, auto cost) -> std::string {
                    if (other && base && other->group.method == base->group.method) {
                        return fmt::format(" ({} is the plain method)", other->group.method);
                    }
                    return "; " + against(other, ours, cost);
                };
                // By difference, a ratio only where it is resolved: both differences' intervals
                // above zero and each within reach of its timer's volume cost (the two measures
                // agree); "not resolved" and why otherwise.
                auto unresolved = [&](const SearchOutcome& o) -> std::string {
                    const std::optional<Difference> d = difference_of(o);
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
                };
                auto against_by_difference = [&](const SearchOutcome* other,
                                                 const SearchOutcome& ours) -> std::string {
                    if (!other) {
                        return "no plain method";
                    }
                    for (const SearchOutcome* o : {&ours, other}) {
                        if (const std::string why = unresolved(*o); !why.empty()) {
                            return fmt::format("against **{}** {}: not resolved ({})",
                                               other->group.method, difference_text(*other), why);
                        }
                    }
                    return fmt::format("×{:.2f} against **{}** {}",
                                       difference_of(*other)->ms / difference_of(ours)->ms,
                                       other->group.method, difference_text(*other));
                };
                if (hybrid && baseline && hybrid_volume && baseline_volume) {
                    std::string line = fmt::format("- {:.3g}% on {} {}x{}:", 100 * target,
                                                   scene_label(scene), w, h);
                    if (none) {
                        const bool plain_is_baseline =
                            plain_frame && plain_frame->group.method == baseline->group.method;
                        line += fmt::format(
                            " volume cost (frame − none{}) **{}** {}: {}{}.",
                            difference_of(*hybrid)->paired ? ", paired" : "", hybrid->group.method,
                            difference_text(*hybrid), against_by_difference(baseline, *hybrid),
                            plain_is_baseline ? fmt::format(" ({} is the plain method)",
                                                            plain_frame->group.method)
                                              : "; " + against_by_difference(plain_frame, *hybrid));
                        // What every frame of the protocol pays whatever the method: `none`'s
                        // passes, the shadow map (and a VSM's blur) first.
                        line += fmt::format(
                            " (Fixed passes: `none`'s frame {:.1f} ms, its "
                            "shadow map {:.1f} ms.)",
                            none->frame_ms, none_shadow_ms(*none));
                    }
                    line += fmt::format(
                        " Frame **{}** {:.1f} ms: {}{}. Volume cost by timers **{}** {:.1f} "
                        "ms: {}{}.",
                        hybrid->group.method, frame(*hybrid),
                        against(baseline, *hybrid, frame) + overlapping(baseline, *hybrid),
                        and_plain(baseline, plain_frame, *hybrid, frame) +
                            (plain_frame && plain_frame->group.method != baseline->group.method
                                 ? overlapping(plain_frame, *hybrid)
                                 : std::string()),
                        hybrid_volume->group.method, volume(*hybrid_volume),
                        against(baseline_volume, *hybrid_volume, volume),
                        and_plain(baseline_volume, plain_volume, *hybrid_volume, volume));
                    headlines.push_back(line);
                }
            }
        }
        // The CSV's volume cost by difference: value, interval, and the flag.
        auto difference_fields = [&](const SearchOutcome& o) -> std::string {
            const std::optional<Difference> d =
                o.complete && o.reached ? difference_of(o) : std::nullopt;
            if (!d || !d->interval) {
                return ",,,";
            }
            return fmt::format("{},{},{},{}", d->ms, d->interval->low, d->interval->high,
                               outside(o.summary.volume_ms, d->interval) ? 1 : 0);
        };
        for (const SearchOutcome& o : outcomes) {
            const auto key = std::tuple{o.group.scene, o.group.width, o.group.height};
            const SearchOutcome* baseline = baselines[key];
            const SearchOutcome* volume_baseline = volume_baselines[key];
            const bool measured = o.complete && (o.reached || !o.value.empty());
            csv += fmt::format(
                "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", target,
                csv_field(o.group.scene), o.group.width, o.group.height, o.group.method,
                csv_field(o.group.settings_text()), o.parameter, o.value, o.reached ? 1 : 0,
                o.complete ? 1 : 0, measured ? fmt::format("{}", o.summary.rel_rmse) : "",
                measured ? fmt::format("{}", o.summary.frame_ms) : "",
                measured ? fmt::format("{}", 1000.0 / o.summary.frame_ms) : "",
                baseline ? baseline->group.method : "",
                baseline && o.reached
                    ? fmt::format("{}", baseline->summary.frame_ms / o.summary.frame_ms)
                    : "",
                measured ? fmt::format("{}", o.summary.volume_ms) : "",
                volume_baseline ? volume_baseline->group.method : "",
                volume_baseline && o.reached
                    ? fmt::format("{}", volume_baseline->summary.volume_ms / o.summary.volume_ms)
                    : "",
                difference_fields(o), o.probes.size());
        }
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
        md += fmt::format(
            "\n### Headline: the best region method against the best method without regions "
            "({}) and against {}, at equal error\n\n{}\n",
            fmt::join(x.equal_error->baselines, ", "), plain.empty() ? "none" : plain,
            fmt::join(headlines, "\n"));
    }
    return {md, csv};
}

// Per scene and size: the beam tree and how the view's eye rays cross its regions.
std::string regions_table(const std::vector<StoredRow>& rows) {
    std::string md =
        "Eye-ray fraction: of the eye-ray length inside the light's cone and range, in front of "
        "the first surface, the share in each region type. Volume fraction: of the influence "
        "volume. Lit crossings: per pixel, twice the maximal lit intervals along the whole eye "
        "ray (the fewest fragments an analytic pass without a depth test draws) and up to the "
        "first surface. Uncertain span: the length from the first uncertain entry to "
        "the last exit over the uncertain length (what one spanning interval per pixel "
        "marches).\n\n"
        "| scene | size | beams | region faces | eye-ray fraction lit / uncertain / unlit | "
        "volume fraction lit / uncertain / unlit | lit crossings / px (ray / visible) | "
        "uncertain span | tree + regions ms |\n"
        "|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
    std::set<std::pair<std::string, std::string>> done;
    for (const StoredRow& r : rows) {
        if (!done.insert({r.cell.scene, r.cell.size()}).second) {
            continue;
        }
        const Json& v = r.row;
        md += fmt::format(
            "| {} | {} | {} | {} | {:.1f}% / {:.1f}% / {:.1f}% | {:.1f}% / {:.1f}% / {:.1f}% | "
            "{:.2f} / {:.2f} | {:.2f}x | {:.1f} |\n",
            scene_label(r.cell.scene), r.cell.size(), v.value("beams", 0),
            v.value("region_faces", 0), 100 * v.value("ray_frac_lit", 0.0),
            100 * v.value("ray_frac_uncertain", 0.0), 100 * v.value("ray_frac_unlit", 0.0),
            100 * v.value("volume_frac_lit", 0.0), 100 * v.value("volume_frac_uncertain", 0.0),
            100 * v.value("volume_frac_unlit", 0.0), v.value("lit_crossings", 0.0),
            v.value("lit_crossings_visible", 0.0), v.value("uncertain_span_ratio", 0.0),
            v.value("cpu_ms_beamtree_regions", 0.0));
    }
    return md;
}

// Per method, scene and size with an analytic pass: the fragments it draws per pixel against the
// fewest it could (the lit crossings of the regions table). Two counts: what the rasterizer
// shaded (`stat_fragments_analytic`, fragment-shader invocations: llvmpipe counts every 4×4
// block a triangle touches in full, so small triangles cost more than they cover) and what it
// rasterized (`stat_fragments_rasterized`, samples passed: the (pixel, face) pairs themselves).
std::string fragments_table(const std::vector<StoredRow>& rows) {
    std::string md;
    std::set<std::tuple<std::string, std::string, std::string>> done;
    auto ratio = [](double value, double minimum) {
        return minimum > 0.0 ? fmt::format("{:.2f}x", value / minimum) : std::string();
    };
    for (const StoredRow& r : rows) {
        const Json& v = r.row;
        // One row per variant: a method's parameters can change what it draws (beamtree's
        // surfaces).
        const std::string settings = r.cell.settings_text();
        const std::string method =
            settings.empty() ? r.cell.method : r.cell.method + " " + settings;
        if (!v.contains("stat_fragments_analytic") || !v["stat_fragments_analytic"].is_number() ||
            !done.insert({method, r.cell.scene, r.cell.size()}).second) {
            continue;
        }
        const double pixels = v.value("width", 1.0) * v.value("height", 1.0);
        const double shaded = v["stat_fragments_analytic"].get<double>() / pixels;
        const bool counted =
            v.contains("stat_fragments_rasterized") && v["stat_fragments_rasterized"].is_number();
        const double rasterized =
            counted ? v["stat_fragments_rasterized"].get<double>() / pixels : std::nan("");
        const double minimum = v.value("lit_crossings", 0.0);
        md += fmt::format("| {} | {} | {} | {:.2f} | {} | {:.2f} | {} | {} |\n", method,
                          scene_label(r.cell.scene), r.cell.size(), shaded,
                          counted ? fmt::format("{:.2f}", rasterized) : "", minimum,
                          ratio(shaded, minimum), counted ? ratio(rasterized, minimum) : "");
    }
    if (md.empty()) {
        return md;
    }
    return "\n## Analytic-pass fragments\n\nPer pixel of the image: the fragments the analytic "
           "pass shades (`stat_fragments_analytic`, fragment-shader invocations; llvmpipe counts "
           "each 4×4 block a triangle touches in full), the fragments it rasterizes "
           "(`stat_fragments_rasterized`, samples passed), the fewest it could (lit crossings per "
           "pixel along the whole eye ray, regions table), and each count over that minimum.\n\n"
           "| method | scene | size | shaded / px | rasterized / px | minimum / px | shaded ratio "
           "| rasterized ratio |\n"
           "|---|---|---|---:|---:|---:|---:|---:|\n" +
           md;
}

// Animation cells (docs/design.md §11): per cell, over its repetitions, the frame time's median
// with its interval, p95 and worst frame, the CPU update and what of it the frame waited for, the
// error per frame (median, p95, worst) and the temporal metrics (core/temporal_metrics.h).
std::string animation_table(const Experiment& x, const std::vector<Entry>& entries) {
    // The fastest cell of each scene (and size), marked only when significant.
    std::map<std::pair<std::string, std::string>, std::vector<const Entry*>> by_view;
    for (const Entry& e : entries) {
        by_view[{e.cell.scene, e.cell.size()}].push_back(&e);
    }
    std::set<const Entry*> fastest;
    for (const auto& [view, cells] : by_view) {
        if (const Entry* f = significant_fastest(cells)) {
            fastest.insert(f);
        }
    }
    std::string md;
    for (const Entry& e : entries) {
        if (e.rows.empty() || !e.rows.front()->row.contains("per_frame")) {
            continue;
        }
        // The CPU update per frame, pooled over the repetitions, with its interval.
        std::vector<std::vector<double>> updates;
        for (const StoredRow* r : e.rows) {
            std::vector<double> u;
            for (const Json& v : r->row["per_frame"].value("update_ms", Json::array())) {
                u.push_back(v.get<double>());
            }
            updates.push_back(std::move(u));
        }
        std::vector<double> pooled_updates;
        for (const auto& u : updates) {
            pooled_updates.insert(pooled_updates.end(), u.begin(), u.end());
        }
        const Interval update_interval = median_interval(updates);
        auto over_reps = [&](const char* key) -> std::optional<double> {
            std::vector<double> values;
            for (const StoredRow* r : e.rows) {
                if (r->row.contains(key) && r->row[key].is_number()) {
                    values.push_back(r->row[key].get<double>());
                }
            }
            if (values.empty()) {
                return std::nullopt;
            }
            return median(values);
        };
        auto worst = [&](const char* key, const char* frame_key) -> std::string {
            const StoredRow* at = nullptr;
            for (const StoredRow* r : e.rows) {
                if (r->row.contains(key) && r->row[key].is_number() &&
                    (!at || r->row[key].get<double>() > at->row[key].get<double>())) {
                    at = r;
                }
            }
            if (!at) {
                return "–";
            }
            const double v = at->row[key].get<double>();
            return fmt::format("{} (#{})",
                               std::string(key).find("rel_rmse") != std::string::npos
                                   ? format_error("rel_rmse", v)
                                   : fmt::format("{:.1f}", v),
                               at->row.value(frame_key, -1));
        };
        auto percent = [&](const char* key) {
            const auto v = over_reps(key);
            return v ? fmt::format("{:.3f}%", 100.0 * *v) : std::string("–");
        };
        const auto pops = over_reps("pops");
        const std::string frame_ms = fmt::format("{:.1f} [{:.1f}–{:.1f}]", e.frame_ms,
                                                 e.frame_ms_interval.low, e.frame_ms_interval.high);
        md += fmt::format(
            "| {} | {} | {} | {} | {:.1f} | {} | {:.1f} [{:.1f}–{:.1f}] / {:.2f} | {} | {} | {} "
            "| {} | {} | {} |\n",
            scene_label(e.cell.scene), e.cell.method, e.cell.settings_text(),
            fastest.contains(&e) ? "**" + frame_ms + "**" : frame_ms,
            over_reps("frame_ms_p95").value_or(0.0), worst("frame_ms_worst", "frame_worst"),
            median(pooled_updates), update_interval.low, update_interval.high,
            over_reps("cpu_ms_critical").value_or(0.0), percent("rel_rmse"),
            percent("rel_rmse_p95"), worst("rel_rmse_worst", "error_worst_frame"),
            percent("temporal_error"), percent("flicker"), pops ? fmt::format("{:g}", *pops) : "–");
    }
    if (md.empty()) {
        return md;
    }
    // What each scene played (its animation, or an orbit of a still scene).
    std::vector<std::string> played;
    const StoredRow* any = nullptr;
    for (const Entry& e : entries) {
        if (e.rows.empty() || !e.rows.front()->row.contains("per_frame")) {
            continue;
        }
        any = e.rows.front();
        const std::string text = fmt::format("{}: {}", scene_label(e.cell.scene),
                                             any->row.value("sequence", std::string("?")));
        if (rank(played, text) == played.size()) {
            played.push_back(text);
        }
    }
    return fmt::format(
               "\n## Along the animation\n\nEach cell played its scene ({}; {} frame mode), every "
               "frame "
               "measured; the error scored on every {} frame(s) against the reference of that "
               "frame. Frame ms: median over every frame of every repetition, with its 95% "
               "bootstrap interval (in bold the scene's fastest, when its interval does not "
               "overlap the next one's), the 95th percentile, and the slowest frame (#index). "
               "CPU: the median update (beam tree, regions, meshes, partitions) with its interval, "
               "and the part of it the frame waited for (the critical path; pipelined, the rest "
               "ran beside the draw). "
               "Error: relative RMSE of I_s per scored frame, median, p95 and worst (#frame). "
               "Temporal error, flicker and popping as defined in docs/harness.md (pops: frames "
               "above "
               "{}× the median error and {} above it).\n\n"
               "| scene | method | params | frame ms [95% CI] | p95 | worst | CPU update / "
               "critical ms | error median | p95 | worst | temporal error | flicker | pops |\n"
               "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
               fmt::join(played, "; "), any->row.value("frame_mode", std::string("serial")),
               any->row.value("stride", 1), x.scoring.pop_factor,
               format_error("rel_rmse", x.scoring.pop_floor)) +
           md;
}

// The equal-error search's probes, one row each: the cell, its frame time with its interval,
// its volume cost and its error.
std::string probes_table(const Experiment& x, const std::vector<StoredRow>& rows) {
    const std::vector<Entry> entries = aggregate(rows, x.table_metric);
    std::string md =
        "| scene | size | method | params | frame ms [95% CI] | FPS | volume cost ms | error |\n"
        "|---|---|---|---|---:|---:|---:|---:|\n";
    for (const Entry& e : entries) {
        md += fmt::format(
            "| {} | {} | {} | {} | {:.2f}{} | {:.3g} | {:.2f} | {} |\n", scene_label(e.cell.scene),
            e.cell.size(), e.cell.method, e.cell.settings_text(), e.frame_ms,
            e.has_interval
                ? fmt::format(" [{:.2f}–{:.2f}]", e.frame_ms_interval.low, e.frame_ms_interval.high)
                : std::string(),
            1000.0 / e.frame_ms, e.volume_ms,
            e.error ? format_error(x.table_metric, *e.error) : "–");
    }
    return md;
}

std::string sweep_table(const Experiment& x, const std::vector<StoredRow>& rows) {
    const std::vector<Entry> entries = aggregate(rows, x.table_metric);
    if (entries.empty()) {
        return "No cells measured.\n";
    }
    // Row dimensions: the configured ones that some cell has (scene and size always).
    auto value_of = [](const Cell& cell, const std::string& dim) -> std::optional<std::string> {
        if (dim == "scene") {
            return cell.scene;
        }
        if (dim == "size") {
            return cell.size();
        }
        if (const std::string* v = cell.setting(dim)) {
            return *v;
        }
        return std::nullopt;
    };
    std::vector<std::string> dims;
    for (const std::string& dim : x.table_rows) {
        if (std::any_of(entries.begin(), entries.end(),
                        [&](const Entry& e) { return value_of(e.cell, dim).has_value(); })) {
            dims.push_back(dim);
        }
    }
    for (const char* always : {"scene", "size"}) {
        if (rank(dims, std::string(always)) == dims.size()) {
            dims.push_back(always);
        }
    }
    // Columns: the method, plus its parameters that vary and are not row dimensions.
    std::map<std::string, std::set<std::string>> varying;  // method → parameter names
    {
        std::map<std::pair<std::string, std::string>, std::set<std::string>> values;
        for (const Entry& e : entries) {
            for (const Setting& s : e.cell.settings) {
                values[{e.cell.method, s.name}].insert(s.value);
            }
        }
        for (const auto& [key, set] : values) {
            if (set.size() > 1 && rank(dims, key.second) == dims.size()) {
                varying[key.first].insert(key.second);
            }
        }
    }
    auto column_of = [&](const Cell& cell) {
        std::string label = cell.method;
        for (const Setting& s : cell.settings) {
            if (varying[cell.method].contains(s.name)) {
                label += " " + s.name + "=" + s.value;
            }
        }
        return label;
    };
    std::vector<std::string> columns;
    for (const std::string& method : x.methods) {
        for (const Entry& e : entries) {
            if (e.cell.method == method && rank(columns, column_of(e.cell)) == columns.size()) {
                columns.push_back(column_of(e.cell));
            }
        }
    }
    // Rows: distinct values of the dimensions among the cells that have them all; a cell that
    // lacks a dimension (beamtree has no dz) appears in every row agreeing on the rest.
    std::vector<std::vector<std::string>> table_rows;
    for (const Entry& e : entries) {
        std::vector<std::string> key;
        for (const std::string& dim : dims) {
            if (const auto v = value_of(e.cell, dim)) {
                key.push_back(*v);
            }
        }
        if (key.size() == dims.size() && rank(table_rows, key) == table_rows.size()) {
            table_rows.push_back(key);
        }
    }
    if (table_rows.empty()) {  // no cell has every dimension: scene × size only
        std::erase_if(dims, [](const std::string& d) { return d != "scene" && d != "size"; });
        return sweep_table(
            [&] {
                Experiment y = x;
                y.table_rows = dims;
                return y;
            }(),
            rows);
    }
    std::vector<std::vector<std::string>> order(dims.size());  // first-seen order per dimension
    for (const auto& key : table_rows) {
        for (size_t d = 0; d < dims.size(); ++d) {
            if (rank(order[d], key[d]) == order[d].size()) {
                order[d].push_back(key[d]);
            }
        }
    }
    auto dim_rank = [&](size_t d, const std::string& v) {
        if (dims[d] == "scene") {
            return rank(x.scenes, v);
        }
        if (dims[d] == "size") {
            for (size_t i = 0; i < x.sizes.size(); ++i) {
                if (fmt::format("{}x{}", x.sizes[i].first, x.sizes[i].second) == v) {
                    return i;
                }
            }
        }
        // Parameters in the order the file lists them (Nilsson's dz 0.5 before 0.1).
        const std::vector<std::string> listed = x.listed_values(dims[d]);
        for (size_t i = 0; i < listed.size(); ++i) {
            if (same_value(listed[i], v)) {
                return i;
            }
        }
        return listed.size() + rank(order[d], v);
    };
    std::stable_sort(table_rows.begin(), table_rows.end(), [&](const auto& a, const auto& b) {
        for (size_t d = 0; d < dims.size(); ++d) {
            if (dim_rank(d, a[d]) != dim_rank(d, b[d])) {
                return dim_rank(d, a[d]) < dim_rank(d, b[d]);
            }
        }
        return false;
    });

    std::string md =
        fmt::format("| {} | {} |\n", fmt::join(dims, " | "), fmt::join(columns, " | "));
    for (size_t d = 0; d < dims.size(); ++d) {
        md += "|---";
    }
    for (size_t c = 0; c < columns.size(); ++c) {
        md += "|---:";
    }
    md += "|\n";
    for (const auto& key : table_rows) {
        std::vector<const Entry*> cells(columns.size(), nullptr);
        for (const Entry& e : entries) {
            bool match = true;
            for (size_t d = 0; d < dims.size(); ++d) {
                const auto v = value_of(e.cell, dims[d]);
                match = match && (!v || *v == key[d]);
            }
            const size_t c = rank(columns, column_of(e.cell));
            if (match && !cells[c]) {
                cells[c] = &e;
            }
        }
        const Entry* fastest = significant_fastest(cells);
        std::vector<std::string> shown = key;
        for (size_t d = 0; d < dims.size(); ++d) {
            if (dims[d] == "scene") {
                shown[d] = scene_label(shown[d]);
            }
        }
        md += fmt::format("| {} |", fmt::join(shown, " | "));
        for (const Entry* e : cells) {
            if (!e) {
                md += " – |";
                continue;
            }
            const std::string fps = fps_text(*e);
            md += fmt::format(" {}{} |", e == fastest ? "**" + fps + "**" : fps,
                              e->error ? " (" + format_error(x.table_metric, *e->error) + ")" : "");
        }
        md += "\n";
    }
    return md;
}

}  // namespace sl::experiments
