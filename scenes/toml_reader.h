#pragma once
// Strict reading of one TOML table (scene files, experiment files): every key read is remembered
// so that finish() rejects the rest — a misspelt key is an error naming the file, line, table and
// key, never silently ignored. Values set from the command line have no line; their errors say so.

#include <toml++/toml.h>

#include <cmath>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "core/error.h"
#include "core/suggest.h"

namespace sl {

// The largest magnitude of a scene's vector components (positions, directions, sizes, angles in
// degrees, coefficients, intensities): the GPU computes in float32, whose 7 digits leave nothing
// of a scene laid out beyond it, and whose range a product of two such values must not leave.
inline constexpr double kMaxSceneValue = 1e6;
// The smallest non-zero magnitude: float32's smallest normal number. Below it a value is a
// subnormal on the GPU and in GLM, where a direction made from it normalises to NaN.
inline constexpr double kMinSceneValue = 1.1754943508222875e-38;

// `text` as a TOML basic string literal, quotes and backslashes escaped (for files we write).
inline std::string toml_quoted(const std::string& text) {
    std::string quoted = "\"";
    for (const char c : text) {
        if (c == '"' || c == '\\') {
            quoted += '\\';
        }
        quoted += c;
    }
    return quoted + "\"";
}

// Reads the keys of one TOML table, remembering which were read so that finish() can reject the
// rest: a misspelt key is an error, never silently ignored.
class TomlTableReader {
public:
    TomlTableReader(const toml::table& table, std::string origin, std::string context)
        : table_(table), origin_(std::move(origin)), context_(std::move(context)) {}

    bool has(std::string_view key) const { return table_.contains(key); }
    const std::string& origin() const { return origin_; }
    const std::string& context() const { return context_; }

    [[noreturn]] void error(std::string_view key, const std::string& reason) const {
        const toml::node* node = table_.get(key);
        const auto line = node ? node->source().begin.line : table_.source().begin.line;
        fail("{}: {}{}: {}", where(line), prefix(), clipped(key), reason);
    }

