#pragma once
// The microfacet BRDF terms both shading paths use, in a local frame whose +z is the normal, and
// the split-sum DFG table (Karis 2013, "Real Shading in Unreal Engine 4").
//
// Roughness is the distribution's α throughout: Beckmann's m of Moschos eq. 2.10 and GGX's α,
// one scene value for both paths.

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "materials/ibl_settings.h"

namespace sl::ibl {

// D(h) for cos θ_h = n·h; normalised so that ∫ D(h) (n·h) dω_h = 1.
// Beckmann: Moschos eq. 2.10, e^((c² − 1)/(α² c²)) / (π α² c⁴). GGX: α² / (π ((α² − 1) c² + 1)²).
float distribution(Distribution distribution, float alpha, float n_dot_h);
// Schlick Fresnel, Moschos eq. 2.11: F0 + (1 − F0)(1 − v·h)⁵.
glm::vec3 fresnel_schlick(glm::vec3 f0, float v_dot_h);
float fresnel_schlick(float f0, float v_dot_h);
// Moschos eq. 2.12: Beckmann's rational approximation of the Smith masking term G1(v).
float beckmann_g1(float alpha, float n_dot_v);
// Exact Smith masking term of GGX, G1(v) = 2 (n·v) / (n·v + sqrt(α² + (1 − α²)(n·v)²)).
float ggx_g1(float alpha, float n_dot_v);
// Height-correlated Smith G2(v, l) for GGX (Heitz 2014, eq. 99), the split-sum path's term.
float ggx_g2(float alpha, float n_dot_v, float n_dot_l);
// The separable Smith G1(v) G1(l) with Moschos eq. 2.12 (the seed path's shadowing).
float beckmann_g2(float alpha, float n_dot_v, float n_dot_l);

// A half vector drawn with density D(h)(n·h) in the local frame from u in [0, 1)².
glm::vec3 sample_half_vector(Distribution distribution, float alpha, glm::vec2 u);

// The i-th of n Hammersley points: (i/n, radical inverse of i in base 2).
glm::vec2 hammersley(uint32_t i, uint32_t n);

// An orthonormal frame (tangent, bitangent) around unit n (Duff et al. 2017, branchless).
void orthonormal_basis(glm::vec3 n, glm::vec3& tangent, glm::vec3& bitangent);

// The split-sum environment BRDF: ∫ f(v, l)(n·l) dl = F0·A + B with Schlick's F, so
// A = ∫ (1 − Fc) f/F (n·l), B = ∫ Fc f/F (n·l), Fc = (1 − v·h)⁵. Rows: √α = j/(n − 1); columns:
// n·v = i/(n − 1) (the first column at 1e-3): texel centres on the range's ends, so that α = 0
// and 1 and n·v = 1 are looked up exactly. RG interleaved.
struct DfgTable {
    int size = 0;
    Distribution distribution = Distribution::ggx;
    std::vector<float> ab;  // size * size * 2, row j = roughness, column i = n·v

    glm::vec2 at(int i, int j) const {
        return {ab[size_t(j * size + i) * 2], ab[size_t(j * size + i) * 2 + 1]};
    }
    // Bilinear lookup, clamped; the GPU samples it at ((value (n − 1) + ½) / n) for the same.
    glm::vec2 lookup(float n_dot_v, float alpha) const;
};
// One (A, B) pair by importance sampling `samples` half vectors (Hammersley).
glm::vec2 integrate_dfg(Distribution distribution, float n_dot_v, float alpha, int samples);
DfgTable compute_dfg_table(Distribution distribution, int size = 64, int samples = 1024);

}  // namespace sl::ibl
