#pragma once
// `beamtree`: volume integration over the beam tree's lit regions alone (Nilsson's "Beam Tree"
// column, docs/design.md §3): every lit-region face in one draw, signed additive blending into the
// float target, G(z) in closed form (analytic/region_pass.h). Exact where the objects are their
// own bounding volumes, B̂ ⊆ B otherwise (the uncertain regions are left to the hybrids).
// Parameters: none. Statistics: the beam tree's CPU time and the region faces drawn.

#include <memory>

#include "frame/volume_method.h"

namespace sl::frame {
class MethodRegistry;
}

namespace sl::analytic {

// Registers `beamtree` (frame/method_registry.h).
void register_methods(frame::MethodRegistry& registry);

}  // namespace sl::analytic