    double number(std::string_view key, double fallback) {
        const toml::node* node = take(key);
        if (!node) {
            return fallback;
        }
        const std::optional<double> value =
            node->is_number() ? node->value<double>() : std::nullopt;
        if (!value) {
            error(key, "expected a number");
        }
        if (!std::isfinite(*value)) {
            error(key, fmt::format("value {} is not finite", *value));
        }
        if (*value != 0.0 && std::abs(*value) < kMinSceneValue) {
            error(key, fmt::format("value {:g} is below float32's smallest normal number ({:g}): "
                                   "write 0 or a larger value",
                                   *value, kMinSceneValue));
        }
        return *value;
    }
    double number(std::string_view key) {
        require(key);
        return number(key, 0.0);
    }
    // A number in [lo, hi] (open at an end when the flag says so).
    double number_in(std::string_view key, double fallback, double lo, double hi,
                     bool open_lo = false, bool open_hi = false) {
        const double v = number(key, fallback);
        if ((open_lo ? v <= lo : v < lo) || (open_hi ? v >= hi : v > hi)) {
            error(key, fmt::format("must be in {}{}, {}{}, got {}", open_lo ? '(' : '[', lo, hi,
                                   open_hi ? ')' : ']', v));
        }
        return v;
    }
    int integer_in(std::string_view key, int fallback, int lo, int hi) {
        const toml::node* node = take(key);
        if (!node) {
            return fallback;
        }
        const std::optional<int64_t> value =
            node->as_integer() ? node->value<int64_t>() : std::nullopt;
        if (!value || *value < lo || *value > hi) {
            error(key, fmt::format("expected an integer in [{}, {}]", lo, hi));
        }
        return int(*value);
    }
    glm::vec3 vec3(std::string_view key, glm::vec3 fallback) {
        const toml::node* node = take(key);
        if (!node) {
            return fallback;
        }
        const toml::array* array = node->as_array();
        if (!array || array->size() != 3) {
            error(key, "expected an array of three numbers");
        }
        glm::vec3 v;
        for (int i = 0; i < 3; ++i) {
            const std::optional<double> c = (*array)[i].value<double>();
            if (!c || !(*array)[i].is_number()) {
                error(key, "expected an array of three numbers");
            }
            if (!std::isfinite(*c)) {
                error(key, fmt::format("component {} is not finite", i));
            }
            if (*c != 0.0 && std::abs(*c) < kMinSceneValue) {
                error(key, fmt::format("component {} is {:g}: below float32's smallest normal "
                                       "number ({:g}); write 0 or a larger value",
                                       i, *c, kMinSceneValue));
            }
            if (std::abs(*c) > kMaxSceneValue) {
                error(key, fmt::format("component {} is {}: must be within ±{:g} (the GPU computes "
                                       "in float32)",
                                       i, *c, kMaxSceneValue));
            }
            v[i] = float(*c);
        }
        return v;
    }
    glm::vec3 vec3(std::string_view key) {
        require(key);
        return vec3(key, glm::vec3(0.0f));
    }
    glm::vec3 non_negative_vec3(std::string_view key, glm::vec3 fallback) {
        const glm::vec3 v = vec3(key, fallback);
        if (v.x < 0 || v.y < 0 || v.z < 0) {
            error(key, "components must not be negative");
        }
        return v;
    }
    bool boolean(std::string_view key, bool fallback) {
        const toml::node* node = take(key);
        if (!node) {
            return fallback;
        }
        if (!node->is_boolean()) {
            error(key, "expected true or false");
        }
        return *node->value<bool>();
    }
    std::string string(std::string_view key, std::string fallback) {
        const toml::node* node = take(key);
        if (!node) {
            return fallback;
        }
        if (!node->is_string()) {
            error(key, "expected a string");
        }
        return std::string(*node->value<std::string_view>());
    }
    std::string string(std::string_view key) {
        require(key);
        return string(key, "");
    }
    const toml::table* table(std::string_view key) {
        const toml::node* node = take(key);
        if (node && !node->is_table()) {
            error(key, "expected a table");
        }
        return node ? node->as_table() : nullptr;
    }
    const toml::array* array(std::string_view key) {
        const toml::node* node = take(key);
        if (node && !node->is_array()) {
            error(key, "expected an array");
        }
        return node ? node->as_array() : nullptr;
    }
    const toml::node* take(std::string_view key) {
        used_.insert(std::string(key));
        return table_.get(key);
    }
    // Every key of the table was read: an unknown one is an error naming it, the nearest known
    // key where it looks misspelt, and the keys this table takes.
    void finish() const {
        for (const auto& [key, node] : table_) {
            if (!used_.contains(std::string(key.str()))) {
                const std::string name(key.str());
                const std::vector<std::string> known(used_.begin(), used_.end());
                std::string list;
                for (const std::string& k : known) {
                    list += (list.empty() ? "" : ", ") + k;
                }
                fail("{}: {}{}: unknown key{} ({})", where(node.source().begin.line), prefix(),
                     clipped(name), did_you_mean(name, known),
                     known.empty() ? "this table takes no keys" : "known: " + list);
            }
        }
    }

private:
    // "file:line", or "file (set on the command line)" for a value that has no line.
    std::string where(toml::source_index line) const {
        return line ? fmt::format("{}:{}", origin_, line) : origin_ + " (set on the command line)";
    }
    std::string prefix() const { return context_.empty() ? "" : context_ + " "; }
    void require(std::string_view key) const {
        if (!table_.contains(key)) {
            fail("{}: {}{}: missing required key", where(table_.source().begin.line), prefix(),
                 key);
        }
    }

    const toml::table& table_;
    std::string origin_;
    std::string context_;
    std::set<std::string> used_;
};

}  // namespace sl
