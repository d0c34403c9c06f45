#pragma once
// The volumetric methods by name: every method is created from here, and the renderer, the
// harness and the viewer know methods only through frame::VolumeMethod. A method lives in its
// family's folder, which adds it to the table (frame/method_registry.h).

#include <memory>
#include <string>
#include <vector>

#include "frame/volume_method.h"

namespace sl::methods {

// The methods that exist, in display order.
std::vector<std::string> volume_method_names();
// Throws sl::Error naming the known methods when `name` is not one of them.
std::unique_ptr<frame::VolumeMethod> create_volume_method(const std::string& name);

}  // namespace sl::methods
