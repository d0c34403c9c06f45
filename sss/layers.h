#pragma once
// Multi-layered materials (Rohat §3.4.2 eq. 3.7-3.12, §5.1.2; Donner & Jensen 2005): each layer's
// radially symmetric R(r) and T(r) sampled on a 2D grid, zero padded, Fourier transformed (FFTW),
// combined with the Kubelka-Munk equations per frequency, and transformed back.

#include <functional>
#include <vector>

#include "sss/diffusion.h"

namespace sl::sss {

// One channel of one layer: reflectance and transmittance profiles, 1/mm², of the distance in mm.
struct LayerFunctions {
    std::function<double(double)> R;
    std::function<double(double)> T;
};

// One channel of the stack, from the top layer down.
struct CombinedLayers {
    double spacing = 0.0;      // mm between radial samples
    std::vector<double> R, T;  // at r = k spacing, k = 0 .. grid/2 − 1
    double total_R = 0.0;      // the DC terms: ∫ R dA and ∫ T dA
    double total_T = 0.0;
};

// Samples every layer on a grid x grid lattice of spacing 2 extent / grid centred on the entry
// point, zero pads to twice that, and folds the layers top-down with
//   T12 = T1 T2 / (1 − R2 R1)               (eq. 3.10)
//   R12 = R1 + T1 R2 T1 / (1 − R2 R1)       (eq. 3.12)
// (a symmetric layer reflects the same from above and below). `grid` must be even, ≥ 8.
CombinedLayers combine_layers(const std::vector<LayerFunctions>& layers, double extent_mm,
                              int grid = 256);

// The stack (sss::Layer, materials/scattering_material.h) as one profile:
// The stack's combined reflectance as a radial profile for the renderer, per channel, and the
// totals. The profile's r_max is `extent_mm`.
struct LayeredProfile {
    RadialProfile reflectance;
    dvec3 total_R{0.0};
    dvec3 total_T{0.0};
};
LayeredProfile layered_profile(const std::vector<Layer>& layers, double extent_mm, int grid = 256,
                               int texels = 512, int pairs = 10);

}  // namespace sl::sss
