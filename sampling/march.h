#pragma once
// The ray-marching methods (docs/design.md §3):
//   march    Moschos' screen-space ray marcher (§3.2, algorithms 1-5): per pixel of a full, ½ or
//            ¼ resolution buffer, N samples along the eye ray clipped to the light (algorithm 4 on
//            the pyramid, or the exact cone), shadow-map visibility with dark-sample skipping,
//            jitter, the shared model or Moschos' eq. 3.1, phase animation; then depth-aware
//            upsampling, optionally through the 5x5 Gaussian of algorithm 3 or its depth-aware
//            variant.
//   hybrid3  the lit regions in closed form (the boundary of their union, beamtree/boundary.h)
//            plus the marcher inside each pixel's uncertain intervals only (per-pixel lists of
//            the uncertain surface's crossings, analytic/region_lists.h), with samples in
//            proportion to their length: N = clamp(ceil(density x length), min_samples,
//            samples). Lit and uncertain regions are disjoint: nothing is counted twice.
// Parameters: samples, resolution_scale, blur, shadow, shadow_size, jitter, clip (march),
// attenuation, optical_thickness, animate_phase (march), density, min_samples (hybrid3).
// Statistics: samples evaluated (after dark-sample skipping), buffer size, and for hybrid3 the
// beam tree's time, region faces and the pixels whose list overflowed.

#include <memory>

#include "frame/volume_method.h"

namespace sl::frame {
class MethodRegistry;
}

namespace sl::sampling {

enum class MarchVariant { march, hybrid3 };

// Registers `march` and `hybrid3` (frame/method_registry.h).
void register_march_methods(frame::MethodRegistry& registry);

}  // namespace sl::sampling
