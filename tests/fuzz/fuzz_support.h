#pragma once
// Shared by the libFuzzer targets (tests/fuzz/*_fuzzer.cpp, built by scripts/fuzz.sh with
// AddressSanitizer and UndefinedBehaviorSanitizer): the property every loader must keep is that
// any input either loads or throws sl::Error (one clear message). Any other exception, a crash,
// a sanitizer report, a leak, a timeout or running out of memory is a finding.

#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "core/error.h"

namespace sl::fuzz {

inline bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The input as a file of the given extension (loaders that take a path), in a per-process
// scratch folder that stays for the run.
inline std::filesystem::path write_input(const uint8_t* data, size_t size, const char* extension) {
    static const std::filesystem::path dir = [] {
        const char* tmp = std::getenv("TMPDIR");
        std::filesystem::path d = std::filesystem::path(tmp ? tmp : "/tmp") /
                                  ("shaftlab-fuzz-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    const std::filesystem::path path = dir / (std::string("input") + extension);
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (!file) {
        std::abort();
    }
    if (size > 0 && std::fwrite(data, 1, size, file) != size) {
        std::abort();
    }
    std::fclose(file);
    return path;
}

// Runs `load`; sl::Error is the expected answer to bad input. Its message must be one line of
// printable text (user bytes quoted safely), else the target aborts.
template <typename Load>
int expect_load_or_error(Load&& load) {
    try {
        load();
    } catch (const Error& e) {
        for (const char c : std::string_view(e.what())) {
            const auto u = static_cast<unsigned char>(c);
            if (u < 0x20 || u == 0x7f) {
                std::fprintf(stderr, "error message has a control byte 0x%02x: %s\n", u, e.what());
                std::abort();
            }
        }
    }
    return 0;
}

}  // namespace sl::fuzz
