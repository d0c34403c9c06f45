#pragma once
// A method as a run configures it: created by name from the registry, with the run's shadow map as
// the default of its own shadow parameters, then each NAME=VALUE setting applied. `render`,
// `animate`, the viewer and the harness all make their methods here.

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "frame/volume_method.h"

namespace sl::methods {

using Settings = std::vector<std::pair<std::string, std::string>>;

// The method `name` with the run's shadow map as the default of its own `shadow` parameters
// (when it declares them), then each (name, value) setting applied and the whole set validated
// (VolumeMethod::validate); throws sl::Error naming the method and parameter on an unknown one,
// a bad value or a combination the method refuses.
std::unique_ptr<frame::VolumeMethod> create_configured_method(const std::string& name,
                                                              const frame::ShadowSettings& run,
                                                              const Settings& settings);

// "NAME=VALUE" command-line settings split into pairs; throws sl::Error on one without '='.
Settings parse_settings(const std::vector<std::string>& name_value);

}  // namespace sl::methods
