#pragma once
// Where shaftlab caches what is expensive to recompute (reference images, prefiltered cube-map
// chains): $SHAFTLAB_CACHE, else ~/.cache/shaftlab, else a folder under the temporary directory.

#include <filesystem>
#include <functional>

namespace sl {

std::filesystem::path cache_directory();

// Writes a cache file all or nothing: `write` fills a temporary beside `file`, which is renamed
// into place. A failure (sl::Error) only costs the next run the time again, so it is swallowed.
void write_cache_file(const std::filesystem::path& file,
                      const std::function<void(const std::filesystem::path&)>& write);

}  // namespace sl
