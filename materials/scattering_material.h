#pragma once
// Optical properties of translucent materials (Rohat §4.2): reduced scattering and absorption
// coefficients per RGB channel in 1/mm, and the relative index of refraction; and the stacks of
// layers a scene file coats an object with. The scene format names these, so they lie below
// scenes/; sss/ computes what they scatter. The types keep their concept's namespace.

#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

namespace sl::sss {

using dvec3 = glm::dvec3;

struct ScatteringMaterial {
    std::string name;
    dvec3 sigma_s_reduced{1.0};  // σs', 1/mm
    dvec3 sigma_a{0.0};          // σa, 1/mm
    double eta = 1.3;            // relative index of refraction (inside / outside)
    std::string source;          // where the numbers come from
};

// Rohat table 4.1 and the rest of Jensen et al. 2001's measured set (figure 5 of the paper), plus
// `jade`, which no one measured: chosen for a green stone (η of nephrite). Rohat's table prints
// apple's blue σa as 0.46; Jensen's paper has 0.046, which is what the preset holds.
const std::vector<ScatteringMaterial>& material_presets();
// The preset of that name (case-insensitive); throws sl::Error naming the known ones.
const ScatteringMaterial& material_preset(std::string_view name);

// σs' = σs (1 − g) (Rohat eq. 4.2).
dvec3 reduced_scattering(const dvec3& sigma_s, double g);
// σa(λ) = 4π Im(η) / λ (§4.2.1), per metre for λ in metres.
double absorption_from_complex_ior(double imaginary_ior, double wavelength_m);

// A stack of translucent slabs, top first; the last may be semi-infinite (thickness 0 = dipole,
// no transmittance).
struct Layer {
    ScatteringMaterial material;
    double thickness_mm = 0.0;
};

// Checks a material for rendering: finite, σs' > 0, σa ≥ 0, η > 0; throws sl::Error otherwise.
void validate(const ScatteringMaterial& material);

}  // namespace sl::sss
