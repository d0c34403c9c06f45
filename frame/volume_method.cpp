#include "frame/volume_method.h"

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
    if (type == Type::choice)
        return choices.at(size_t(value));
    return fmt::format("{}", value);
}

double VolumeMethod::parameter(const std::string& name) const {
    for (const Parameter& p : parameters_) {
        if (p.name == name)
            return p.value;
    }
    fail("method '{}' has no parameter {}", this->name(), quote(name));
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
    parameter.value = parameter.default_value;
    parameters_.push_back(std::move(parameter));
}

void VolumeMethod::declare_shadow_parameters() {
    declare({.name = "shadow",
             .type = Parameter::Type::choice,
             .default_value = double(ShadowFilter::pcf),
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
        frame.filter = ShadowFilter(int(parameter("shadow")));
    }
    if (has_parameter("shadow_size")) {
        frame.map_size = int(parameter("shadow_size"));
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
    std::string known;
    for (const Parameter& p : parameters_)
        known += (known.empty() ? "" : ", ") + p.name;
    fail("method '{}' has no parameter {} ({})", this->name(), quote(name),
         known.empty() ? "it has none" : "it has: " + known);
}

}  // namespace sl::frame
