#include "frame/shadow_fit.h"

#include <optional>

#include <glm/matrix.hpp>

#include "scenes/view_window.h"

namespace sl::frame {

glm::mat4 shadow_view_projection(const SpotLight& light, const Camera& camera, float aspect) {
    const glm::dmat4 whole = glm::dmat4(light.projection()) * glm::dmat4(light.view());
    if (!light.parallel()) {
        return glm::mat4(whole);
    }
    const std::optional<ViewWindow> window = view_window(light, camera, aspect);
    if (!window) {
        return glm::mat4(whole);
    }
    // [lo, hi] -> [-1, 1]³.
    const glm::dvec3 lo = window->lo, hi = window->hi;
    glm::dmat4 fit(1.0);
    for (int k = 0; k < 3; ++k) {
        fit[k][k] = 2.0 / (hi[k] - lo[k]);
        fit[3][k] = -(hi[k] + lo[k]) / (hi[k] - lo[k]);
    }
    return glm::mat4(fit * whole);
}

}  // namespace sl::frame
