#include "core/error.h"

#include <cmath>

namespace sl {}  // namespace sl
