#pragma once
// The summary outputs of a bench directory (see bench.h): results.csv, frames.csv, table.md,
// equal_error.csv, env.json and plots/, all from the rows in cells/, each written atomically.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/experiment.h"

namespace sl::experiments {

// Every row of the directory, with its cell, in sweep order (scene, size, method, parameters,
// repetition).
struct StoredRow {
    Cell cell;
    int rep = 0;
    nlohmann::ordered_json row;
};
std::vector<StoredRow> load_rows(const Experiment& experiment, const std::filesystem::path& out);

// This run beside a baseline run of the same experiment (the committed results, another machine):
// per cell, in this run's order, the FPS here and there and their ratio, and the error here and
// there; a cell only one of them has is marked. Markdown, with both machines named. Throws when
// the baseline holds no rows.
std::string baseline_comparison(const Experiment& experiment, const std::filesystem::path& out,
                                const std::filesystem::path& baseline);

// A scene as the tables, the CSV's `scene` column, the plots and the progress lines name it: a
// scene file by its stem without ".scene" ("/…/experiments/toplight-hg.scene.toml" is
// "toplight-hg"), a name as it is. The cells keep the sweep's own spelling.
std::string scene_label(const std::string& scene);

// results.csv's text: the union of the rows' columns, fixed ones first.
std::string results_csv(const std::vector<StoredRow>& rows);
// frames.csv's text: every frame of every animation row (its per_frame series), long format.
std::string frames_csv(const std::vector<StoredRow>& rows);
// Nilsson Table 6.1's layout: rows (dz ×) scene × size, columns methods, FPS with the error.
std::string sweep_table(const Experiment& experiment, const std::vector<StoredRow>& rows);

// Machine, GL, compiler, libraries, git state and the experiment (file verbatim, overrides).
nlohmann::ordered_json environment(const Experiment& experiment,
                                   const std::vector<StoredRow>& rows);

// Runs a program and waits for it; returns its exit status (128 + signal when killed).
int spawn_and_wait(const std::vector<std::string>& arguments);

}  // namespace sl::experiments
