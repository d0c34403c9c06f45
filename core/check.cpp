#include "core/check.h"

#include <cstdio>
#include <cstdlib>

#include <fmt/format.h>

namespace sl::detail {

void check_failed(const char* condition, const char* file, int line, const std::string& values) {
    std::fprintf(stderr, "shaftlab: internal error: check failed at %s:%d: %s%s%s\n", file, line,
                 condition, values.empty() ? "" : " ", values.c_str());
    std::fflush(stderr);
    std::abort();
}

std::string index_values(long long index, long long size) {
    return fmt::format("(index {}, size {})", index, size);
}

}  // namespace sl::detail
