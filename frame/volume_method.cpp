#include "frame/volume_method.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.h"

namespace sl::frame {

namespace {

const std::vector<std::string> kShadowFilterNames = {"hard", "pcf", "vsm"};

class NoVolume final : public VolumeMethod {
public:
    std::string name() const override { return "none"; }
    std::string accepts() const override { return "every scene (it renders no medium)"; }
    void prepare(const Scene&) override {}
    std::unique_ptr<FrameWork> cpu_update(const Scene&, const SceneChange&) const override {
        return nullptr;
    }
    void apply_update(const Scene&, const SceneChange&, std::unique_ptr<FrameWork>) override {}
    void render(const VolumeInputs&) override {}
};

}  // namespace

std::unique_ptr<VolumeMethod> create_no_volume() {
    return std::make_unique<NoVolume>();
}

const char* to_string(ShadowFilter filter) {
    return kShadowFilterNames[size_t(filter)].c_str();
}

ShadowFilter parse_shadow_filter(const std::string& text) {
    for (size_t i = 0; i < kShadowFilterNames.size(); ++i) {
        if (kShadowFilterNames[i] == text)
            return ShadowFilter(i);
    }
    fail("unknown shadow filter {} (known: {})", quote(text), fmt::join(kShadowFilterNames, ", "));
}

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

const Parameter& VolumeMethod::find(const std::string& name) const {
    for (const Parameter& p : parameters_) {
        if (p.name == name)
            return p;
    }
    std::string known;
    for (const Parameter& p : parameters_)
        known += (known.empty() ? "" : ", ") + p.name;
    fail("method '{}' has no parameter {} ({})", this->name(), quote(name),
         known.empty() ? "it has none" : "it has: " + known);
}

const Parameter& VolumeMethod::typed(const std::string& name,
                                     std::initializer_list<Parameter::Type> types,
                                     const char* reader) const {
    const Parameter& p = find(name);
    if (std::find(types.begin(), types.end(), p.type) == types.end()) {
        fail("method '{}' parameter '{}' is {}, not read with {}()", this->name(), name,
             p.type_name(), reader);
    }
    return p;
}

double VolumeMethod::number(const std::string& name) const {
    return typed(name, {Parameter::Type::integer, Parameter::Type::real}, "number").value;
}

bool VolumeMethod::flag(const std::string& name) const {
    return typed(name, {Parameter::Type::boolean}, "flag").value != 0.0;
}

size_t VolumeMethod::choice_index(const std::string& name) const {
    return size_t(typed(name, {Parameter::Type::choice}, "choice").value);
}

const std::string& VolumeMethod::choice_name(const std::string& name) const {
    const Parameter& p = typed(name, {Parameter::Type::choice}, "choice_name");
    return p.choices.at(size_t(p.value));
}

bool VolumeMethod::has_parameter(const std::string& name) const {
    for (const Parameter& p : parameters_) {
        if (p.name == name)
            return true;
    }
    return false;
}

void VolumeMethod::declare(Parameter parameter) {
    if (parameter.type == Parameter::Type::choice) {
        parameter.min = 0;
        parameter.max = double(parameter.choices.size()) - 1;
    }
    if (parameter.type == Parameter::Type::boolean) {
        parameter.min = 0;
        parameter.max = 1;
    }
    parameter.value = parameter.default_value;
    parameters_.push_back(std::move(parameter));
}

void VolumeMethod::declare_flag(std::string name, bool default_value, std::string description) {
    declare({.name = std::move(name),
             .type = Parameter::Type::boolean,
             .default_value = default_value ? 1.0 : 0.0,
             .description = std::move(description)});
}

void VolumeMethod::declare_choice(std::string name, std::vector<std::string> choices,
                                  size_t default_index, std::string description) {
    declare({.name = std::move(name),
             .type = Parameter::Type::choice,
             .default_value = double(default_index),
             .description = std::move(description),
             .choices = std::move(choices)});
}

void VolumeMethod::declare_shadow_parameters(ShadowFilter filter) {
    declare({.name = "shadow",
             .type = Parameter::Type::choice,
             .default_value = double(filter),
             .description = "shadow map filter for mid-air visibility and surfaces",
             .choices = kShadowFilterNames});
    declare({.name = "shadow_size",
             .type = Parameter::Type::integer,
             .default_value = 2048,
             .min = 16,
             .max = 16384,
             .description = "shadow map resolution (texels per side)"});
}

ShadowSettings VolumeMethod::shadow_settings(ShadowSettings frame) const {
    if (has_parameter("shadow")) {
        frame.filter = choice<ShadowFilter>("shadow");
    }
    if (has_parameter("shadow_size")) {
        frame.map_size = int(number("shadow_size"));
    }
    return frame;
}

void VolumeMethod::set(const std::string& name, const std::string& text) {
    for (Parameter& p : parameters_) {
        if (p.name != name)
            continue;
        if (p.type == Parameter::Type::choice) {
            for (size_t i = 0; i < p.choices.size(); ++i) {
                if (p.choices[i] == text) {
                    p.value = double(i);
                    return;
                }
            }
            fail("method '{}' parameter '{}': {} is not one of {}", this->name(), name, quote(text),
                 fmt::join(p.choices, ", "));
        }
        if (p.type == Parameter::Type::boolean) {
            // By name; 1 and 0 are the spellings of the numeric flags this type replaced.
            if (text == "true" || text == "on" || text == "1") {
                p.value = 1.0;
                return;
            }
            if (text == "false" || text == "off" || text == "0") {
                p.value = 0.0;
                return;
            }
            fail("method '{}' parameter '{}': {} is not a flag (true or false)", this->name(), name,
                 quote(text));
        }
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        const bool integral = p.type != Parameter::Type::integer || value == std::floor(value);
        if (text.empty() || *end != '\0' || !std::isfinite(value) || !integral) {
            fail("method '{}' parameter '{}': {} is not {}", this->name(), name, quote(text),
                 p.type == Parameter::Type::integer ? "an integer" : "a finite number");
        }
        if (value < p.min || value > p.max) {
            fail("method '{}' parameter '{}': {} is out of range [{}, {}]", this->name(), name,
                 text, p.min, p.max);
        }
        p.value = value;
        return;
    }
    find(name);  // throws, naming the parameters the method has
}

}  // namespace sl::frame
