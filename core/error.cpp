#include "core/error.h"

#include <cmath>

namespace sl {

void require_finite(float value, const std::string& what) {
    if (!std::isfinite(value)) {
        fail("{}: value {} is not finite", what, value);
    }
}

}  // namespace sl
