#include "gl/volume_method.h"

#include <cmath>
#include <cstdlib>

#include "core/error.h"

namespace sl::gl {

double VolumeMethod::parameter(const std::string& name) const {
    for (const Parameter& p : parameters_) {
        if (p.name == name)
            return p.value;
    }
    fail("method '{}' has no parameter '{}'", this->name(), name);
}

void VolumeMethod::declare(Parameter parameter) {
    parameter.value = parameter.default_value;
    parameters_.push_back(std::move(parameter));
}

void VolumeMethod::set(const std::string& name, const std::string& text) {
    for (Parameter& p : parameters_) {
        if (p.name != name)
            continue;
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        const bool integral = p.type != Parameter::Type::integer || value == std::floor(value);
        if (text.empty() || *end != '\0' || !std::isfinite(value) || !integral) {
            fail("method '{}' parameter '{}': '{}' is not {}", this->name(), name, text,
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
    fail("method '{}' has no parameter '{}' ({})", this->name(), name,
         known.empty() ? "it has none" : "it has: " + known);
}

}  // namespace sl::gl
