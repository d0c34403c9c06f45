#include "analytic/phase_functions.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sl::analytic {

double phase(PhaseFunction function, double g, double cos_alpha) {
    constexpr double inv_4pi = 0.25 / std::numbers::pi;
    const double c = cos_alpha;
    switch (function) {
        case PhaseFunction::isotropic:
            return inv_4pi;
        case PhaseFunction::henyey_greenstein:
            return inv_4pi * (1.0 - g * g) / std::pow(1.0 + g * g - 2.0 * g * c, 1.5);
        case PhaseFunction::schlick: {
            // The seed's fit exceeds 1 for g above about 0.93 (1.0015 at g = 0.97), where the
            // function turns singular and negative: keep |k| < 1.
            const double k = std::clamp(1.55 * g - 0.55 * g * g * g, -0.999, 0.999);
            const double d = 1.0 - k * c;
            return inv_4pi * (1.0 - k * k) / (d * d);
        }
        case PhaseFunction::rayleigh:
            return 3.0 / (16.0 * std::numbers::pi) * (1.0 + c * c);
        case PhaseFunction::mie_hazy:
            return inv_4pi * (0.5 + 4.5 * std::pow(0.5 * (1.0 + c), 8));
        case PhaseFunction::mie_murky:
            return inv_4pi * (0.5 + 16.5 * std::pow(0.5 * (1.0 + c), 32));
        case PhaseFunction::nishita_hazy:
            return 0.125 / std::numbers::pi * (1.0 + 9.0 * std::pow(0.5 * (1.0 + c), 8));
    }
    return 0.0;
}

bool uses_asymmetry(PhaseFunction function) {
    return function == PhaseFunction::henyey_greenstein || function == PhaseFunction::schlick;
}

}  // namespace sl::analytic
