#include "core/cache.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>

#include "core/error.h"

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

void write_cache_file(const std::filesystem::path& file,
                      const std::function<void(const std::filesystem::path&)>& write) {
    std::error_code ec;
    std::filesystem::create_directories(file.parent_path(), ec);
    const std::filesystem::path temporary = file.string() + fmt::format(".{}.tmp", getpid());
    try {
        write(temporary);
        std::filesystem::rename(temporary, file, ec);
    } catch (const Error&) {
    }
    std::filesystem::remove(temporary, ec);
}

}  // namespace sl
