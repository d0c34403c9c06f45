#pragma once
// The one exception type for bad input and failed operations. Its message is a single line that
// names the file or key at fault and why; the CLI prints it and exits non-zero.

#include <fmt/format.h>

#include <stdexcept>
#include <string>

namespace sl {

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
    throw Error(fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace sl
