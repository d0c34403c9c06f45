#include "experiments/bench.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <sstream>

#include "core/error.h"
#include "core/image.h"
#include "core/metrics.h"
#include "core/output_files.h"
#include "core/statistics.h"
#include "core/temporal_metrics.h"
#include "experiments/equal_error.h"
#include "experiments/process.h"
#include "experiments/report.h"
#include "experiments/sequence.h"
#include "experiments/shards.h"
#include "experiments/summary.h"
#include "frame/frame_loop.h"
#include "frame/renderer.h"
#include "gl/platform.h"
#include "methods/configured_method.h"
#include "methods/frame_measurement.h"
#include "methods/region_statistics.h"
#include "methods/registry.h"
#include "methods/result_row.h"
#include "reference/cache.h"
#include "reference/reference.h"
#include "scenes/scene_file.h"
#include "scenes/variations.h"
#include "sss/subsurface_pass.h"

extern char** environ;

namespace sl::experiments {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using Json = nlohmann::ordered_json;

namespace {

std::string duration_text(double seconds) {
    const long s = std::lround(seconds);
    return s >= 3600 ? fmt::format("{}h{:02}m", s / 3600, s / 60 % 60)
                     : fmt::format("{}m{:02}s", s / 60, s % 60);
}

// The cell's scene variations (scenes/variations.h) as text, "" when it has none; with
// `view_only`, only those that change what the eye rays and the beam tree see.
std::string variations_text(const Cell& cell, bool view_only) {
    std::string text;
    for (const Setting& setting : cell.settings) {
        if (is_scene_variation(setting.name) &&
            (!view_only || scene_variation_changes_view(setting.name))) {
            text += fmt::format(";{}={}", setting.name, setting.value);
        }
    }
    return text;
}

// What one process keeps between cells: each scene file read once, each variation of it made
// once, and the region statistics of each view.
struct Caches {
    std::map<std::string, Scene> loaded;  // by name, as read
    std::map<std::string, Scene> scenes;  // by name and variations
    std::map<std::tuple<std::string, int, int, bool>, methods::RegionStatistics> regions;

