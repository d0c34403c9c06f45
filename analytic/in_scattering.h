#pragma once
// The in-scattered radiance I_s along an eye ray (Nilsson eq. 2.7, DESIGN.md §1), in C++: the
// integrand e(z), the part of a ray inside the spot light's exact cone and range, and the integral
// of e over a lit interval in closed form where one exists:
//   simplified, isotropic       Nilsson eq. 2.17
//   physical, isotropic         Sun, Ramamoorthi, Narasimhan & Nayar 2005: A0 F(A1, ξ)
//   anisotropic, pure 1/(a1 r²) (σs I / (a1 h)) ∫ p dθ  (simplified with a0 = 0)
// and by adaptive quadrature otherwise (a smooth cone edge, anisotropic physical, ...).
// Visibility is the caller's: the interval given is taken as unshadowed.

#include <glm/vec3.hpp>

#include "scenes/scene.h"

namespace sl::analytic {

using glm::dvec3;

struct EyeRay {
    dvec3 origin;
    dvec3 direction;  // unit length
};

struct Interval {
    double begin = 0.0;
    double end = 0.0;
    bool empty() const { return !(end > begin); }
};

// e(z) per channel at distance z along the ray, light cone factor and range included.
dvec3 scattering_density(const EyeRay& ray, double z, const SpotLight& light, const Medium& medium);

// The points of the ray within [0, t_max] inside the light's exact (convex) cone and between its
// near and far range along the axis: one interval, possibly empty.
Interval light_interval(const EyeRay& ray, const SpotLight& light, double t_max);

// ∫ e(z) dz over [z0, z1] ∩ light_interval, the whole of it taken as visible.
dvec3 in_scattering(const EyeRay& ray, double z0, double z1, const SpotLight& light,
                    const Medium& medium);

}  // namespace sl::analytic
