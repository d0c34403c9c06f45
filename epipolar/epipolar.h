#pragma once
// `epipolar`: the engine-grade shadow-map marcher: epipolar sampling (Engelhardt & Dachsbacher,
// "Epipolar sampling for shadows and crepuscular rays in participating media with single
// scattering", I3D 2010) with 1D min-max trees (Chen, Baran, Durand & Jarosz, "Real-time volumetric
// shadows using 1D min-max mipmaps", I3D 2011), as Yusov combines them ("Practical implementation
// of light scattering effects using epipolar sampling and 1D min/max binary trees", HPG 2013; GPU
// Pro 5, 2014; Intel's OutdoorLightScattering sample). Per frame, all on the GPU but the slice
// table (geometry.h):
//   coordinates  `slices` lines from the light's screen position to the image border,
//                `samples_per_slice` samples on each, with the depth under each
//                (shaders/coordinates.comp);
//   refine       samples every `max_step` and both sides of every depth discontinuity (view
//                depths further apart than `depth_threshold` of the nearer) are marched, the
//                rest interpolated (shaders/refine.comp);
//   rectify      each slice's line through the shadow map, resampled, and its 1D min-max tree
//                (shaders/rectify.comp, shaders/minmax.comp);
//   march        the marched samples, `samples` steps over the ray's interval in the cone, the
//                tree skipping runs of steps that are all lit or all dark; a lit run adds its
//                closed-form integral (lit_integral = closed_form) or its steps' densities
//                (samples) (shaders/march.comp, shaders/rectified_march.glsl);
//   interpolate  the other samples, linearly between their sources (shaders/interpolate.comp);
//   apply        every pixel from the 4 samples about it on its two slices, bilateral in view
//                depth; a pixel with none of its surface is marched directly through the frame's
//                shadow map (shaders/apply.frag).
// Every light type: a point light's faces and spot lights by their positions, a sun as its point
// at infinity (Yusov's outdoor case: the lines meet where the sun is seen, on screen or off it, or
// at the anti-solar point behind the camera, and run parallel when its beams cross the view; its
// orthographic shadow map sees every epipolar plane as one line, as a perspective map does).
// With interpolation off every pixel is marched directly: the method is then `march` with clip =
// cone (the same samples and sums). With minmax off the march tests every step against the
// rectified line (the plain march the tree must equal).
// Parameters: slices, samples_per_slice, max_step, depth_threshold, samples, lit_integral,
// minmax, interpolation, shadow, shadow_size. Statistics: the slices and samples, marched
// samples, tree lookups, fix-up pixels and samples.

#include <memory>

#include "frame/volume_method.h"

namespace sl::frame {
class MethodRegistry;
}

namespace sl::epipolar {

// Registers `epipolar` (frame/method_registry.h).
void register_methods(frame::MethodRegistry& registry);

}  // namespace sl::epipolar
