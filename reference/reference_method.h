#pragma once
// `reference`: the exact CPU reference (reference/reference.h) as a volumetric method, computed
// once per scene, view and size (with a progress bar on a terminal), cached on disk under
// $SHAFTLAB_CACHE (default ~/.cache/shaftlab) by a hash of everything it depends on, and copied
// into the frame's in-scattering target. Parameters: shadow_samples, transition_tolerance.

#include <memory>

#include "frame/volume_method.h"

namespace sl::reference {

std::unique_ptr<frame::VolumeMethod> create_reference_method();

}  // namespace sl::reference
