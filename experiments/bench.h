#pragma once
// The harness (docs/design.md §6): runs an experiment's cells and writes, into one directory,
//   cells/<cell>.rep<r>.json   one result row per cell and repetition, each written atomically
//                              (an animation cell's row holds its per-frame series); a run
//                              started again skips the rows that exist (resume);
//   images/<cell>.inscatter.exr, images/<cell>.png   I_s and the tone-mapped frame (repetition 0);
//   results.csv                every row, long format;
//   frames.csv                 animation cells: every frame of every row, long format;
//   table.md                   Nilsson Table 6.1's layout (and the equal-error report);
//   equal_error.csv            when the experiment has [equal_error];
//   env.json                   machine, GL, compiler, libraries, git, the experiment verbatim;
//   plots/*.png                by experiments/plots.py (Debian's python3-matplotlib);
//   experiment.toml            the experiment as run: a directory holds one experiment only.

#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/experiment.h"
#include "experiments/rows.h"
#include "experiments/shards.h"

namespace sl::experiments {

struct BenchOptions {
    std::filesystem::path out;
    Shard shard;
    // For process isolation: the command line that re-runs this bench (executable, experiment,
    // presets, overrides, --out); the harness appends --cell JSON --rep R.
    std::vector<std::string> relaunch;
    bool write_outputs = true;  // results.csv, table.md, env.json, plots after the cells
    // Called on the GL thread after every measured frame of an animation cell (progress); an
    // Interrupted thrown from it stops the whole run as a kill would (the tests' interruption).
    std::function<void(const Cell&, int rep, int frame)> on_frame;
};

// Thrown by BenchOptions::on_frame to stop run_bench mid-cell: nothing of the cell is written.
struct Interrupted : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Runs every cell of this shard that has no row yet, printing progress to stderr, then writes
// the summary outputs. Returns the number of cells that failed (their rows are absent; running
// again retries them).
int run_bench(const Experiment& experiment, const BenchOptions& options);

// One cell and repetition in this process (the child of process isolation): writes its row.
void run_cell(const Experiment& experiment, const std::filesystem::path& out,
              const nlohmann::json& cell, int rep);

}  // namespace sl::experiments
