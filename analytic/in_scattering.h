#pragma once
// The in-scattered radiance I_s along an eye ray (Nilsson eq. 2.7, docs/design.md §1), in C++: the
// integrand e(z), the part of a ray inside the spot light's exact cone and range, and the integral
// of e over a lit interval in closed form (in_scattering.cpp derives each):
//   simplified, isotropic       Nilsson eq. 2.17
//   simplified, anisotropic     σs I / (a1 H) R(κ, β): the phase function's integral in one angle
//                               β, with H² = h² + a0/a1 and κ = h / H
//   physical, any phase         Sun, Ramamoorthi, Narasimhan & Nayar 2005 generalised:
//                               2 σs I e^(-σt z_s) / h · F_p(σt h, ξ), F_p(u, v) =
//                               ∫_0^v exp(-u tan ζ) p(cos 2ζ) dζ (the scattering angle is 2ζ)
// and by adaptive quadrature of e(z) where none holds (a ray through the light, a1 = 0 with an
// anisotropic phase function). A smooth cone edge (eq. 2.9's falloff option) multiplies e by the
// cone factor, which depends on the angle to the axis, not on the angle variable: in_scattering
// integrates it by quadrature, and in_scattering_pieces gives the GPU's approximation of it.
// Visibility is the caller's: the interval given is taken as unshadowed.
//
// Conditioning. The GPU evaluates an antiderivative G(z) per fragment and sums
// ±G(z) in float32, so G must stay of the size of what it integrates. Anchored behind the eye,
// G loses every digit where the light is behind the eye and the ray points away from it (γ -> π):
// the ray then spans a sliver of the angle variable next to its end (ζ -> π/2 in Sun's form,
// β -> π/2 in R), 1/h times smaller than what G holds, and a table in that angle cannot resolve
// it either (rings and a blob of up to 4x the image's peak). With x = z - z_s and
// r² = x² + h², q = x + r = h tan ζ (q = h² / (r - x) for x < 0, without cancellation):
//   ∫_z^∞ e dz = 2 σs I σt e^(-σt z_s) K(σt h, σt q),
//   K(u, s) = ∫_s^∞ e^(-s') p(c) / (u² + s'²) ds', c = cos α = (u² - s'²) / (u² + s'²),
// whose tail is well conditioned in a = u / s = h / q and s: it is tabulated as
// T(a, b) = s (1 + s) e^s K(a s, s) on (sqrt(a), b = sqrt(s / (1 + s))), bounded at both ends,
// and the tail is 2 σs I e^(-σt (z + r)) T / (q (1 + σt q)): no 1/h, no e^(-σt z_s) alone. A ray
// whose lit span lies past its closest approach (z_s <= span start) anchors G at z = +∞ with that
// tail; the others anchor it at z = -∞ (for those the closest approach lies in the span, where
// h >= near, or beyond it, toward the light, where the front table's first cells are exact).
// The simplified model's R gets its complement from β = π/2 likewise, and the angles are taken
// as atan2(h, ±x). The GLSL twin adds the part of a table cell below the point by Gauss
// quadrature of the integrand instead of interpolating it (in_scattering.glsl).

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

// The cosine of the scattering angle in the simplified model's angle variable β (x = H tan β,
// κ = h / H; in_scattering.cpp derives it): -sin β / sqrt(κ² cos² β + sin² β), 0 at κ = β = 0.
double simplified_cos_alpha(double kappa, double beta);

// e(z) per channel at distance z along the ray, light cone factor and range included (for
// parallel beams: the box, and E T(s) in place of I T(r) / r²).
dvec3 scattering_density(const EyeRay& ray, double z, const SpotLight& light, const Medium& medium);
// The same for a point light (no cone; its range is the shell between its cubes).
dvec3 scattering_density(const EyeRay& ray, double z, const PointLight& light,
                         const Medium& medium);

// The points of the ray within [0, t_max] inside the light's exact (convex) cone and between its
// near and far range along the axis: one interval, possibly empty.
Interval light_interval(const EyeRay& ray, const SpotLight& light, double t_max);
// light_interval of a pyramid (SpotShape::pyramid): inside its four sides and the range.
Interval pyramid_interval(const EyeRay& ray, const SpotLight& light, double t_max);
// The parts of the ray within [0, t_max] between a point light's near and far cubes (at most
// two, in order); returns how many.
int point_light_intervals(const EyeRay& ray, const PointLight& light, double t_max,
                          Interval out[2]);
// The same for a cone of another half-angle (radians) about the light's axis.
Interval cone_interval(const EyeRay& ray, const SpotLight& light, double half_angle, double t_max);

// Pieces of the smooth falloff's shell (the cone minus its inner cone of half-angle
// cone - falloff, where the factor is 1) along a ray, each shell interval cut into this many
// equal parts in z. in_scattering_pieces weights each part's closed form by the cone factor at its
// middle (analytic/shaders/in_scattering.glsl does the same).
constexpr int kFalloffPieces = 16;

// ∫ e(z) dz over [z0, z1] ∩ light_interval, the whole of it taken as visible.
dvec3 in_scattering(const EyeRay& ray, double z0, double z1, const SpotLight& light,
                    const Medium& medium);

// ∫ e(z) dz of a point light over [z0, z1] within its range, the whole of it taken as visible:
// the spot light's closed forms without the cone (point_light_intervals cut the ray).
dvec3 in_scattering(const EyeRay& ray, double z0, double z1, const PointLight& light,
                    const Medium& medium);

// The closed forms above for a hard cone edge (the scene's falloff ignored), over [z0, z1] ∩
// light_interval. Parallel beams (SpotLight::parallel, a directional light) have their own: the
// scattering angle is constant and the light's path s in the medium linear in z, so
//   physical    σs p(cos α) E e^(-σt (a·(O - P))) (e^(-k z0) - e^(-k z1)) / k, k = σt (1 + a·V)
//   simplified  σs p(cos α) E (z1 - z0).
dvec3 in_scattering_hard_edge(const EyeRay& ray, double z0, double z1, const SpotLight& light,
                              const Medium& medium);

// in_scattering with a smooth falloff approximated as the GPU does: the closed form of the hard
// edge over the inner cone, and over each of the shell's pieces times the cone factor at the
// piece's middle (midpoint product rule, error O(kFalloffPieces^-2), measured in
// results/analytic_media.md). Equals in_scattering for a hard edge.
dvec3 in_scattering_pieces(const EyeRay& ray, double z0, double z1, const SpotLight& light,
                           const Medium& medium, int pieces = kFalloffPieces);

}  // namespace sl::analytic