    // The cell's scene with the cell's variations applied.
    const Scene& scene(const Cell& cell) {
        const std::string key = cell.scene + variations_text(cell, false);
        auto found = scenes.find(key);
        if (found == scenes.end()) {
            auto base = loaded.find(cell.scene);
            if (base == loaded.end()) {
                base =
                    loaded.emplace(cell.scene, load_scene(cell.scene, SceneSearchPaths::defaults()))
                        .first;
            }
            Scene scene = base->second;  // meshes are shared, not copied
            for (const Setting& setting : cell.settings) {
                if (is_scene_variation(setting.name)) {
                    apply_scene_variation(scene, setting.name, setting.value);
                }
            }
            found = scenes.emplace(key, std::move(scene)).first;
        }
        return found->second;
    }
    // The region statistics of the cell's view (an animation cell: of its first frame), shared by
    // the variations that leave the view as it is.
    const methods::RegionStatistics& region(const Cell& cell, const Scene& view, bool animated) {
        const auto key = std::make_tuple(cell.scene + variations_text(cell, true), cell.width,
                                         cell.height, animated);
        if (!regions.contains(key)) {
            regions[key] = methods::region_statistics(view, cell.width, cell.height);
        }
        return regions[key];
    }
};

// What every cell sets up: the scene, the configured method, a fresh GL context and renderer.
struct CellSetup {
    const Scene* scene = nullptr;
    frame::RenderOptions options;
    std::unique_ptr<frame::VolumeMethod> method;
    double load_ms = 0.0;
};

CellSetup set_up(const Experiment& x, const Cell& cell, Caches& caches) {
    CellSetup s;
    const auto start = Clock::now();
    s.scene = &caches.scene(cell);
    s.load_ms = ms_since(start);
    s.options = {.width = cell.width,
                 .height = cell.height,
                 .shadow = {.filter = frame::parse_shadow_filter(x.render.shadow),
                            .map_size = x.render.shadow_map_size,
                            .radius = x.render.pcf_radius}};
    std::vector<std::pair<std::string, std::string>> settings;
    for (const Setting& setting : cell.settings) {
        if (!is_scene_variation(setting.name)) {
            settings.emplace_back(setting.name, setting.value);
        }
    }
    s.method = methods::create_configured_method(cell.method, s.options.shadow, settings);
    return s;
}

// Each cell's method configured as it will be measured, without a GL context: a combination
// of parameters a method refuses (VolumeMethod::validate) stops the run before its first frame,
// naming the cell.
void validate_cells(const Experiment& x) {
    const frame::ShadowSettings shadow{.filter = frame::parse_shadow_filter(x.render.shadow),
                                       .map_size = x.render.shadow_map_size,
                                       .radius = x.render.pcf_radius};
    for (const Cell& cell : x.cells()) {
        methods::Settings settings;
        for (const Setting& setting : cell.settings) {
            if (!is_scene_variation(setting.name)) {
                settings.emplace_back(setting.name, setting.value);
            }
        }
        try {
            methods::create_configured_method(cell.method, shadow, settings);
        } catch (const Error& e) {
            fail("{}: cell {} {} {}: {}", x.source.string(), cell.scene, cell.method,
                 cell.settings_text(), e.what());
        }
    }
}

// A fresh GL context and a renderer for `scene`, with the method prepared for it, timed.
struct CellContext {
    std::unique_ptr<gl::Platform> platform;
    gl::ContextInfo info;
    std::unique_ptr<frame::SceneRenderer> renderer;
    double setup_ms = 0.0;
    double prepare_ms = 0.0;
};

CellContext open_context(const CellSetup& s, const Scene& scene) {
    CellContext c;
    auto start = Clock::now();
    c.platform = gl::create_headless_platform();
    c.info = c.platform->info();
    c.renderer = std::make_unique<frame::SceneRenderer>(scene, s.options);
    c.setup_ms = ms_since(start);
    start = Clock::now();
    s.method->set_view_aspect(s.options.aspect());
    s.method->prepare(scene);
    c.prepare_ms = ms_since(start);
    return c;
}

// I_s (EXR) and the tone-mapped frame (PNG) of repetition 0; returns the row's image path.
std::string write_images(const Experiment& x, const Cell& cell, int rep, const fs::path& out,
                         const frame::Frame& frame) {
    std::string image;
    if (rep != 0) {
        return image;
    }
    OutputFiles images(out / "images");
    if (x.images) {
        images.add(cell.id() + ".inscatter.exr",
                   [&](const fs::path& path) { write_exr(frame.in_scattering, path); });
    }
    if (x.previews && std::max(cell.width, cell.height) <= x.preview_max_size) {
        image = "images/" + cell.id() + ".png";
        images.add(cell.id() + ".png", [&](const fs::path& path) {
            write_png(frame.display_srgb8, cell.width, cell.height, path);
        });
    } else if (x.images) {
        image = "images/" + cell.id() + ".inscatter.exr";
    }
    images.commit();
    return image;
}

Json row_head(const Experiment& x, const Cell& cell, int rep, int frames,
              const std::vector<double>& frame_ms) {
    Json row = {{"experiment", x.name}, {"cell", cell.id()}};
    row.update(methods::view_columns(cell.scene, cell.method, cell.width, cell.height,
                                     cell.settings_text()));
    row["rep"] = rep;
    methods::add_frame_times(row, frames, frame_ms);
    return row;
}

Json metric_value(const Experiment& x, const char* name, bool scored, double value) {
    const bool wanted =
        scored && std::find(x.metrics.begin(), x.metrics.end(), name) != x.metrics.end();
    return wanted && std::isfinite(value) ? Json(value) : Json();
}

// The region statistics, the method's counters and parameters, the shadow map, the context and
// the harness's own settings.
void add_tail(Json& row, const Experiment& x, const frame::VolumeMethod& method,
              const frame::MethodStatistics& statistics, const methods::RegionStatistics& regions,
              const frame::SceneRenderer& renderer, const gl::ContextInfo& context,
              const std::string& image) {
    methods::add_regions(row, regions, statistics);
    methods::add_method(row, method, statistics, image);
    methods::add_context(row, renderer.shadow(), context);
    row["reference"] = x.reference;
    row["isolation"] = x.protocol.isolation == Isolation::process ? "process" : "context";
    row["warmup"] = x.protocol.warmup;
    methods::add_subsurface(row, renderer);
}

// Renders one still cell and repetition in a fresh GL context and returns its result row.
Json measure_still_cell(const Experiment& x, const Cell& cell, int rep, const fs::path& out,
                        Caches& caches) {
    CellSetup s = set_up(x, cell, caches);
    const Scene& scene = *s.scene;
    const CellContext c = open_context(s, scene);
    frame::SceneRenderer& renderer = *c.renderer;
    const gl::ContextInfo& context = c.info;
    const double setup_ms = c.setup_ms, prepare_ms = c.prepare_ms;

    // Paired with `none` at the method's own shadow map (harness.md, "Paired"), or alone.
    std::optional<methods::PairedMeasurement> paired;
    if (x.protocol.paired && cell.method != "none") {
        const frame::ShadowSettings shadow = s.method->shadow_settings(s.options.shadow);
        const auto none =
            methods::create_configured_method("none", shadow,
                                              {{"shadow", frame::to_string(shadow.filter)},
                                               {"shadow_size", std::to_string(shadow.map_size)}});
        none->prepare(scene);
        paired = methods::measure_paired_frames(renderer, *s.method, *none, x.protocol.warmup,
                                                x.protocol.frames);
    }
    const methods::FrameMeasurement m =
        paired ? paired->method
               : methods::measure_frames(renderer, *s.method, x.protocol.warmup, x.protocol.frames);
    const frame::Frame frame = renderer.read_back();

    std::optional<ErrorMetrics> error;
    if (!x.reference.empty()) {
        // Scored where the rasterized surface is the reference's first hit (docs/harness.md).
        const std::vector<uint8_t> scored =
            reference::same_surface_pixels(scene, cell.width, cell.height, frame.depth);
        const auto reference = methods::create_volume_method(x.reference);
        error =
            compare_images(frame.in_scattering, renderer.render(*reference).in_scattering, &scored);
    }

    auto start = Clock::now();
    const methods::RegionStatistics& regions = caches.region(cell, scene, false);
    const double regions_ms = ms_since(start);
    const std::string image = write_images(x, cell, rep, out, frame);

    Json row = row_head(x, cell, rep, x.protocol.frames, m.frame_ms);
    methods::add_gpu(row, m.gpu, m.gpu_total_ms);
    // The volume cost (docs/design.md §11): the volume pass's GPU time plus the method's CPU work
    // per frame (slicing and partitioning sampling planes); what the regions must make cheaper.
    row["volume_cost_ms"] = m.gpu.volume_ms + methods::statistic(m.statistics, "cpu_ms_frame");
    row["cpu_ms_scene_load"] = s.load_ms;
    row["cpu_ms_gl_setup"] = setup_ms;
    row["cpu_ms_prepare"] = prepare_ms;
    row["cpu_ms_region_statistics"] = regions_ms;
    row["rel_rmse"] = metric_value(x, "rel_rmse", error.has_value(), error ? error->rel_rmse : 0.0);
    row["max_abs"] = metric_value(x, "max_abs", error.has_value(), error ? error->max_abs : 0.0);
    // psnr is empty when exact (infinite).
    row["psnr"] = metric_value(x, "psnr", error.has_value(), error ? error->psnr : 0.0);
    row["unscored_pixels"] = error ? Json(error->unscored) : Json();
    add_tail(row, x, *s.method, m.statistics, regions, renderer, context, image);
    row["protocol"] = "still";
    row["frame_ms_samples"] = m.frame_ms;  // for the confidence intervals (statistics.h)
    if (paired) {
        row["paired_with"] = "none";
        row["paired_difference_ms"] = median(paired->difference_ms);
        row["paired_difference_ms_samples"] = paired->difference_ms;
        row["paired_baseline_ms_samples"] = paired->baseline_ms;
    }
    return row;
}

// The scores of an animation cell's frames against the reference sequence, and the frame to show
// (the worst-scored one).
struct SequenceScores {
    explicit SequenceScores(int frames) : errors(static_cast<size_t>(frames)) {}
    std::vector<std::optional<ErrorMetrics>> errors;  // per frame, the scored ones set
    TemporalMetrics temporal;
    std::optional<frame::Frame> picture;
    int picture_frame = -1;

