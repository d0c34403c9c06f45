#pragma once
// The sampling-plane methods (docs/design.md §3):
//   planes   Dobashi et al. 2000's view-aligned planes every dz of eye depth, clipped to the
//            influence pyramid (Mitchell 2004), shadow-map visibility per sample (Nilsson §3.1);
//   hybrid1  Nilsson's Method 1 (§5.3): every plane partitioned by the beam tree; lit pieces
//            drawn without the shadow lookup, uncertain pieces with it, unlit pieces dropped;
//   hybrid2  Nilsson's Method 2 (§5.4): the lit regions integrated in closed form
//            (analytic/region_pass.h) plus the planes' uncertain pieces only.
// The hybrids' `partition`: gpu (default) classifies each plane sample with the beam tree on
// the GPU (beamtree/shaders/classify.glsl) and draws the planes whole; cpu is Nilsson's method,
// every plane cut by the tree on the CPU each frame. hybrid2's lit regions are the boundary of
// their union (beamtree/boundary.h).
// Parameters: dz, jitter, shadow, shadow_size, partition. Statistics per frame: CPU time of
// slicing and partitioning (and their sum, cpu_ms_frame), slices, pieces of each kind (cpu),
// fragment-shader invocations of the planes.

#include <memory>

#include "frame/volume_method.h"

namespace sl::frame {
class MethodRegistry;
}

namespace sl::sampling {

enum class PlanesVariant { planes, hybrid1, hybrid2 };

// Registers `planes`, `hybrid1` and `hybrid2` (frame/method_registry.h).
void register_planes_methods(frame::MethodRegistry& registry);

}  // namespace sl::sampling
