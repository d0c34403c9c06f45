#pragma once
// Phase functions p(cos α) of the scattering angle α between the light's direction of travel and
// the scattered direction, each normalised to 1 over the sphere (Nilsson eq. 2.3).
//   isotropic          1 / 4π
//   henyey-greenstein  (1 - g²) / (4π (1 + g² - 2g cos α)^1.5)          Moschos eq. 2.2
//   schlick            (1 - k²) / (4π (1 - k cos α)²), k = 1.55g - 0.55g³  Moschos eq. 2.3,
//                      with the sign of k cos α chosen so that g > 0 scatters forward as in HG
//                      (the seed's "1 + k cos θ" peaks backwards for k > 0), and |k| <= 0.999
//                      (the fit exceeds 1 for g above about 0.93)
//   rayleigh           3 / (16π) (1 + cos² α)                               Moschos eq. 2.4
//   mie-hazy           (1/4π) (1/2 + 9/2 ((1 + cos α)/2)^8)                 Moschos eq. 2.5
//   mie-murky          (1/4π) (1/2 + 33/2 ((1 + cos α)/2)^32)               Moschos eq. 2.6
//   nishita-hazy       K (1 + 9 cos^16(α/2)), K = 1/(8π)                    Nilsson eq. 2.4
// Nishita's K: ∫ over the sphere = 2πK ∫_{-1}^{1} (1 + 9((1+μ)/2)^8) dμ = 2πK (2 + 2) = 8πK, so
// K = 1/(8π) ≈ 1/25.13; appendix A's K ≈ 1/16.46 integrates with a √(1-μ²) factor the solid
// angle does not have. With the right K it is exactly mie-hazy.

#include "scenes/scene.h"

namespace sl::analytic {

double phase(PhaseFunction function, double g, double cos_alpha);
// Whether the function reads g (Henyey-Greenstein and Schlick).
bool uses_asymmetry(PhaseFunction function);

}  // namespace sl::analytic
