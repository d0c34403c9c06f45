#pragma once
// The environment's light reflected by a surface, on the CPU: the two real-time paths exactly as
// ibl/shaders/ibl.glsl computes them (the GPU's oracle), and the integral they approximate,
// estimated by Monte Carlo with many samples (their oracle).

#include <functional>

#include <glm/vec3.hpp>

#include "ibl/environment.h"

namespace sl::ibl {

struct SurfacePoint {
    glm::vec3 n;  // unit normal
    glm::vec3 v;  // unit direction to the eye
    glm::vec3 albedo;
    float alpha;  // microfacet roughness
    glm::vec3 f0;
};

// ibl/shaders/ibl.glsl environment_radiance(), with the cube map's trilinear lookup.
glm::vec3 shade_environment(const LoadedEnvironment& environment, Shading shading,
                            const SurfacePoint& p);

// ∫ L(l) f(l, v)(n·l) dl over the hemisphere for the path's own BRDF: Beckmann D (eq. 2.10),
// Schlick F, the separable eq. 2.12 G and Lambert for `moschos`; GGX, height-correlated Smith,
// Schlick and Lambert weighted by 1 − (F0 A + B) for `split_sum`. L from the level-0 cube
// (bilinear). Specular and diffuse parts importance sampled (`samples` each, Hammersley).
// `visible`, when given, says whether the environment is seen in direction l (occlusion).
glm::vec3 reference_environment_radiance(const LoadedEnvironment& environment, Shading shading,
                                         const SurfacePoint& p, int samples,
                                         const std::function<bool(glm::vec3)>& visible = {});

}  // namespace sl::ibl
