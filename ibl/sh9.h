#pragma once
// Order-2 (nine-coefficient) spherical-harmonic projection of an environment and the irradiance it
// gives (Ramamoorthi & Hanrahan 2001, "An Efficient Representation for Irradiance Environment
// Maps"). Also the diffuse environment light of the SSS work (Rohat eq. 4.8–4.15).
//
// Basis convention: real SH in the world frame's Cartesian coordinates of a unit direction
// (x, y, z), the polar axis being world +z (not the scene's up, +y: the basis is just a basis; the
// coefficients rotate with the world, and irradiance is evaluated in the same frame). Order
// (l, m): 0:(0,0) 1:(1,−1) 2:(1,0) 3:(1,1) 4:(2,−2) 5:(2,−1) 6:(2,0) 7:(2,1) 8:(2,2), with
//   Y00 = 0.282095, Y1−1 = 0.488603 y, Y10 = 0.488603 z, Y11 = 0.488603 x,
//   Y2−2 = 1.092548 xy, Y2−1 = 1.092548 yz, Y20 = 0.315392 (3z² − 1), Y21 = 1.092548 xz,
//   Y22 = 0.546274 (x² − y²).

#include <array>

#include <glm/vec3.hpp>

#include "ibl/cube_map.h"

namespace sl::ibl {

struct Sh9 {
    std::array<glm::vec3, 9> coefficients{};  // L_lm, RGB

    // Radiance reconstructed in direction d (band-limited; may ring negative).
    glm::vec3 radiance(glm::vec3 d) const;
    // Irradiance E(n) = Σ Â_l L_lm Y_lm(n), Â = (π, 2π/3, π/4) (R&H eq. 7–8).
    glm::vec3 irradiance(glm::vec3 n) const;
};

std::array<float, 9> sh9_basis(glm::vec3 d);
// L_lm = Σ_texels L(ω) Y_lm(ω) Ω_texel with each texel's exact solid angle.
Sh9 project_sh9(const CubeMap& cube);

}  // namespace sl::ibl