    void score(int k, frame::Frame frame, const Image& truth, const std::vector<uint8_t>& scored) {
        errors[size_t(k)] = compare_images(frame.in_scattering, truth, &scored);
        temporal.add(frame.in_scattering, truth);
        if (!picture || errors[size_t(k)]->rel_rmse > errors[size_t(picture_frame)]->rel_rmse) {
            picture = std::move(frame);
            picture_frame = k;
        }
    }
};

// The error columns of an animation row: per frame the median and p95 relative RMSE and the
// worst frame, max_abs the sequence's largest, psnr the median; the temporal metrics.
void add_sequence_scores(Json& row, const Experiment& x, const SequenceScores& scores) {
    std::vector<double> rel_rmse, max_abs, psnr;
    for (const auto& e : scores.errors) {
        if (e) {
            rel_rmse.push_back(e->rel_rmse);
            max_abs.push_back(e->max_abs);
            if (std::isfinite(e->psnr)) {
                psnr.push_back(e->psnr);
            }
        }
    }
    const bool scored = !rel_rmse.empty();
    row["rel_rmse"] = metric_value(x, "rel_rmse", scored, median(rel_rmse));
    row["max_abs"] = metric_value(x, "max_abs", scored,
                                  scored ? *std::max_element(max_abs.begin(), max_abs.end()) : 0.0);
    row["psnr"] = metric_value(x, "psnr", !psnr.empty(), median(psnr));
    if (scored) {
        row["rel_rmse_p95"] = percentile(rel_rmse, 95.0);
        row["rel_rmse_worst"] = *std::max_element(rel_rmse.begin(), rel_rmse.end());
        row["error_worst_frame"] = scores.picture_frame;
        row["temporal_error"] = scores.temporal.temporal_error();
        row["flicker"] = scores.temporal.flicker();
        row["pops"] = count_pops(rel_rmse, x.scoring.pop_factor, x.scoring.pop_floor);
        row["scored_frames"] = int(rel_rmse.size());
    }
}

// Every frame's costs and error, as the row's `per_frame` series (frames.csv).
Json per_frame_series(const std::vector<frame::FrameRecord>& records, const Sequence& sequence,
                      const SequenceScores& scores) {
    Json series = Json::object();
    for (const char* name : {"frame", "time_s", "frame_ms", "update_ms", "apply_ms", "wait_ms",
                             "draw_ms", "gpu_ms", "gpu_ms_volume", "rel_rmse"}) {
        series[name] = Json::array();
    }
    for (const frame::FrameRecord& r : records) {
        series["frame"].push_back(r.frame);
        series["time_s"].push_back(sequence.time(r.frame));
        series["frame_ms"].push_back(r.frame_ms);
        series["update_ms"].push_back(r.update_ms);
        series["apply_ms"].push_back(r.apply_ms);
        series["wait_ms"].push_back(r.wait_ms);
        series["draw_ms"].push_back(r.draw_ms);
        series["gpu_ms"].push_back(r.gpu.total_ms());
        series["gpu_ms_volume"].push_back(r.gpu.volume_ms);
        const auto& e = scores.errors[size_t(r.frame)];
        series["rel_rmse"].push_back(e ? Json(e->rel_rmse) : Json());
    }
    return series;
}

// What one play of an animated cell leaves: every frame's record, the method's statistics of
// every frame, and the scores of every stride-th frame (or the last frame's picture).
struct PlayedSequence {
    std::vector<frame::FrameRecord> records;
    NamedSeries statistics;
    SequenceScores scores;
};

// Plays the sequence through frame::FrameLoop, scoring every stride-th frame against
// `x.reference` drawn in the same context from the same scene state.
PlayedSequence play_sequence(const Experiment& x, const Cell& cell, int rep,
                             const Sequence& sequence, frame::VolumeMethod& method,
                             frame::SceneRenderer& renderer, Scene& live,
                             const BenchOptions* options) {
    const int frames = sequence.frames();
    const int stride = x.scoring.stride;
    const std::unique_ptr<frame::VolumeMethod> reference =
        x.reference.empty() ? nullptr : methods::create_volume_method(x.reference);
    Scene reference_scene = live;
    if (reference) {
        reference->prepare(reference_scene);
    }
    PlayedSequence played{{}, {}, SequenceScores(frames)};
    SequenceScores& scores = played.scores;
    frame::FrameLoop loop(
        renderer, method, live,
        x.protocol.pipelined ? frame::FrameMode::pipelined : frame::FrameMode::serial);
    loop.play(
        frames, [&](int k) { return sequence.state(k); },
        [&](const frame::FrameRecord& record) {
            played.records.push_back(record);
            collect(played.statistics, method.frame_statistics());
            const int k = record.frame;
            if (reference && k % stride == 0) {
                frame::Frame frame = renderer.read_back();
                const std::vector<uint8_t> scored =
                    reference::same_surface_pixels(live, cell.width, cell.height, frame.depth);
                reference->update(live, scene_change(reference_scene, live));
                reference_scene = live;
                scores.score(k, std::move(frame), renderer.render(*reference).in_scattering,
                             scored);
            } else if (!reference && k + 1 == frames) {
                scores.picture = renderer.read_back();  // no scores: the last frame is shown
                scores.picture_frame = k;
            }
            if (options && options->on_frame) {
                options->on_frame(cell, rep, k);
            }
            if (isatty(STDERR_FILENO) && (k % 10 == 9 || k + 1 == frames)) {
                fmt::print(stderr, "\r  {} rep {}: frame {}/{}{}", cell.id(), rep, k + 1, frames,
                           k + 1 == frames ? "\n" : "");
            }
        });
    return played;
}

// The row's frame timings: medians (and the worst frame, the update's p95) over the records.
void add_frame_timings(Json& row, const std::vector<frame::FrameRecord>& records,
                       const std::vector<double>& frame_ms,
                       const frame::MethodStatistics& method_statistics) {
    auto series = [&](auto get) {
        std::vector<double> v;
        for (const frame::FrameRecord& r : records) {
            v.push_back(get(r));
        }
        return v;
    };
    const std::vector<double> critical = series([](const auto& r) { return r.critical_cpu_ms(); });
    methods::PassSeries passes;
    for (const frame::FrameRecord& r : records) {
        passes.add(r.gpu);
    }
    const frame::PassTimings gpu = passes.medians();
    const size_t slowest =
        size_t(std::max_element(frame_ms.begin(), frame_ms.end()) - frame_ms.begin());
    row["frame_ms_worst"] = frame_ms[slowest];
    row["frame_worst"] = int(slowest);
    methods::add_gpu(row, gpu, passes.total_median());
    row["volume_cost_ms"] =
        gpu.volume_ms + methods::statistic(method_statistics, "cpu_ms_frame") + median(critical);
    row["cpu_ms_update"] = median(series([](const auto& r) { return r.update_ms; }));
    row["cpu_ms_update_p95"] = percentile(series([](const auto& r) { return r.update_ms; }), 95.0);
    row["cpu_ms_apply"] = median(series([](const auto& r) { return r.apply_ms; }));
    row["cpu_ms_wait"] = median(series([](const auto& r) { return r.wait_ms; }));
    row["cpu_ms_critical"] = median(critical);
    row["cpu_ms_draw"] = median(series([](const auto& r) { return r.draw_ms; }));
}

// Plays one animation cell and repetition (docs/design.md §11) in a fresh GL context: every frame's
// CPU update, apply, draw and GPU passes through frame::FrameLoop, and every stride-th frame scored
// against the reference of that frame (computed first, multithreaded, cached on disk, so that
// the measured frames run undisturbed and a second repetition or an interrupted run pays for
// nothing again). Returns its row, with the per-frame series in `per_frame`.
Json measure_animated_cell(const Experiment& x, const Cell& cell, int rep, const fs::path& out,
                           Caches& caches, const BenchOptions* options) {
    CellSetup s = set_up(x, cell, caches);
    const Sequence sequence(*s.scene, x.protocol);
    const int frames = sequence.frames();

    // The reference sequence, before anything is measured.
    auto start = Clock::now();
    if (x.reference == "reference") {
        for (int k = 0; k < frames; k += x.scoring.stride) {
            reference::cached_reference(sequence.state(k), cell.width, cell.height, {});
        }
    }
    const double reference_ms = ms_since(start);

    Scene live = sequence.state(0);
    const CellContext c = open_context(s, live);
    frame::SceneRenderer& renderer = *c.renderer;
    for (int i = 0; i < x.protocol.warmup; ++i) {
        renderer.draw(*s.method);  // shader compilation and first-use costs
    }
    const PlayedSequence played =
        play_sequence(x, cell, rep, sequence, *s.method, renderer, live, options);
    std::vector<double> frame_ms;
    for (const frame::FrameRecord& r : played.records) {
        frame_ms.push_back(r.frame_ms);
    }
    const frame::MethodStatistics method_statistics = medians(played.statistics);

    start = Clock::now();
    const methods::RegionStatistics& regions = caches.region(cell, sequence.state(0), true);
    const double regions_ms = ms_since(start);
    const std::string image = played.scores.picture
                                  ? write_images(x, cell, rep, out, *played.scores.picture)
                                  : std::string();

    Json row = row_head(x, cell, rep, frames, frame_ms);
    add_frame_timings(row, played.records, frame_ms, method_statistics);
    row["cpu_ms_scene_load"] = s.load_ms;
    row["cpu_ms_gl_setup"] = c.setup_ms;
    row["cpu_ms_prepare"] = c.prepare_ms;
    row["cpu_ms_region_statistics"] = regions_ms;
    add_sequence_scores(row, x, played.scores);
    add_tail(row, x, *s.method, method_statistics, regions, renderer, c.info, image);
    row["protocol"] = "animation";
    row["sequence"] = sequence.description();
    row["frame_mode"] = x.protocol.pipelined ? "pipelined" : "serial";
    row["step_s"] = sequence.step();
    row["stride"] = x.scoring.stride;
    row["reference_sequence_ms"] = reference_ms;
    row["frame_ms_samples"] = frame_ms;
    row["per_frame"] = per_frame_series(played.records, sequence, played.scores);
    return row;
}

Json measure_cell(const Experiment& x, const Cell& cell, int rep, const fs::path& out,
                  Caches& caches, const BenchOptions* options = nullptr) {
    return x.protocol.animated() ? measure_animated_cell(x, cell, rep, out, caches, options)
                                 : measure_still_cell(x, cell, rep, out, caches);
}

}  // namespace

namespace {

std::string cell_label(const Cell& cell) {
    const std::string scene = scene_label(cell.scene);
    return cell.settings.empty()
               ? fmt::format("{} {} {}", scene, cell.size(), cell.method)
               : fmt::format("{} {} {} {}", scene, cell.size(), cell.method, cell.settings_text());
}

}  // namespace

void run_cell(const Experiment& x, const fs::path& out, const nlohmann::json& cell_json, int rep) {
    const Cell cell = cell_from_json(cell_json);
    Caches caches;
    write_row(out, cell, rep, measure_cell(x, cell, rep, out, caches));
}

namespace {

// The indices this shard runs (i/n: every n-th from the i-th).
std::vector<size_t> shard_indices(size_t total, const Shard& shard) {
    std::vector<size_t> mine;
    for (size_t i = 0; i < total; ++i) {
        if (int(i % size_t(shard.count)) == shard.index - 1) {
            mine.push_back(i);
        }
    }
    return mine;
}

// One run of an experiment into its directory: the cells measured (or their rows loaded from an
// earlier run), with progress, counting what failed.
class BenchRun {
public:
    BenchRun(const Experiment& x, const BenchOptions& options) : x_(x), options_(options) {}

