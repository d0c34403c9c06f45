#include "experiments/summary.h"

#include <cstdlib>
#include <string>

#include "core/error.h"
#include "core/output_files.h"
#include "experiments/aggregate.h"
#include "experiments/csv.h"
#include "experiments/environment.h"
#include "experiments/process.h"
#include "experiments/report.h"
#include "experiments/rows.h"

#ifndef SHAFTLAB_SOURCE_DIR
#error "SHAFTLAB_SOURCE_DIR must be defined by the build"
#endif

namespace sl::experiments {

namespace fs = std::filesystem;

namespace {

// summary.json: the run in one document a script reads, cell by cell as the table shows them
// (over the repetitions: the median frame time with its interval, the mean error), with where it
// was measured.
nlohmann::ordered_json summary_json(const Experiment& x, const std::vector<StoredRow>& rows,
                                    const nlohmann::ordered_json& env) {
    nlohmann::ordered_json cells = nlohmann::ordered_json::array();
    for (const Entry& e : aggregate(rows, x.table_metric)) {
        nlohmann::ordered_json cell = {{"scene", e.cell.scene},
                                       {"method", e.cell.method},
                                       {"width", e.cell.width},
                                       {"height", e.cell.height},
                                       {"params", e.cell.settings_text()},
                                       {"repetitions", e.rows.size()},
                                       {"frame_ms", e.frame_ms},
                                       {"fps", e.frame_ms > 0.0 ? 1000.0 / e.frame_ms : 0.0},
                                       {"volume_cost_ms", e.volume_ms}};
        if (e.has_interval) {
            cell["frame_ms_interval"] = {e.frame_ms_interval.low, e.frame_ms_interval.high};
        }
        cell[x.table_metric] =
            e.error ? nlohmann::ordered_json(*e.error) : nlohmann::ordered_json();
        if (!e.rows.empty()) {
            const nlohmann::ordered_json& first = e.rows.front()->row;
            for (const char* key : {"unscored_pixels", "ray_frac_lit", "ray_frac_uncertain",
                                    "ray_frac_unlit", "paired_difference_ms"}) {
                if (first.contains(key)) {
                    cell[key] = first[key];
                }
            }
        }
        cells.push_back(std::move(cell));
    }
    return {{"experiment", x.name},     {"source", x.source.string()}, {"overrides", x.overrides},
            {"metric", x.table_metric}, {"environment", env},          {"cells", cells}};
}

}  // namespace

void write_summary(const Experiment& x, const fs::path& out) {
    const std::vector<StoredRow> rows = load_rows(x, out);
    const nlohmann::ordered_json env = environment(x, rows);
    const Report report = make_report(x, rows, env);
    OutputFiles files(out);
    files.add_text("results.csv", results_csv(rows));
    if (x.protocol.animated()) {
        files.add_text("frames.csv", frames_csv(rows));
    }
    files.add_text("table.md", report.markdown);
    files.add_text("env.json", env.dump(2) + "\n");
    files.add_text("summary.json", summary_json(x, rows, env).dump(2) + "\n");
    if (x.equal_error) {
        files.add_text("equal_error.csv", report.equal_error_csv);
    }
    files.commit();
    if (x.plots && !rows.empty()) {
        // Debian's interpreter has Debian's matplotlib (python3-matplotlib), whatever is on PATH;
        // SHAFTLAB_PYTHON names another (a machine whose matplotlib lives elsewhere).
        const char* chosen = std::getenv("SHAFTLAB_PYTHON");
        const std::string python = chosen && *chosen                ? chosen
                                   : fs::exists("/usr/bin/python3") ? "/usr/bin/python3"
                                                                    : "python3";
        const int code = spawn_and_wait(
            {python, std::string(SHAFTLAB_SOURCE_DIR) + "/experiments/plots.py", out.string()});
        if (code != 0) {
            fail("experiments/plots.py failed (status {}); is python3-matplotlib installed?", code);
        }
    }
}

}  // namespace sl::experiments
