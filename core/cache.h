#pragma once
// Where shaftlab caches what is expensive to recompute (reference images, prefiltered cube-map
// chains): $SHAFTLAB_CACHE, else ~/.cache/shaftlab, else a folder under the temporary directory.

#include <filesystem>

namespace sl {

std::filesystem::path cache_directory();

}  // namespace sl