    void run_searches() {
        // One unit per search group; each runs its bisections for every target.
        const std::vector<Cell> groups = search_groups(x_);
        const std::vector<size_t> mine = shard_indices(groups.size(), options_.shard);
        for (size_t k = 0; k < mine.size(); ++k) {
            const Cell& group = groups[mine[k]];
            for (const double target : x_.equal_error->targets) {
                const std::string progress =
                    fmt::format("[search {}/{}, target {:.3g}%]", k + 1, mine.size(), 100 * target);
                const SearchOutcome outcome = search_equal_error(
                    x_, group, target, [&](const Cell& cell) { return ensure(cell, progress); });
                const std::string setting =
                    outcome.parameter.empty()
                        ? std::string("as is")
                        : fmt::format("{}={}", outcome.parameter, outcome.value);
                fmt::print(stderr, "  => {}: {}\n", cell_label(group),
                           !outcome.complete ? "incomplete"
                           : outcome.reached
                               ? fmt::format("{} at {:.1f} ms", setting, outcome.summary.frame_ms)
                               : "target not reached");
            }
        }
    }

    void run_sweep() {
        const std::vector<Cell> cells = x_.cells();
        std::vector<size_t> mine = shard_indices(cells.size(), options_.shard);
        if (x_.protocol.order_shuffled) {
            std::mt19937_64 random(x_.protocol.seed);
            std::shuffle(mine.begin(), mine.end(), random);
        }
        for (size_t k = 0; k < mine.size(); ++k) {
            // Remaining time from the cells measured in this run (rows from an earlier run are
            // free).
            const std::string remaining =
                measured_ ? fmt::format(", ~{} left", duration_text(measured_seconds_ / measured_ *
                                                                    double(mine.size() - k)))
                          : std::string();
            ensure(cells[mine[k]], fmt::format("[{}/{}{}]", k + 1, mine.size(), remaining));
        }
    }

