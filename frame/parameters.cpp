#include "frame/parameters.h"

#include <cmath>
#include <cstdlib>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.h"
#include "core/suggest.h"
#include "core/text.h"

namespace sl::frame {

std::string Parameter::text() const {
    switch (type) {
        case Type::choice:
            return choices.at(size_t(value));
        case Type::boolean:
            return value != 0.0 ? "true" : "false";
        default:
            return fmt::format("{}", value);
    }
}

const char* Parameter::type_name() const {
    constexpr const char* kNames[] = {"integer", "real", "bool", "enum"};
    return kNames[size_t(type)];
}

size_t ParameterSet::add(Parameter parameter) {
    if (has(parameter.name)) {
        fail("method '{}' declares parameter '{}' twice", owner_, parameter.name);
    }
    parameter.value = parameter.default_value;
    all_.push_back(std::move(parameter));
    return all_.size() - 1;
}

Param<int> ParameterSet::integer(std::string name, int default_value, int min, int max,
                                 std::string description) {
    return {&all_, add({.name = std::move(name),
                        .type = Parameter::Type::integer,
                        .default_value = double(default_value),
                        .min = double(min),
                        .max = double(max),
                        .description = std::move(description)})};
}

Param<double> ParameterSet::real(std::string name, double default_value, double min, double max,
                                 std::string description) {
    return {&all_, add({.name = std::move(name),
                        .type = Parameter::Type::real,
                        .default_value = default_value,
                        .min = min,
                        .max = max,
                        .description = std::move(description)})};
}

Param<bool> ParameterSet::flag(std::string name, bool default_value, std::string description) {
    return {&all_, add({.name = std::move(name),
                        .type = Parameter::Type::boolean,
                        .default_value = default_value ? 1.0 : 0.0,
                        .min = 0.0,
                        .max = 1.0,
                        .description = std::move(description)})};
}

size_t ParameterSet::add_choice(std::string name, std::vector<std::string> choices,
                                size_t default_index, std::string description) {
    if (default_index >= choices.size()) {
        fail("method '{}' parameter '{}': default choice {} of {}", owner_, name, default_index,
             choices.size());
    }
    const double max = double(choices.size()) - 1.0;
    return add({.name = std::move(name),
                .type = Parameter::Type::choice,
                .default_value = double(default_index),
                .min = 0.0,
                .max = max,
                .description = std::move(description),
                .choices = std::move(choices)});
}

bool ParameterSet::has(const std::string& name) const {
    for (const Parameter& p : all_) {
        if (p.name == name) {
            return true;
        }
    }
    return false;
}

const Parameter& ParameterSet::find(const std::string& name) const {
    std::vector<std::string> known;
    for (const Parameter& p : all_) {
        if (p.name == name) {
            return p;
        }
        known.push_back(p.name);
    }
    fail("method '{}' has no parameter {}{} ({})", owner_, quote(name), did_you_mean(name, known),
         known.empty() ? "it has none" : fmt::format("it has: {}", fmt::join(known, ", ")));
}

void ParameterSet::set(const std::string& name, const std::string& text) {
    Parameter& p = all_[size_t(&find(name) - all_.data())];
    switch (p.type) {
        case Parameter::Type::choice:
            for (size_t i = 0; i < p.choices.size(); ++i) {
                if (p.choices[i] == text) {
                    p.value = double(i);
                    return;
                }
            }
            fail("method '{}' parameter '{}': {} is not one of {}{}", owner_, name, quote(text),
                 fmt::join(p.choices, ", "), did_you_mean(text, p.choices));
        case Parameter::Type::boolean:
            if (text == "true" || text == "on" || text == "1") {
                p.value = 1.0;
                return;
            }
            if (text == "false" || text == "off" || text == "0") {
                p.value = 0.0;
                return;
            }
            fail("method '{}' parameter '{}': {} is not a flag (true or false)", owner_, name,
                 quote(text));
        case Parameter::Type::integer:
        case Parameter::Type::real:
            break;
    }
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    const bool integral = p.type != Parameter::Type::integer || value == std::floor(value);
    if (text.empty() || *end != '\0' || !std::isfinite(value) || !integral) {
        fail("method '{}' parameter '{}': {} is not {}", owner_, name, quote(text),
             p.type == Parameter::Type::integer ? "an integer" : "a finite number");
    }
    if (value < p.min || value > p.max) {
        fail("method '{}' parameter '{}': {} is out of range [{}, {}]", owner_, name, text, p.min,
             p.max);
    }
    p.value = value;
}

}  // namespace sl::frame
