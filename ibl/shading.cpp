#include "ibl/shading.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace sl::ibl {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// Figure 3.24 per level: tan² θ and tan² θ / α² (ibl/environment_textures.cpp, the same values).
glm::vec2 cone_terms(float lod) {
    const size_t l0 = size_t(lod);
    const float f = lod - float(l0);
    return moschos_cone_measure(l0) * (1.0f - f) + moschos_cone_measure(l0 + 1) * f;
}

// How far the split-sum lobe's dominant direction stays at r rather than n (Lagarde & de
// Rousiers 2014, "Moving Frostbite to PBR", listing 22).
float dominant_direction_weight(float alpha) {
    const float smoothness = std::clamp(1.0f - alpha, 0.0f, 1.0f);
    return smoothness * (std::sqrt(smoothness) + alpha);
}

float g2(Shading shading, float alpha, float n_dot_v, float n_dot_l) {
    return shading == Shading::moschos ? beckmann_g2(alpha, n_dot_v, n_dot_l)
                                       : ggx_g2(alpha, n_dot_v, n_dot_l);
}

}  // namespace

glm::vec3 shade_environment(const LoadedEnvironment& e, Shading shading, const SurfacePoint& p) {
    const float n_dot_v = std::max(glm::dot(p.n, p.v), 1e-4f);
    const glm::vec3 r = 2.0f * glm::dot(p.n, p.v) * p.n - p.v;
    const float lod = roughness_to_lod(e.chain, p.alpha);
    const glm::vec3 prefiltered = sample_lod(e.chain.levels, r, lod);
    if (shading == Shading::moschos) {
        const float last = float(e.chain.levels.size() - 1);
        const glm::vec2 cone = cone_terms(std::min(std::max(lod, 1.0f), last));
        const float g = beckmann_g1(p.alpha, n_dot_v) * beckmann_g1(p.alpha, n_dot_v);
        const glm::vec3 specular = cone.y * fresnel_schlick(p.f0, n_dot_v) * g / (4.0f * n_dot_v);
        const glm::vec3 diffuse = p.albedo * n_dot_v * cone.x;
        return e.intensity * prefiltered * (specular + diffuse);
    }
    const glm::vec3 dominant = glm::normalize(glm::mix(p.n, r, dominant_direction_weight(p.alpha)));
    const glm::vec2 ab = e.dfg.lookup(n_dot_v, std::clamp(p.alpha, 0.0f, 1.0f));
    const glm::vec3 specular_weight = p.f0 * ab.x + ab.y;
    return e.intensity * sample_lod(e.chain.levels, dominant, lod) * specular_weight +
           p.albedo / kPi * glm::max(e.sh.irradiance(p.n), glm::vec3(0.0f)) *
               (glm::vec3(1.0f) - specular_weight);
}

glm::vec3 reference_environment_radiance(const LoadedEnvironment& e, Shading shading,
                                         const SurfacePoint& p, int samples,
                                         const std::function<bool(glm::vec3)>& visible) {
    const Distribution d = shading == Shading::moschos ? Distribution::beckmann : Distribution::ggx;
    const float n_dot_v = std::max(glm::dot(p.n, p.v), 1e-4f);
    glm::vec3 t, b;
    orthonormal_basis(p.n, t, b);
    const CubeMap& source = e.chain.levels[0];
    glm::vec3 specular(0.0f), diffuse(0.0f);
    for (int i = 0; i < samples; ++i) {
        const glm::vec2 u = hammersley(uint32_t(i), uint32_t(samples));
        // Specular: h ~ D(h)(n·h); f (n·l) / pdf(l) = F G (v·h) / ((n·v)(n·h)).
        const glm::vec3 hl = sample_half_vector(d, p.alpha, u);
        const glm::vec3 h = hl.x * t + hl.y * b + hl.z * p.n;
        const float v_dot_h = glm::dot(p.v, h);
        const glm::vec3 l = 2.0f * v_dot_h * h - p.v;
        const float n_dot_l = glm::dot(p.n, l);
        if (n_dot_l > 0.0f && v_dot_h > 0.0f && (!visible || visible(l))) {
            specular += source.sample(l) * fresnel_schlick(p.f0, v_dot_h) *
                        (g2(shading, p.alpha, n_dot_v, n_dot_l) * v_dot_h / (n_dot_v * hl.z));
        }
        // Diffuse: cosine-weighted l; (albedo/π)(n·l) / pdf = albedo.
        const float radius = std::sqrt(u.x), phi = 2.0f * kPi * u.y;
        const glm::vec3 c(radius * std::cos(phi), radius * std::sin(phi),
                          std::sqrt(std::max(0.0f, 1.0f - u.x)));
        const glm::vec3 l_diffuse = c.x * t + c.y * b + c.z * p.n;
        if (!visible || visible(l_diffuse)) {
            diffuse += source.sample(l_diffuse);
        }
    }
    specular /= float(samples);
    diffuse *= p.albedo / float(samples);
    if (shading == Shading::split_sum) {
        const glm::vec2 ab = e.dfg.lookup(n_dot_v, std::clamp(p.alpha, 0.0f, 1.0f));
        diffuse *= glm::vec3(1.0f) - (p.f0 * ab.x + ab.y);
    }
    return e.intensity * (specular + diffuse);
}

}  // namespace sl::ibl
