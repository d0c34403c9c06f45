#include "ibl/sh9.h"

#include <numbers>

#include <glm/geometric.hpp>

namespace sl::ibl {

std::array<float, 9> sh9_basis(glm::vec3 d) {
    const float x = d.x, y = d.y, z = d.z;
    return {0.282095f,
            0.488603f * y,
            0.488603f * z,
            0.488603f * x,
            1.092548f * x * y,
            1.092548f * y * z,
            0.315392f * (3.0f * z * z - 1.0f),
            1.092548f * x * z,
            0.546274f * (x * x - y * y)};
}

glm::vec3 Sh9::radiance(glm::vec3 d) const {
    const std::array<float, 9> y = sh9_basis(glm::normalize(d));
    glm::vec3 sum(0.0f);
    for (size_t i = 0; i < 9; ++i) {
        sum += coefficients[i] * y[i];
    }
    return sum;
}

glm::vec3 Sh9::irradiance(glm::vec3 n) const {
    constexpr float pi = std::numbers::pi_v<float>;
    constexpr float band[9] = {pi,     2 * pi / 3, 2 * pi / 3, 2 * pi / 3, pi / 4,
                               pi / 4, pi / 4,     pi / 4,     pi / 4};
    const std::array<float, 9> y = sh9_basis(glm::normalize(n));
    glm::vec3 sum(0.0f);
    for (size_t i = 0; i < 9; ++i) {
        sum += band[i] * coefficients[i] * y[i];
    }
    return sum;
}

Sh9 project_sh9(const CubeMap& cube) {
    // Accumulate in double: a 512² cube sums 1.5 M terms.
    std::array<glm::dvec3, 9> sum{};
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < cube.size; ++y)
            for (int x = 0; x < cube.size; ++x) {
                const std::array<float, 9> basis = sh9_basis(cube.direction(f, x, y));
                const glm::dvec3 weighted =
                    glm::dvec3(cube.texel(f, x, y)) * double(texel_solid_angle(cube.size, x, y));
                for (size_t i = 0; i < 9; ++i) {
                    sum[i] += weighted * double(basis[i]);
                }
            }
    Sh9 sh;
    for (size_t i = 0; i < 9; ++i) {
        sh.coefficients[i] = glm::vec3(sum[i]);
    }
    return sh;
}

}  // namespace sl::ibl
