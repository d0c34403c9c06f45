#include "materials/scattering_material.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>

#include "core/error.h"

namespace sl::sss {

namespace {

bool same_name(std::string_view a, std::string_view b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) ==
                      std::tolower(static_cast<unsigned char>(y));
           });
}

bool finite(const dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

const std::vector<ScatteringMaterial>& material_presets() {
    static const std::vector<ScatteringMaterial> presets = [] {
        const std::string rohat = "Rohat table 4.1 (Jensen et al. 2001)";
        const std::string jensen = "Jensen et al. 2001";
        return std::vector<ScatteringMaterial>{
            {"apple", {2.29, 2.39, 1.97}, {0.0030, 0.0034, 0.046}, 1.3, rohat},
            {"marble", {2.19, 2.62, 3.00}, {0.0021, 0.0041, 0.0071}, 1.5, rohat},
            {"potato", {0.68, 0.70, 0.55}, {0.0024, 0.0090, 0.12}, 1.3, rohat},
            {"skimmilk", {0.70, 1.22, 1.90}, {0.0014, 0.0025, 0.0142}, 1.3, rohat},
            {"spectralon", {11.6, 20.4, 14.9}, {0.0, 0.0, 0.0}, 1.3, rohat},
            {"wholemilk", {2.55, 3.21, 3.77}, {0.0011, 0.0024, 0.014}, 1.3, rohat},
            {"chicken1", {0.15, 0.21, 0.38}, {0.015, 0.077, 0.19}, 1.3, jensen},
            {"chicken2", {0.19, 0.25, 0.32}, {0.018, 0.088, 0.20}, 1.3, jensen},
            {"cream", {7.38, 5.47, 3.15}, {0.0002, 0.0028, 0.0163}, 1.3, jensen},
            {"ketchup", {0.18, 0.07, 0.03}, {0.061, 0.97, 1.45}, 1.3, jensen},
            {"skin1", {0.74, 0.88, 1.01}, {0.032, 0.17, 0.48}, 1.3, jensen},
            {"skin2", {1.09, 1.59, 1.79}, {0.013, 0.070, 0.145}, 1.3, jensen},
            {"jade",
             {0.9, 1.1, 0.8},
             {0.12, 0.012, 0.09},
             1.61,
             "shaftlab (not measured): green translucent stone, η of nephrite"},
        };
    }();
    return presets;
}

const ScatteringMaterial& material_preset(std::string_view name) {
    for (const ScatteringMaterial& m : material_presets()) {
        if (same_name(m.name, name)) {
            return m;
        }
    }
    std::string known;
    for (const ScatteringMaterial& m : material_presets()) {
        known += (known.empty() ? "" : ", ") + m.name;
    }
    fail("unknown translucent material {} (known: {})", quote(name), known);
}

dvec3 reduced_scattering(const dvec3& sigma_s, double g) {
    return sigma_s * (1.0 - g);  // eq. 4.2
}

double absorption_from_complex_ior(double imaginary_ior, double wavelength_m) {
    if (!(wavelength_m > 0.0) || !(imaginary_ior >= 0.0)) {
        fail("absorption from a complex index needs λ > 0 and Im(η) ≥ 0 (got λ = {}, Im = {})",
             wavelength_m, imaginary_ior);
    }
    return 4.0 * std::numbers::pi * imaginary_ior / wavelength_m;  // §4.2.1
}

void validate(const ScatteringMaterial& m) {
    if (!finite(m.sigma_s_reduced) || !finite(m.sigma_a) || !std::isfinite(m.eta)) {
        fail("translucent material '{}': coefficients must be finite", m.name);
    }
    if (!(std::min({m.sigma_s_reduced.x, m.sigma_s_reduced.y, m.sigma_s_reduced.z}) > 0.0)) {
        fail("translucent material '{}': reduced scattering σs' must be > 0 in every channel",
             m.name);
    }
    if (std::min({m.sigma_a.x, m.sigma_a.y, m.sigma_a.z}) < 0.0) {
        fail("translucent material '{}': absorption σa must be ≥ 0", m.name);
    }
    if (!(m.eta > 0.0)) {
        fail("translucent material '{}': index of refraction must be > 0", m.name);
    }
}

}  // namespace sl::sss
