#pragma once
// The one exception type for bad input and failed operations. Its message is a single line that
// names the file or key at fault and why; the CLI prints it and exits non-zero. The message is
// made printable (core/text.h) whatever bytes went into it; a value echoed from user input should
// also go through quote() where it is formatted, so that it is truncated.

#include <fmt/format.h>

#include <stdexcept>
#include <string>

#include "core/text.h"

namespace sl {

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(printable(message)) {}
};

template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
    throw Error(fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace sl
