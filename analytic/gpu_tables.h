#pragma once
// The lookup tables of the light model's GLSL twin (analytic/shaders/in_scattering.glsl), made on
// the CPU from the same closed forms and quadrature as analytic/in_scattering.cpp.

#include "gl/objects.h"
#include "scenes/scene.h"

namespace sl::analytic {

// Sun et al. 2005's F(u, v) = ∫_0^v exp(-u tan ζ) dζ on u in [0, 32], v in [0, π/2], 1024², for
// in_scattering.glsl's `sun_table` at texture unit kSunTableUnit.
constexpr GLuint kSunTableUnit = 7;
gl::Texture create_sun_table();
// P(θ) = ∫_{-π/2}^θ p(-sin t) dt for the medium's phase function, 1024 samples over
// θ in [-π/2, π/2], for in_scattering.glsl's `phase_table` at texture unit kPhaseTableUnit.
constexpr GLuint kPhaseTableUnit = 6;
gl::Texture create_phase_table(const Medium& medium);

}  // namespace sl::analytic
