#include "experiments/csv.h"

#include <algorithm>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace sl::experiments {

namespace {

template <typename T>
size_t rank(const std::vector<T>& list, const T& value) {
    return size_t(std::find(list.begin(), list.end(), value) - list.begin());
}

}  // namespace

using Json = nlohmann::ordered_json;

std::string csv_field(const Json& value) {
    if (value.is_null()) {
        return "";
    }
    if (value.is_number_float()) {
        return fmt::format("{}", value.get<double>());
    }
    if (!value.is_string()) {
        return value.dump();
    }
    std::string text = value.get<std::string>();
    if (text.find_first_of(",\"\n") == std::string::npos) {
        return text;
    }
    std::string quoted = "\"";
    for (const char c : text) {
        quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    }
    return quoted + "\"";
}

std::string results_csv(const std::vector<StoredRow>& rows) {
    // Columns: the fixed ones in this order, then per family in first-seen order.
    static const std::vector<std::string> head = {
        "experiment", "cell",   "scene", "method",          "width",       "height",      "params",
        "rep",        "frames", "fps",   "frame_ms_median", "frame_ms_p5", "frame_ms_p95"};
    static const std::vector<std::string> middle = {"rel_rmse",
                                                    "max_abs",
                                                    "psnr",
                                                    "unscored_pixels",
                                                    "ray_frac_lit",
                                                    "ray_frac_uncertain",
                                                    "ray_frac_unlit",
                                                    "volume_frac_lit",
                                                    "volume_frac_uncertain",
                                                    "volume_frac_unlit",
                                                    "lit_crossings",
                                                    "lit_crossings_visible",
                                                    "uncertain_span_ratio",
                                                    "beams",
                                                    "region_faces",
                                                    "samples_or_slices",
                                                    "image"};
    // Series (an animation's per_frame, the frame times) go to frames.csv, not here.
    std::vector<std::string> seen;
    for (const StoredRow& r : rows) {
        for (const auto& [key, value] : r.row.items()) {
            if (!value.is_structured() && std::find(seen.begin(), seen.end(), key) == seen.end()) {
                seen.push_back(key);
            }
        }
    }
    std::vector<std::string> columns = head;
    columns.insert(columns.begin() + 3, "scene_file");
    auto family = [&](const std::string& prefix) {
        for (const std::string& key : seen) {
            if (key.starts_with(prefix) && rank(columns, key) == columns.size()) {
                columns.push_back(key);
            }
        }
    };
    family("gpu_ms_");
    family("cpu_ms_");
    columns.insert(columns.end(), middle.begin(), middle.end());
    family("stat_");
    family("param_");
    family("");
    std::string csv = fmt::format("{}\n", fmt::join(columns, ","));
    for (const StoredRow& r : rows) {
        std::vector<std::string> fields;
        for (const std::string& column : columns) {
            // The scene by its name (a scene file by its stem), the file in scene_file.
            if (column == "scene" || column == "scene_file") {
                const std::string scene = r.cell.scene;
                fields.push_back(csv_field(Json(column == "scene"          ? scene_label(scene)
                                                : scene.ends_with(".toml") ? scene
                                                                           : std::string())));
                continue;
            }
            fields.push_back(r.row.contains(column) ? csv_field(r.row.at(column)) : "");
        }
        csv += fmt::format("{}\n", fmt::join(fields, ","));
    }
    return csv;
}

std::string frames_csv(const std::vector<StoredRow>& rows) {
    static const std::vector<std::string> series = {"time_s",   "frame_ms",      "update_ms",
                                                    "apply_ms", "wait_ms",       "draw_ms",
                                                    "gpu_ms",   "gpu_ms_volume", "rel_rmse"};
    std::string csv =
        fmt::format("cell,scene,method,width,height,params,rep,frame,{}\n", fmt::join(series, ","));
    for (const StoredRow& r : rows) {
        if (!r.row.contains("per_frame")) {
            continue;
        }
        const Json& f = r.row.at("per_frame");
        const Json& frames = f.at("frame");
        for (size_t i = 0; i < frames.size(); ++i) {
            std::vector<std::string> fields = {csv_field(r.row.at("cell")),
                                               csv_field(Json(scene_label(r.cell.scene))),
                                               r.cell.method,
                                               std::to_string(r.cell.width),
                                               std::to_string(r.cell.height),
                                               csv_field(Json(r.cell.settings_text())),
                                               std::to_string(r.rep),
                                               frames[i].dump()};
            for (const std::string& name : series) {
                fields.push_back(f.contains(name) && i < f[name].size() ? csv_field(f[name][i])
                                                                        : "");
            }
            csv += fmt::format("{}\n", fmt::join(fields, ","));
        }
    }
    return csv;
}

}  // namespace sl::experiments
