#pragma once
// The row store of a bench directory: cells/<cell>.rep<r>.json, one result row per cell and
// repetition, each with the cell it measured. The harness writes them (bench.h); the tables, the
// CSV and env.json read them back here.

#include <filesystem>
#include <optional>
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

// A scene as the tables, the CSV's `scene` column, the plots and the progress lines name it: a
// scene file by its stem without ".scene" ("/…/experiments/toplight-hg.scene.toml" is
// "toplight-hg"), a name as it is. The cells keep the sweep's own spelling.
std::string scene_label(const std::string& scene);

// cells/<cell>.rep<r>.json under `out`.
std::filesystem::path row_path(const std::filesystem::path& out, const Cell& cell, int rep);
// Writes one row with its cell, atomically.
void write_row(const std::filesystem::path& out, const Cell& cell, int rep,
               const nlohmann::ordered_json& row);
// The row file's document ({cell, rep, row}); nullopt when there is none; throws sl::Error naming
// the file when it is not a row.
std::optional<nlohmann::ordered_json> read_row(const std::filesystem::path& path);
// The directory holds one experiment: its effective document is written on the first run and
// must match on every later one (resume), so rows of different settings never mix.
void claim_directory(const Experiment& experiment, const std::filesystem::path& out);

// A cell as the row files and process isolation's command line carry it.
nlohmann::json cell_to_json(const Cell& cell);
Cell cell_from_json(const nlohmann::json& json);  // throws sl::Error on a malformed one

}  // namespace sl::experiments
