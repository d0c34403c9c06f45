#include "experiments/baseline.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "core/error.h"
#include "core/statistics.h"
#include "experiments/aggregate.h"

namespace sl::experiments {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

// One cell's rows in a run: FPS, error, frame times.
struct Cells {
    std::vector<double> fps, error;
    std::vector<std::vector<double>> samples;  // frame ms per repetition
    bool complete = true;                      // every row kept its frames
    void add(const Json& row) {
        fps.push_back(row.at("fps").get<double>());
        if (row.contains("rel_rmse") && row["rel_rmse"].is_number()) {
            error.push_back(row["rel_rmse"].get<double>());
        }
        samples.push_back(frame_samples(row, complete));
    }
    // FPS with the interval of the median frame time inverted, when the frames were kept.
    std::string fps_text() const {
        if (!complete) {
            return fmt::format("{:.2f}", median(fps));
        }
        const Interval i = median_interval(samples);
        return fmt::format("{:.2f} [{:.2f}–{:.2f}]", median(fps), 1000.0 / i.high, 1000.0 / i.low);
    }
    // The mean rel_rmse in percent, or "" without one.
    std::string error_text() const {
        if (error.empty()) {
            return "";
        }
        double sum = 0.0;
        for (const double e : error) {
            sum += e / double(error.size());
        }
        return fmt::format("{:.3g}%", 100 * sum);
    }
};

// The baseline's rows by cell id (its experiment file may be an older version of this one).
std::map<std::string, Cells> baseline_cells(const fs::path& baseline) {
    std::map<std::string, Cells> theirs;
    if (fs::is_directory(baseline / "cells")) {
        for (const auto& entry : fs::directory_iterator(baseline / "cells")) {
            const std::string name = entry.path().filename().string();
            if (name.starts_with(".") || !name.ends_with(".json")) {
                continue;
            }
            std::ifstream file(entry.path());
            try {
                const Json row = Json::parse(file).at("row");
                theirs[row.at("cell").get<std::string>()].add(row);
            } catch (const std::exception& e) {
                fail("{}: not a result row: {}", entry.path().string(), e.what());
            }
        }
    }
    if (theirs.empty()) {
        fail("{}: no result rows (cells/*.json) to compare with", baseline.string());
    }
    return theirs;
}

std::string machine(const fs::path& dir) {
    std::ifstream file(dir / "env.json");
    try {
        const Json env = Json::parse(file);
        return fmt::format("{} ({} cores), GL {}", env.at("cpu").value("model", "?"),
                           env.at("cpu").value("cores", 0), env.at("gl").value("renderer", "?"));
    } catch (const std::exception&) {
        return std::string("an unrecorded machine");
    }
}

}  // namespace

std::string baseline_comparison(const Experiment& x, const fs::path& out,
                                const fs::path& baseline) {
    const std::map<std::string, Cells> theirs = baseline_cells(baseline);
    std::map<std::string, Cells> ours;
    std::vector<std::string> order;
    for (const StoredRow& r : load_rows(x, out)) {
        const std::string id = r.row.at("cell").get<std::string>();
        if (!ours.contains(id)) {
            order.push_back(id);
        }
        ours[id].add(r.row);
    }
    std::string md = fmt::format(
        "# {}: this machine beside {}\n\nHere: {}.\nThere: {}.\n\nFPS is the median over "
        "the cell's repetitions, with the 95% interval of the median frame time (inverted) "
        "where the rows kept their frames; the ratio is here / there (above 1: faster here), "
        "marked * where the two intervals do not overlap (a significant difference). The "
        "error is the mean rel_rmse of I_s; it should not depend on the machine beyond the "
        "GPU's rounding.\n\n| cell | FPS here | FPS there | ratio | error here | error there "
        "|\n|---|---:|---:|---:|---:|---:|\n",
        x.name, baseline.string(), machine(out), machine(baseline));
    std::vector<double> ratios;
    for (const std::string& id : order) {
        const Cells& here = ours.at(id);
        const auto it = theirs.find(id);
        if (it == theirs.end()) {
            md += fmt::format("| {} | {} | (none) | | {} | |\n", id, here.fps_text(),
                              here.error_text());
            continue;
        }
        const Cells& there = it->second;
        const double ratio = median(here.fps) / median(there.fps);
        ratios.push_back(ratio);
        const bool significant =
            here.complete && there.complete &&
            !median_interval(here.samples).overlaps(median_interval(there.samples));
        md += fmt::format("| {} | {} | {} | {:.2f}x{} | {} | {} |\n", id, here.fps_text(),
                          there.fps_text(), ratio, significant ? " *" : "", here.error_text(),
                          there.error_text());
    }
    for (const auto& [id, cells] : theirs) {
        if (!ours.contains(id)) {
            md += fmt::format("| {} | (none) | {} | | | |\n", id, cells.fps_text());
        }
    }
    if (!ratios.empty()) {
        std::sort(ratios.begin(), ratios.end());
        md += fmt::format("\nRatio over {} cells: median {:.2f}x, from {:.2f}x to {:.2f}x.\n",
                          ratios.size(), median(ratios), ratios.front(), ratios.back());
    }
    return md;
}

}  // namespace sl::experiments
