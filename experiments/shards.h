#pragma once
// Sharded runs: `--shard i/n` runs every n-th cell of a sweep (on as many machines), and `shaftlab
// merge` joins the shards' directories into one and writes its summary.

#include <filesystem>
#include <string>
#include <vector>

namespace sl::experiments {

struct Shard {
    int index = 1;  // 1..count
    int count = 1;
};
// "i/n" with 1 <= i <= n; throws sl::Error otherwise.
Shard parse_shard(const std::string& text);

// Joins shard directories of one experiment into `out` (rows and images copied) and writes the
// summary outputs there.
void merge_shards(const std::vector<std::filesystem::path>& shards,
                  const std::filesystem::path& out);

}  // namespace sl::experiments
