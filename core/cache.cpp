#include "core/cache.h"

#include <cstdlib>

namespace sl {

std::filesystem::path cache_directory() {
    if (const char* dir = std::getenv("SHAFTLAB_CACHE"); dir && *dir) {
        return dir;
    }
    if (const char* home = std::getenv("HOME"); home && *home) {
        return std::filesystem::path(home) / ".cache" / "shaftlab";
    }
    return std::filesystem::temp_directory_path() / "shaftlab-cache";
}

}  // namespace sl
