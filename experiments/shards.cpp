#include "experiments/shards.h"

#include <fstream>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/output_files.h"
#include "core/text.h"
#include "experiments/experiment.h"
#include "experiments/rows.h"
#include "experiments/summary.h"

namespace sl::experiments {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

Shard parse_shard(const std::string& text) {
    static const std::regex pattern(R"((\d{1,6})/(\d{1,6}))");
    std::smatch match;
    if (std::regex_match(text, match, pattern)) {
        const Shard shard{std::stoi(match[1]), std::stoi(match[2])};
        if (shard.count >= 1 && shard.index >= 1 && shard.index <= shard.count) {
            return shard;
        }
    }
    fail("--shard {}: expected i/n with 1 <= i <= n, e.g. 2/4", quote(text));
}

void merge_shards(const std::vector<fs::path>& shards, const fs::path& out) {
    if (shards.empty()) {
        fail("merge: no shard directories given");
    }
    std::string effective;
    for (const fs::path& shard : shards) {
        std::ifstream file(shard / "experiment.toml", std::ios::binary);
        if (!file) {
            fail("{}: not a bench output directory (no experiment.toml)", shard.string());
        }
        std::ostringstream text;
        text << file.rdbuf();
        if (effective.empty()) {
            effective = text.str();
        } else if (text.str() != effective) {
            fail("{}: a different experiment than {} (experiment.toml differs)", shard.string(),
                 shards.front().string());
        }
    }
    // The experiment as run, re-read from the first shard's env.json (verbatim file and
    // overrides), so the summary knows its sweep.
    const fs::path env_path = shards.front() / "env.json";
    std::ifstream env_file(env_path);
    if (!env_file) {
        fail("{}: missing; was the shard run to its end?", env_path.string());
    }
    const Json env = Json::parse(env_file);
    const Json& source = env.at("experiment");
    std::vector<std::string> presets, overrides;
    for (const auto& o : source.at("overrides")) {
        const std::string text = o.get<std::string>();
        if (text.starts_with("preset ")) {
            presets.push_back(text.substr(7));
        } else {
            overrides.push_back(text);
        }
    }
    const Experiment x = parse_experiment(source.at("text").get<std::string>(),
                                          source.at("file").get<std::string>(), presets, overrides);
    claim_directory(x, out);
    size_t copied = 0;
    for (const fs::path& shard : shards) {
        for (const char* sub : {"cells", "images"}) {
            if (!fs::is_directory(shard / sub)) {
                continue;
            }
            for (const auto& entry : fs::directory_iterator(shard / sub)) {
                const std::string name = entry.path().filename().string();
                if (name.starts_with(".")) {
                    continue;
                }
                OutputFiles files(out / sub);
                files.add(name, [&](const fs::path& path) {
                    fs::copy_file(entry.path(), path, fs::copy_options::overwrite_existing);
                });
                files.commit();
                copied += sub == std::string("cells");
            }
        }
    }
    fmt::print(stderr, "merge: {} rows from {} shards into {}\n", copied, shards.size(),
               out.string());
    write_summary(x, out);
}

}  // namespace sl::experiments
