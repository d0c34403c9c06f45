#include "experiments/summary.h"

#include <cstdlib>
#include <string>

#include "core/error.h"
#include "core/output_files.h"
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