    int failed() const { return failed_; }

private:
    // Measures (or loads) every repetition of a cell; nullopt when one failed.
    std::optional<CellSummary> ensure(const Cell& cell, const std::string& progress) {
        std::vector<double> errors, times, volume_times;
        for (int rep = 0; rep < x_.protocol.repetitions; ++rep) {
            const fs::path path = row_path(options_.out, cell, rep);
            std::optional<Json> row = read_row(path);
            const bool fresh = !row;
            if (fresh) {
                row = measure(cell, rep, path);
                if (!row) {
                    return std::nullopt;
                }
            }
            const Json& r = row->at("row");
            times.push_back(r.at("frame_ms_median").get<double>());
            volume_times.push_back(r.value("volume_cost_ms", 0.0));
            errors.push_back(r.at("rel_rmse").is_number() ? r.at("rel_rmse").get<double>() : 0.0);
            print_progress(progress, cell, rep, r, fresh);
        }
        double error = 0.0;
        for (const double e : errors) {
            error += e / double(errors.size());
        }
        return CellSummary{error, median(times), median(volume_times)};
    }

    // One repetition of a cell, measured here or in a process of its own; nullopt when it failed.
    std::optional<Json> measure(const Cell& cell, int rep, const fs::path& path) {
        const auto cell_start = Clock::now();
        std::optional<Json> row;
        try {
            if (x_.protocol.isolation == Isolation::process) {
                std::vector<std::string> args = options_.relaunch;
                args.insert(args.end(),
                            {"--cell", cell_to_json(cell).dump(), "--rep", std::to_string(rep)});
                if (const int code = spawn_and_wait(args); code != 0) {
                    fail("the cell's process exited with status {}", code);
                }
                row = read_row(path);
                if (!row) {
                    fail("the cell's process wrote no row");
                }
            } else {
                const Json measured_row =
                    measure_cell(x_, cell, rep, options_.out, caches_, &options_);
                write_row(options_.out, cell, rep, measured_row);
                row = Json{{"row", measured_row}};
            }
        } catch (const Interrupted&) {
            throw;  // the run stops here, as if killed: the cell left nothing behind
        } catch (const std::exception& e) {
            ++failed_;
            fmt::print(stderr, "  FAILED {} rep {}: {}\n", cell_label(cell), rep, e.what());
            return std::nullopt;
        }
        ++measured_;
        measured_seconds_ += ms_since(cell_start) / 1000.0;
        return row;
    }

