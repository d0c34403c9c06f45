#pragma once
// The exact CPU reference for I_s (docs/design.md §3 `reference`): for every pixel, the eye ray to
// its first hit on the true meshes (Embree), the lit intervals along it from shadow rays at many
// points with every light/shadow transition refined by bisection, and each interval integrated
// by analytic::in_scattering (closed form where one exists). Multithreaded (TBB).

#include <embree3/rtcore.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "analytic/in_scattering.h"
#include "core/image.h"
#include "scenes/scene.h"

namespace sl::reference {

struct ReferenceOptions {
    int shadow_samples = 256;            // visibility samples along each ray's lit interval
    double transition_tolerance = 1e-6;  // metres: bisection of light/shadow transitions
};

class ReferenceRenderer {
public:
    explicit ReferenceRenderer(const Scene& scene);
    ~ReferenceRenderer();
    ReferenceRenderer(const ReferenceRenderer&) = delete;
    ReferenceRenderer& operator=(const ReferenceRenderer&) = delete;

    // I_s for the ray up to distance t_max (its first hit).
    analytic::dvec3 in_scattering(const analytic::EyeRay& ray, double t_max,
                                  const ReferenceOptions& options) const;
    // Distance to the first hit on the scene's meshes, or `far` when there is none.
    double first_hit(const analytic::EyeRay& ray, double far) const;
    bool occluded(const analytic::dvec3& from, const analytic::dvec3& to) const;
    // Whether anything lies on the ray from `from` along the unit `direction` (a directional
    // light's shadow ray, out of the scene).
    bool occluded_towards(const analytic::dvec3& from, const analytic::dvec3& direction) const;
    // The first surface the ray hits before `far`: its distance, object (index into
    // Scene::objects) and the mesh's interpolated normal in world space, turned towards the ray's
    // origin like the GPU's two-sided shading.
    struct SurfaceHit {
        double t = 0;
        int object = -1;
        glm::vec3 normal{0.0f};
    };
    std::optional<SurfaceHit> first_surface(const analytic::EyeRay& ray, double far) const;

    // I_s of every pixel of the scene's camera at the given size (rows top to bottom); `progress`
    // receives the fraction done.
    Image render(int width, int height, const ReferenceOptions& options,
                 const std::function<void(double)>& progress = {}) const;

private:
    RTCRayHit intersect(const analytic::EyeRay& ray, double far) const;

    const Scene& scene_;
    RTCDevice device_ = nullptr;
    RTCScene rtc_scene_ = nullptr;
    RTCScene shadow_scene_ = nullptr;  // the shadow casters only (rtc_scene_ when all are)
};

// Per pixel of the scene's camera at width x height (rows top to bottom), 1 where the rasterized
// surface and the reference's first hit are the same: the distance along the pixel's eye ray to
// the surface the depth buffer holds (`window_depth`, [0, 1], 1 where nothing was drawn) and to
// the first hit of its ray cast (the camera's far plane where none) within 1e-3 of the larger.
// Where they differ (a silhouette the rasterizer gives to another surface than the ray through
// the pixel centre meets), a method and the reference integrate different intervals, and the
// pixel is left out of the score (docs/harness.md, "Scoring").
std::vector<uint8_t> same_surface_pixels(const Scene& scene, int width, int height,
                                         const std::vector<float>& window_depth);

// A 64-bit hash of everything the reference image depends on (scene geometry, camera, light,
// medium, size, options), naming its cache file.
uint64_t reference_key(const Scene& scene, int width, int height, const ReferenceOptions& options);

}  // namespace sl::reference
