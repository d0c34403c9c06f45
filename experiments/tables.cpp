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

// Per scene and size: the beam tree and how the view's eye rays cross its regions.
std::string regions_table(const std::vector<StoredRow>& rows) {
    std::string md =
        "Eye-ray fraction: of the eye-ray length inside the light's cone and range, in front of "
        "the first surface, the share in each region type. Volume fraction: of the influence "
        "volume. Lit crossings: per pixel, twice the maximal lit intervals along the whole eye "
        "ray (the fewest fragments an analytic pass without a depth test draws) and up to the "
        "first surface. Uncertain span: the length from the first uncertain entry to "
        "the last exit over the uncertain length (what one spanning interval per pixel "
        "marches; none where less than 10^-6 of the length is uncertain).\n\n"
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
        if (v.contains("regions_unavailable")) {
            // No statistics (the light inside a volume, or several lights, each its own tree):
            // why, instead of zeros.
            md += fmt::format("| {} | {} | {} |  |  |  |  |  |  |\n", scene_label(r.cell.scene),
                              r.cell.size(), v.value("regions_unavailable", std::string()));
            continue;
        }
        md += fmt::format(
            "| {} | {} | {} | {} | {:.1f}% / {:.1f}% / {:.1f}% | {:.1f}% / {:.1f}% / {:.1f}% | "
            "{:.2f} / {:.2f} | {} | {:.1f} |\n",
            scene_label(r.cell.scene), r.cell.size(), v.value("beams", 0),
            v.value("region_faces", 0), 100 * v.value("ray_frac_lit", 0.0),
            100 * v.value("ray_frac_uncertain", 0.0), 100 * v.value("ray_frac_unlit", 0.0),
            100 * v.value("volume_frac_lit", 0.0), 100 * v.value("volume_frac_uncertain", 0.0),
            100 * v.value("volume_frac_unlit", 0.0), v.value("lit_crossings", 0.0),
            v.value("lit_crossings_visible", 0.0),
            v.value("uncertain_span_ratio", 0.0) > 0.0
                ? fmt::format("{:.2f}x", v.value("uncertain_span_ratio", 0.0))
                : std::string("none"),
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

namespace {

bool is_animation(const Entry& e) {
    return !e.rows.empty() && e.rows.front()->row.contains("per_frame");
}

// The cells of each scene (and size) whose frame time is significantly the fastest.
std::set<const Entry*> fastest_per_view(const std::vector<Entry>& entries) {
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
    return fastest;
}

// A column of an animation cell over its repetitions: the median, and the worst with the
// frame it came from.
class OverRepetitions {
public:
    explicit OverRepetitions(const Entry& e) : e_(e) {}

    std::optional<double> median_of(const char* key) const {
        std::vector<double> values;
        for (const StoredRow* r : e_.rows) {
            if (r->row.contains(key) && r->row[key].is_number()) {
                values.push_back(r->row[key].get<double>());
            }
        }
        if (values.empty()) {
            return std::nullopt;
        }
        return median(values);
    }
    std::string worst(const char* key, const char* frame_key) const {
        const StoredRow* at = nullptr;
        for (const StoredRow* r : e_.rows) {
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
    }
    std::string percent(const char* key) const {
        const auto v = median_of(key);
        return v ? fmt::format("{:.3f}%", 100.0 * *v) : std::string("–");
    }

private:
    const Entry& e_;
};

// One animation cell's row.
std::string animation_row(const Entry& e, bool fastest) {
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
    const OverRepetitions reps(e);
    const auto pops = reps.median_of("pops");
    const std::string frame_ms = fmt::format("{:.1f} [{:.1f}–{:.1f}]", e.frame_ms,
                                             e.frame_ms_interval.low, e.frame_ms_interval.high);
    return fmt::format(
        "| {} | {} | {} | {} | {:.1f} | {} | {:.1f} [{:.1f}–{:.1f}] / {:.2f} | {} | {} | {} "
        "| {} | {} | {} |\n",
        scene_label(e.cell.scene), e.cell.method, e.cell.settings_text(),
        fastest ? "**" + frame_ms + "**" : frame_ms, reps.median_of("frame_ms_p95").value_or(0.0),
        reps.worst("frame_ms_worst", "frame_worst"), median(pooled_updates), update_interval.low,
        update_interval.high, reps.median_of("cpu_ms_critical").value_or(0.0),
        reps.percent("rel_rmse"), reps.percent("rel_rmse_p95"),
        reps.worst("rel_rmse_worst", "error_worst_frame"), reps.percent("temporal_error"),
        reps.percent("flicker"), pops ? fmt::format("{:g}", *pops) : "–");
}

}  // namespace

// Animation cells (docs/design.md §11): per cell, over its repetitions, the frame time's median
// with its interval, p95 and worst frame, the CPU update and what of it the frame waited for, the
// error per frame (median, p95, worst) and the temporal metrics (core/temporal_metrics.h).
std::string animation_table(const Experiment& x, const std::vector<Entry>& entries) {
    const std::set<const Entry*> fastest = fastest_per_view(entries);
    std::string md;
    // What each scene played (its animation, or an orbit of a still scene).
    std::vector<std::string> played;
    const StoredRow* any = nullptr;
    for (const Entry& e : entries) {
        if (!is_animation(e)) {
            continue;
        }
        md += animation_row(e, fastest.contains(&e));
        any = e.rows.front();
        const std::string text = fmt::format("{}: {}", scene_label(e.cell.scene),
                                             any->row.value("sequence", std::string("?")));
        if (rank(played, text) == played.size()) {
            played.push_back(text);
        }
    }
    if (md.empty()) {
        return md;
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

namespace {

// A cell's value along a row dimension of a sweep table; nullopt where the cell lacks it.
std::optional<std::string> dimension_value(const Cell& cell, const std::string& dim) {
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
}

// What a sweep table shows, before it is formatted: its row dimensions, its columns (a method
// with the parameters that vary and are not rows), and the rows' keys in display order.
struct SweepLayout {
    std::vector<std::string> dims;
    std::map<std::string, std::set<std::string>> varying;  // method → column parameters
    std::vector<std::string> columns;
    std::vector<std::vector<std::string>> rows;

    std::string column_of(const Cell& cell) const {
        std::string label = cell.method;
        const auto it = varying.find(cell.method);
        for (const Setting& s : cell.settings) {
            if (it != varying.end() && it->second.contains(s.name)) {
                label += " " + s.name + "=" + s.value;
            }
        }
        return label;
    }
};

// Row dimensions: the configured ones that some cell has, then scene and size (always).
std::vector<std::string> row_dimensions(const Experiment& x, const std::vector<Entry>& entries) {
    std::vector<std::string> dims;
    for (const std::string& dim : x.table_rows) {
        if (std::any_of(entries.begin(), entries.end(),
                        [&](const Entry& e) { return dimension_value(e.cell, dim).has_value(); })) {
            dims.push_back(dim);
        }
    }
    for (const char* always : {"scene", "size"}) {
        if (rank(dims, std::string(always)) == dims.size()) {
            dims.push_back(always);
        }
    }
    return dims;
}

// Per method, its parameters that take more than one value and are not row dimensions.
std::map<std::string, std::set<std::string>> varying_parameters(
    const std::vector<Entry>& entries, const std::vector<std::string>& dims) {
    std::map<std::pair<std::string, std::string>, std::set<std::string>> values;
    for (const Entry& e : entries) {
        for (const Setting& s : e.cell.settings) {
            values[{e.cell.method, s.name}].insert(s.value);
        }
    }
    std::map<std::string, std::set<std::string>> varying;
    for (const auto& [key, set] : values) {
        if (set.size() > 1 && rank(dims, key.second) == dims.size()) {
            varying[key.first].insert(key.second);
        }
    }
    return varying;
}

// Rows: distinct values of the dimensions among the cells that have them all; a cell that lacks
// a dimension (beamtree has no dz) appears in every row agreeing on the rest.
std::vector<std::vector<std::string>> row_keys(const std::vector<Entry>& entries,
                                               const std::vector<std::string>& dims) {
    std::vector<std::vector<std::string>> keys;
    for (const Entry& e : entries) {
        std::vector<std::string> key;
        for (const std::string& dim : dims) {
            if (const auto v = dimension_value(e.cell, dim)) {
                key.push_back(*v);
            }
        }
        if (key.size() == dims.size() && rank(keys, key) == keys.size()) {
            keys.push_back(key);
        }
    }
    return keys;
}

// Scenes and sizes in the experiment's order, parameters in the order the file lists them
// (Nilsson's dz 0.5 before 0.1), anything else as first seen.
void sort_rows(const Experiment& x, const std::vector<std::string>& dims,
               std::vector<std::vector<std::string>>& keys) {
    std::vector<std::vector<std::string>> seen(dims.size());
    for (const auto& key : keys) {
        for (size_t d = 0; d < dims.size(); ++d) {
            if (rank(seen[d], key[d]) == seen[d].size()) {
                seen[d].push_back(key[d]);
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
        const std::vector<std::string> listed = x.listed_values(dims[d]);
        for (size_t i = 0; i < listed.size(); ++i) {
            if (same_value(listed[i], v)) {
                return i;
            }
        }
        return listed.size() + rank(seen[d], v);
    };
    std::stable_sort(keys.begin(), keys.end(), [&](const auto& a, const auto& b) {
        for (size_t d = 0; d < dims.size(); ++d) {
            if (dim_rank(d, a[d]) != dim_rank(d, b[d])) {
                return dim_rank(d, a[d]) < dim_rank(d, b[d]);
            }
        }
        return false;
    });
}

SweepLayout sweep_layout(const Experiment& x, const std::vector<Entry>& entries) {
    SweepLayout layout;
    layout.dims = row_dimensions(x, entries);
    layout.varying = varying_parameters(entries, layout.dims);
    for (const std::string& method : x.methods) {
        for (const Entry& e : entries) {
            const std::string column = layout.column_of(e.cell);
            if (e.cell.method == method && rank(layout.columns, column) == layout.columns.size()) {
                layout.columns.push_back(column);
            }
        }
    }
    layout.rows = row_keys(entries, layout.dims);
    if (layout.rows.empty()) {  // no cell has every dimension: scene × size only
        Experiment y = x;
        y.table_rows = layout.dims;
        std::erase_if(y.table_rows,
                      [](const std::string& d) { return d != "scene" && d != "size"; });
        return sweep_layout(y, entries);
    }
    sort_rows(x, layout.dims, layout.rows);
    return layout;
}

// One row: per column, the first cell agreeing with the key (on the dimensions it has), its FPS
// with the error, the fastest in bold where it is significantly so.
std::string sweep_row(const Experiment& x, const SweepLayout& layout,
                      const std::vector<Entry>& entries, const std::vector<std::string>& key) {
    std::vector<const Entry*> cells(layout.columns.size(), nullptr);
    for (const Entry& e : entries) {
        bool match = true;
        for (size_t d = 0; d < layout.dims.size(); ++d) {
            const auto v = dimension_value(e.cell, layout.dims[d]);
            match = match && (!v || *v == key[d]);
        }
        const size_t c = rank(layout.columns, layout.column_of(e.cell));
        if (match && !cells[c]) {
            cells[c] = &e;
        }
    }
    const Entry* fastest = significant_fastest(cells);
    std::vector<std::string> shown = key;
    for (size_t d = 0; d < layout.dims.size(); ++d) {
        if (layout.dims[d] == "scene") {
            shown[d] = scene_label(shown[d]);
        }
    }
    std::string md = fmt::format("| {} |", fmt::join(shown, " | "));
    for (const Entry* e : cells) {
        if (!e) {
            md += " – |";
            continue;
        }
        const std::string fps = fps_text(*e);
        md += fmt::format(" {}{} |", e == fastest ? "**" + fps + "**" : fps,
                          e->error ? " (" + format_error(x.table_metric, *e->error) + ")" : "");
    }
    return md + "\n";
}

}  // namespace

std::string sweep_table(const Experiment& x, const std::vector<StoredRow>& rows) {
    const std::vector<Entry> entries = aggregate(rows, x.table_metric);
    if (entries.empty()) {
        return "No cells measured.\n";
    }
    const SweepLayout layout = sweep_layout(x, entries);
    std::string md = fmt::format("| {} | {} |\n", fmt::join(layout.dims, " | "),
                                 fmt::join(layout.columns, " | "));
    for (size_t d = 0; d < layout.dims.size(); ++d) {
        md += "|---";
    }
    for (size_t c = 0; c < layout.columns.size(); ++c) {
        md += "|---:";
    }
    md += "|\n";
    for (const auto& key : layout.rows) {
        md += sweep_row(x, layout, entries, key);
    }
    return md;
}

}  // namespace sl::experiments
