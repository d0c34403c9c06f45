#pragma once
// `reference`: the exact CPU reference (reference/reference.h) as a volumetric method, computed
// once per scene, view and size (with a progress bar on a terminal), cached on disk under
// $SHAFTLAB_CACHE (default ~/.cache/shaftlab) by a hash of everything it depends on, and copied
// into the frame's in-scattering target. Parameters: shadow_samples, transition_tolerance.

#include <memory>

#include "frame/volume_method.h"

namespace sl::frame {
class MethodRegistry;
}

namespace sl::reference {

// Registers `reference` (frame/method_registry.h).
void register_methods(frame::MethodRegistry& registry);

}  // namespace sl::reference
