#include "methods/configured_method.h"

#include "core/error.h"
#include "core/text.h"
#include "methods/registry.h"

namespace sl::methods {

Settings parse_settings(const std::vector<std::string>& name_value) {
    Settings settings;
    for (const std::string& setting : name_value) {
        const size_t equals = setting.find('=');
        if (equals == std::string::npos || equals == 0) {
            fail("--set {}: expected NAME=VALUE", quote(setting));
        }
        settings.emplace_back(setting.substr(0, equals), setting.substr(equals + 1));
    }
    return settings;
}

std::unique_ptr<frame::VolumeMethod> create_configured_method(const std::string& name,
                                                              const frame::ShadowSettings& run,
                                                              const Settings& settings) {
    std::unique_ptr<frame::VolumeMethod> method = create_volume_method(name);
    if (method->has_parameter("shadow")) {
        method->set("shadow", frame::to_string(run.filter));
        method->set("shadow_size", std::to_string(run.map_size));
    }
    for (const auto& [parameter, value] : settings) {
        method->set(parameter, value);
    }
    method->validate();
    return method;
}

}  // namespace sl::methods
