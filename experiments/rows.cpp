#include "experiments/rows.h"

#include <algorithm>
#include <fstream>

#include "core/error.h"
#include "core/output_files.h"

namespace sl::experiments {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// Values of one parameter ordered as numbers when they are numbers.
bool value_less(const std::string& a, const std::string& b) {
    const auto x = parse_number(a), y = parse_number(b);
    return x && y ? *x < *y : a < b;
}

template <typename T>
size_t rank(const std::vector<T>& list, const T& value) {
    return size_t(std::find(list.begin(), list.end(), value) - list.begin());
}

}  // namespace

nlohmann::json cell_to_json(const Cell& cell) {
    nlohmann::json settings = nlohmann::json::array();
    for (const Setting& s : cell.settings) {
        settings.push_back({s.name, s.value});
    }
    return {{"scene", cell.scene},
            {"method", cell.method},
            {"width", cell.width},
            {"height", cell.height},
            {"settings", settings}};
}

Cell cell_from_json(const nlohmann::json& json) {
    try {
        Cell cell{json.at("scene").get<std::string>(),
                  json.at("method").get<std::string>(),
                  json.at("width").get<int>(),
                  json.at("height").get<int>(),
                  {}};
        for (const auto& s : json.at("settings")) {
            cell.settings.push_back({s.at(0).get<std::string>(), s.at(1).get<std::string>()});
        }
        return cell;
    } catch (const nlohmann::json::exception& e) {
        fail("not a cell description: {}", e.what());
    }
}

std::vector<StoredRow> load_rows(const Experiment& x, const fs::path& out) {
    std::vector<StoredRow> rows;
    if (!fs::is_directory(out / "cells")) {
        return rows;
    }
    for (const auto& entry : fs::directory_iterator(out / "cells")) {
        const std::string name = entry.path().filename().string();
        if (name.starts_with(".") || !name.ends_with(".json")) {
            continue;
        }
        std::ifstream file(entry.path());
        try {
            const Json json = Json::parse(file);
            rows.push_back(
                {cell_from_json(json.at("cell")), json.at("rep").get<int>(), json.at("row")});
        } catch (const std::exception& e) {
            fail("{}: not a result row: {}", entry.path().string(), e.what());
        }
    }
    // Sweep order (Experiment::cells(): scene, size, method, then each parameter in the order the
    // file lists its values, Nilsson's dz 0.5 before 0.1), then repetition. Values the file does
    // not list (equal-error probes) follow the listed ones, as numbers.
    auto key = [&](const StoredRow& r) {
        return std::tuple(rank(x.scenes, r.cell.scene),
                          rank(x.sizes, std::pair(r.cell.width, r.cell.height)),
                          rank(x.methods, r.cell.method));
    };
    std::map<std::string, std::vector<std::string>> listed;
    auto value_rank = [&](const std::string& name, const std::string& value) {
        auto found = listed.find(name);
        if (found == listed.end()) {
            found = listed.emplace(name, x.listed_values(name)).first;
        }
        const std::vector<std::string>& values = found->second;
        for (size_t i = 0; i < values.size(); ++i) {
            if (same_value(values[i], value)) {
                return i;
            }
        }
        return values.size();
    };
    std::map<std::string, size_t> swept;  // cell id → position in the sweep
    for (const Cell& cell : x.cells()) {
        swept.emplace(cell.id(), swept.size());
    }
    auto position = [&](const StoredRow& r) {
        const auto found = swept.find(r.cell.id());
        return found == swept.end() ? swept.size() : found->second;
    };
    std::sort(rows.begin(), rows.end(), [&](const StoredRow& a, const StoredRow& b) {
        if (key(a) != key(b)) {
            return key(a) < key(b);
        }
        if (position(a) != position(b)) {
            return position(a) < position(b);
        }
        const auto& s = a.cell.settings;
        const auto& t = b.cell.settings;
        for (size_t i = 0; i < std::min(s.size(), t.size()); ++i) {
            if (s[i].name != t[i].name) {
                return s[i].name < t[i].name;
            }
            if (!same_value(s[i].value, t[i].value)) {
                const size_t p = value_rank(s[i].name, s[i].value);
                const size_t q = value_rank(t[i].name, t[i].value);
                return p != q ? p < q : value_less(s[i].value, t[i].value);
            }
        }
        if (s.size() != t.size()) {
            return s.size() < t.size();
        }
        return a.rep < b.rep;
    });
    return rows;
}

std::string scene_label(const std::string& scene) {
    if (!scene.ends_with(".toml")) {
        return scene;
    }
    std::string stem = fs::path(scene).stem().string();
    if (stem.ends_with(".scene")) {
        stem.resize(stem.size() - 6);
    }
    return stem;
}

fs::path row_path(const fs::path& out, const Cell& cell, int rep) {
    return out / "cells" / fmt::format("{}.rep{}.json", cell.id(), rep);
}

void write_row(const fs::path& out, const Cell& cell, int rep, const Json& row) {
    OutputFiles rows(out / "cells");
    rows.add_text(row_path(out, cell, rep).filename().string(),
                  Json{{"cell", cell_to_json(cell)}, {"rep", rep}, {"row", row}}.dump(1) + "\n");
    rows.commit();
}

std::optional<Json> read_row(const fs::path& path) {
    std::ifstream file(path);
    if (!file) {
        return std::nullopt;
    }
    try {
        return Json::parse(file);
    } catch (const nlohmann::json::exception& e) {
        fail("{}: not a result row ({}); delete it to measure the cell again", path.string(),
             e.what());
    }
}

void claim_directory(const Experiment& x, const fs::path& out) {
    for (const char* sub : {"cells", "images"}) {
        std::error_code ec;
        fs::create_directories(out / sub, ec);
        if (ec) {
            fail("{}: cannot create: {}", (out / sub).string(), ec.message());
        }
        // Temporaries of a run that was killed mid-write.
        for (const auto& entry : fs::directory_iterator(out / sub)) {
            const std::string name = entry.path().filename().string();
            if (name.starts_with(".") && name.ends_with(".tmp")) {
                fs::remove(entry.path(), ec);
            }
        }
    }
    const fs::path marker = out / "experiment.toml";
    if (fs::exists(marker)) {
        std::ifstream file(marker, std::ios::binary);
        std::ostringstream text;
        text << file.rdbuf();
        if (text.str() != x.effective) {
            fail(
                "{} holds results of a different experiment or different overrides (see its "
                "experiment.toml); use another --out, or delete the directory",
                out.string());
        }
        return;
    }
    OutputFiles files(out);
    files.add_text("experiment.toml", x.effective);
    files.commit();
}

}  // namespace sl::experiments
