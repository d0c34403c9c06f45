#pragma once
// The diffusion approximation of subsurface transport (Rohat §3.4, §4.2.2, §4.3): the dipole
// (Jensen et al. 2001) and the multipole (Donner & Jensen 2005) in physical units, millimetres
// and 1/mm, per colour channel; the splat radius r_max (eq. 4.3); profiles tabulated the way the
// GPU reads them (§5.1, §5.2.2).

#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "materials/scattering_material.h"

namespace sl::sss {

// Average diffuse Fresnel reflectance F_dr(η), Egan & Hilgeman's polynomial (§3.4.1).
double fresnel_diffuse_reflectance(double eta);
// Groenhuis' boundary term A = (1 + F_dr) / (1 − F_dr) (§3.4.1).
double boundary_term(double eta);

// The diffusion properties of one channel (§4.2.2): constant per material, computed once.
struct Diffusion {
    double sigma_t_reduced = 1.0;  // σt' = σs' + σa
    double sigma_tr = 0.0;         // √(3 σt' σa)
    double albedo_reduced = 1.0;   // α' = σs' / σt'
    double D = 1.0 / 3.0;          // 1 / (3 σt')
    double A = 1.0;                // boundary term
    double z_r = 1.0;              // real source depth 1/σt'
    double z_v = 1.0;              // virtual source height z_r + 4AD
    static Diffusion of(double sigma_s_reduced, double sigma_a, double eta);
};

// One Diffusion per channel.
struct RgbDiffusion {
    Diffusion channel[3];
    static RgbDiffusion of(const ScatteringMaterial& material);
    const Diffusion& operator[](int c) const { return channel[c]; }
};

// The dipole's diffuse reflectance R_d(r), 1/mm² (§3.4.1).
double dipole_rd(double r, const Diffusion& d);
dvec3 dipole_rd(double r, const RgbDiffusion& d);
// Its closed-form integral over the plane, ∫ R_d(r) 2πr dr (Jensen et al. 2001, eq. 6).
double total_diffuse_reflectance(const Diffusion& d);

// Multipole reflectance R(r, d) and transmittance T(r, d) of a slab of thickness d (eq. 3.5,
// 3.6), summing the dipole pairs i = −n..n. Transmittance distances are measured to the bottom
// face, √(r² + (d − z)²) (Donner & Jensen 2005; the seed's eq. 3.6 repeats the reflectance
// distances).
struct ReflectanceTransmittance {
    double R = 0.0;
    double T = 0.0;
};
ReflectanceTransmittance multipole(double r, double thickness, const Diffusion& d, int pairs = 10);

// Composite Simpson's rule over [a, b] with `samples` intervals (made even), listing 5.1.
double simpson(const std::function<double(double)>& f, double a, double b, int samples);

// The splat radius r_max of eq. 4.3: the smallest r whose tail ∫_r^∞ R_d / ∫_0^∞ R_d is below
// epsilon, per listing 5.1 (composite Simpson, r_inf = max(100 mm, 50 z_v)), over all channels.
// `area_weighted` integrates R_d 2πr dr instead of the seed's R_d dr (the tail of the reflected
// flux rather than of the profile).
double splat_radius(const RgbDiffusion& d, double epsilon = 0.01, bool area_weighted = false);

// A radial profile tabulated for a 1D texture: texel i holds the value at r = i r_max/(size−1)
// and the last texel is zero, so that a clamped, linearly filtered lookup at u = r/r_max
// fades to and stays at zero beyond r_max (§5.1.1, §5.2.2).
struct RadialProfile {
    double r_max = 1.0;  // mm
    std::vector<glm::vec3> texels;
    // What the GPU returns for distance r (mm): linear interpolation, clamped.
    glm::vec3 lookup(double r) const;
};
RadialProfile tabulate_dipole(const RgbDiffusion& d, double r_max, int size = 512);

// Multipole R and T tabulated over radius (width) and thickness (height), d in [d_min, d_max];
// the last column is zero as in the 1D profile.
struct SlabProfiles {
    double r_max = 1.0;  // mm
    double d_min = 0.0, d_max = 1.0;
    int width = 0, height = 0;
    std::vector<glm::vec3> R, T;  // row-major, row = thickness
    // Bilinear, clamped, as the GPU reads them.
    glm::vec3 lookup_R(double r, double d) const;
    glm::vec3 lookup_T(double r, double d) const;
};
SlabProfiles tabulate_multipole(const RgbDiffusion& d, double r_max, double d_min, double d_max,
                                int width = 256, int height = 64, int pairs = 10);

// A radial profile averaged over a disk of radius rho (mm) around the source: what a sample that
// stands for a patch of that radius delivers at distance r, with its integral over the plane
// unchanged. Point samples ~1 mm apart alias the dipole's peak (width ~ z_r, 0.4 mm in marble)
// into bright dots; the seed has no such filter. `profile` is evaluated at r in [0, r_max + rho];
// the result has `texels` values at r = i r_max/(texels − 1), the last one zero.
std::vector<glm::vec3> disk_average(const std::function<glm::vec3(double)>& profile, double r_max,
                                    int texels, double rho);

// The footprint radii tabulated per material: level k holds rho_k = rho_max (k/(levels − 1))²,
// level 0 the plain profile; a sample reads between the two levels around its own rho.
struct FootprintLevels {
    int levels = 8;
    double rho_max = 1.0;  // mm
    double radius(int k) const;
    double coordinate(double rho) const;  // in [0, levels − 1]
};

}  // namespace sl::sss
