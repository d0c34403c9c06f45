#include "ibl/microfacet.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "core/error.h"

namespace sl::ibl {

namespace {
constexpr float kPi = std::numbers::pi_v<float>;
}

float distribution(Distribution distribution, float alpha, float n_dot_h) {
    if (n_dot_h <= 0.0f) {
        return 0.0f;
    }
    const float a2 = std::max(alpha * alpha, 1e-12f);
    const float c2 = n_dot_h * n_dot_h;
    if (distribution == Distribution::beckmann) {
        return std::exp((c2 - 1.0f) / (a2 * c2)) / (kPi * a2 * c2 * c2);
    }
    const float d = (a2 - 1.0f) * c2 + 1.0f;
    return a2 / (kPi * d * d);
}

glm::vec3 fresnel_schlick(glm::vec3 f0, float v_dot_h) {
    const float c = std::clamp(1.0f - v_dot_h, 0.0f, 1.0f);
    const float c5 = c * c * c * c * c;
    return f0 + (glm::vec3(1.0f) - f0) * c5;
}

float fresnel_schlick(float f0, float v_dot_h) {
    return fresnel_schlick(glm::vec3(f0), v_dot_h).x;
}

float beckmann_g1(float alpha, float n_dot_v) {
    if (n_dot_v <= 0.0f) {
        return 0.0f;
    }
    const float sin_v = std::sqrt(std::max(0.0f, 1.0f - n_dot_v * n_dot_v));
    if (sin_v <= 0.0f) {
        return 1.0f;
    }
    const float c = n_dot_v / (std::max(alpha, 1e-6f) * sin_v);
    if (c >= 1.6f) {
        return 1.0f;
    }
    return (3.535f * c + 2.181f * c * c) / (1.0f + 2.276f * c + 2.577f * c * c);
}

float ggx_g1(float alpha, float n_dot_v) {
    if (n_dot_v <= 0.0f) {
        return 0.0f;
    }
    const float a2 = alpha * alpha;
    return 2.0f * n_dot_v / (n_dot_v + std::sqrt(a2 + (1.0f - a2) * n_dot_v * n_dot_v));
}

float ggx_g2(float alpha, float n_dot_v, float n_dot_l) {
    if (n_dot_v <= 0.0f || n_dot_l <= 0.0f) {
        return 0.0f;
    }
    // G2 = 1 / (1 + Λ(v) + Λ(l)), Λ(x) = (−1 + sqrt(1 + α² tan² θ)) / 2.
    const float a2 = alpha * alpha;
    auto lambda = [&](float c) {
        return 0.5f * (-1.0f + std::sqrt(1.0f + a2 * (1.0f - c * c) / (c * c)));
    };
    return 1.0f / (1.0f + lambda(n_dot_v) + lambda(n_dot_l));
}

float beckmann_g2(float alpha, float n_dot_v, float n_dot_l) {
    return beckmann_g1(alpha, n_dot_v) * beckmann_g1(alpha, n_dot_l);
}

glm::vec3 sample_half_vector(Distribution distribution, float alpha, glm::vec2 u) {
    const float a2 = alpha * alpha;
    float cos2;
    if (distribution == Distribution::beckmann) {
        // tan² θ = −α² ln(1 − u)
        const float tan2 = -a2 * std::log(std::max(1.0f - u.x, 1e-30f));
        cos2 = 1.0f / (1.0f + tan2);
    } else {
        // tan² θ = α² u / (1 − u)
        cos2 = (1.0f - u.x) / (1.0f + (a2 - 1.0f) * u.x);
    }
    const float cos_theta = std::sqrt(std::clamp(cos2, 0.0f, 1.0f));
    const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
    const float phi = 2.0f * kPi * u.y;
    return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

glm::vec2 hammersley(uint32_t i, uint32_t n) {
    uint32_t bits = i;
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return {float(i) / float(n), float(bits) * 2.3283064365386963e-10f};
}

void orthonormal_basis(glm::vec3 n, glm::vec3& tangent, glm::vec3& bitangent) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    tangent = {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
    bitangent = {b, sign + n.y * n.y * a, -n.y};
}

glm::vec2 DfgTable::lookup(float n_dot_v, float alpha) const {
    const float x = std::clamp(n_dot_v * float(size) - 0.5f, 0.0f, float(size - 1));
    const float y =
        std::clamp(std::sqrt(std::max(alpha, 0.0f)) * float(size) - 0.5f, 0.0f, float(size - 1));
    const int x0 = int(x), y0 = int(y);
    const int x1 = std::min(x0 + 1, size - 1), y1 = std::min(y0 + 1, size - 1);
    const float fx = x - float(x0), fy = y - float(y0);
    return (at(x0, y0) * (1.0f - fx) + at(x1, y0) * fx) * (1.0f - fy) +
           (at(x0, y1) * (1.0f - fx) + at(x1, y1) * fx) * fy;
}

glm::vec2 integrate_dfg(Distribution dist, float n_dot_v, float alpha, int samples) {
    const glm::vec3 v(std::sqrt(std::max(0.0f, 1.0f - n_dot_v * n_dot_v)), 0.0f, n_dot_v);
    glm::vec2 ab(0.0f);
    for (int i = 0; i < samples; ++i) {
        const glm::vec3 h =
            sample_half_vector(dist, alpha, hammersley(uint32_t(i), uint32_t(samples)));
        const float v_dot_h = glm::dot(v, h);
        const glm::vec3 l = 2.0f * v_dot_h * h - v;
        if (l.z <= 0.0f || v_dot_h <= 0.0f) {
            continue;
        }
        // f (n·l) / pdf(l) with pdf(l) = D (n·h) / (4 v·h): G (v·h) / ((n·h)(n·v)).
        const float g = dist == Distribution::ggx ? ggx_g2(alpha, n_dot_v, l.z)
                                                  : beckmann_g2(alpha, n_dot_v, l.z);
        const float weight = g * v_dot_h / (h.z * n_dot_v);
        const float fc = std::pow(1.0f - v_dot_h, 5.0f);
        ab += glm::vec2((1.0f - fc) * weight, fc * weight);
    }
    return ab / float(samples);
}

DfgTable compute_dfg_table(Distribution dist, int size, int samples) {
    if (size < 2 || samples < 1) {
        fail("DFG table: size {} and samples {} must be at least 2 and 1", size, samples);
    }
    DfgTable table{size, dist, std::vector<float>(size_t(size * size) * 2)};
    tbb::parallel_for(0, size, [&](int j) {
        const float root_alpha = float(j) / float(size - 1);
        for (int i = 0; i < size; ++i) {
            // n·v = 0 is a grazing limit the integral cannot be sampled at: start just above it.
            const float n_dot_v = std::max(float(i) / float(size - 1), 1e-3f);
            const glm::vec2 ab = integrate_dfg(dist, n_dot_v, root_alpha * root_alpha, samples);
            table.ab[size_t(j * size + i) * 2] = ab.x;
            table.ab[size_t(j * size + i) * 2 + 1] = ab.y;
        }
    });
    return table;
}

}  // namespace sl::ibl