    void print_progress(const std::string& progress, const Cell& cell, int rep, const Json& r,
                        bool fresh) const {
        const double elapsed = ms_since(started_) / 1000.0;
        std::string temporal;
        if (r.contains("flicker")) {
            temporal = fmt::format(", p95 frame {:.1f} ms, flicker {:.3g}%, {} pops",
                                   r.value("frame_ms_p95", 0.0), 100.0 * r.value("flicker", 0.0),
                                   r.value("pops", 0));
        }
        fmt::print(stderr, "{} {} rep {}: {:.2f} fps{}{}  [{} elapsed{}]\n", progress,
                   cell_label(cell), rep, 1000.0 / r.at("frame_ms_median").get<double>(),
                   r.at("rel_rmse").is_number()
                       ? fmt::format(", rel_rmse {:.3g}%", 100.0 * r.at("rel_rmse").get<double>())
                       : std::string(),
                   temporal, duration_text(elapsed), fresh ? "" : ", from an earlier run");
    }

    const Experiment& x_;
    const BenchOptions& options_;
    Caches caches_;
    const Clock::time_point started_ = Clock::now();
    int failed_ = 0;
    int measured_ = 0;
    double measured_seconds_ = 0.0;
};

}  // namespace

int run_bench(const Experiment& x, const BenchOptions& options) {
    // Everything that can be refused is refused before the directory is claimed.
    if (x.cells().empty()) {
        fail("{}: the sweep is empty (every cell excluded)", x.source.string());
    }
    validate_cells(x);
    for (const std::string& warning : x.warnings) {
        fmt::print(stderr, "bench: warning: {}\n", warning);
    }
    claim_directory(x, options.out);
    BenchRun run(x, options);
    if (x.equal_error) {
        run.run_searches();
    } else {
        run.run_sweep();
    }
    if (options.write_outputs) {
        write_summary(x, options.out);
    }
    if (run.failed()) {
        fmt::print(stderr, "{} cell(s) failed; running the same command again retries them\n",
                   run.failed());
    }
    return run.failed();
}

}  // namespace sl::experiments
