#pragma once
// The exact reference for image-based lighting: per pixel, the eye ray's first hit (Embree) and
// the environment's light reflected there by the shading path's own BRDF, integrated by Monte
// Carlo over the level-0 cube (ibl/shading.h reference_environment_radiance); optionally with
// each sample's visibility (other objects, the floor, hide the environment, which no real-time
// path models). Background pixels see the environment. No spot light, no medium: compared with
// the GPU's surface radiance of the same scene with both turned off (environment_only_scene).

#include <vector>

#include "core/image.h"
#include "ibl/environment.h"
#include "scenes/scene.h"

namespace sl::reference {

struct EnvironmentReferenceOptions {
    int samples = 1024;      // per pixel, for each of the specular and diffuse parts
    bool occlusion = false;  // trace each sample's visibility
};

// `scene` with its spot light off and a clear medium: the surface pass then shows the
// environment's light alone.
Scene environment_only_scene(const Scene& scene);

// `object_ids`, when given, receives each pixel's object index (-1: the environment).
Image render_environment_reference(const Scene& scene, const ibl::LoadedEnvironment& environment,
                                   int width, int height,
                                   const EnvironmentReferenceOptions& options,
                                   std::vector<int>* object_ids = nullptr);

}  // namespace sl::reference
