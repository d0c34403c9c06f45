// The light model against numerical oracles: phase functions integrate to one over the sphere,
// the exact-cone clipping matches a brute-force scan, and every closed form of the in-scattering
// integral matches adaptive quadrature of e(z) to 1e-6 relative.

#include <cmath>
#include <numbers>
#include <random>

#include <glm/geometric.hpp>

#include "analytic/in_scattering.h"
#include "analytic/phase_functions.h"
#include "analytic/quadrature.h"
#include "tests/support.h"

namespace sl::test {
namespace {

using analytic::dvec3;

constexpr PhaseFunction kPhaseFunctions[] = {
    PhaseFunction::isotropic,   PhaseFunction::henyey_greenstein, PhaseFunction::schlick,
    PhaseFunction::rayleigh,    PhaseFunction::mie_hazy,          PhaseFunction::mie_murky,
    PhaseFunction::nishita_hazy};

double uniform(std::mt19937& rng, double lo, double hi) {
    return lo + (hi - lo) * double(rng() >> 5) * (1.0 / 134217728.0);
}

dvec3 random_unit(std::mt19937& rng) {
    for (;;) {
        const dvec3 v(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
        if (const double l = glm::length(v); l > 0.1 && l <= 1.0)
            return v / l;
    }
}

// Every phase function, for every asymmetry, integrates to one over the sphere (Nilsson eq. 2.3).
TEST(PhaseFunctions, IntegrateToOneOverTheSphere) {
    for (const PhaseFunction f : kPhaseFunctions) {
        for (const double g : {-0.9, -0.5, 0.0, 0.3, 0.8, 0.95}) {
            const double total =
                2.0 * std::numbers::pi *
                analytic::integrate([&](double mu) { return analytic::phase(f, g, mu); }, -1.0,
                                    1.0);
            EXPECT_NEAR(total, 1.0, 1e-9) << to_string(f) << " g=" << g;
        }
    }
}

// Nilsson's hazy function with K = 1/(8π) is Moschos's Mie-hazy; HG and Schlick with g > 0
// scatter forwards, and Schlick approximates HG.
TEST(PhaseFunctions, NishitaIsMieHazyAndPositiveGScattersForwards) {
    for (double mu = -1.0; mu <= 1.0; mu += 0.125) {
        EXPECT_NEAR(analytic::phase(PhaseFunction::nishita_hazy, 0, mu),
                    analytic::phase(PhaseFunction::mie_hazy, 0, mu), 1e-15);
    }
    for (const PhaseFunction f : {PhaseFunction::henyey_greenstein, PhaseFunction::schlick}) {
        EXPECT_GT(analytic::phase(f, 0.6, 1.0), 10.0 * analytic::phase(f, 0.6, -1.0))
            << to_string(f);
    }
    EXPECT_NEAR(analytic::phase(PhaseFunction::schlick, 0.5, 0.7) /
                    analytic::phase(PhaseFunction::henyey_greenstein, 0.5, 0.7),
                1.0, 0.1);
}

SpotLight random_light(std::mt19937& rng) {
    SpotLight light;
    light.position = glm::vec3(uniform(rng, -2, 2), uniform(rng, 2, 5), uniform(rng, -2, 2));
    light.target = light.position + glm::vec3(random_unit(rng));
    light.cone_half_angle_degrees = float(uniform(rng, 10, 60));
    light.near = float(uniform(rng, 0.05, 0.5));
    light.far = float(uniform(rng, 5, 15));
    light.intensity = glm::vec3(uniform(rng, 1, 50), uniform(rng, 1, 50), uniform(rng, 1, 50));
    return light;
}

// A ray from a random origin, aimed near the light (through it, grazing it, or across the cone).
analytic::EyeRay random_ray(std::mt19937& rng, const SpotLight& light, int kind) {
    const dvec3 L(light.position), axis = glm::normalize(dvec3(light.direction()));
    analytic::EyeRay ray;
    if (kind == 0) {  // camera inside the cone
        ray.origin = L + uniform(rng, 1.0, 4.0) * axis + 0.1 * random_unit(rng);
        ray.direction = random_unit(rng);
        return ray;
    }
    ray.origin = L + dvec3(uniform(rng, -8, 8), uniform(rng, -8, 8), uniform(rng, -8, 8));
    dvec3 target = L + uniform(rng, 0.5, 6.0) * axis + uniform(rng, 0.0, 2.0) * random_unit(rng);
    if (kind == 1)
        target = L;  // through the light
    if (kind == 2)
        target = L + 1e-9 * random_unit(rng);  // γ -> 0
    if (kind == 3)
        target = L + 1e-4 * random_unit(rng);  // nearly through it
    ray.direction = glm::normalize(target - ray.origin);
    return ray;
}

bool inside_light(const analytic::EyeRay& ray, double z, const SpotLight& light) {
    const dvec3 q = ray.origin + z * ray.direction - dvec3(light.position);
    const double axial = glm::dot(q, glm::normalize(dvec3(light.direction())));
    const double r = glm::length(q);
    return axial >= light.near && axial <= light.far &&
           axial >= r * std::cos(double(light.cone_half_angle_degrees) * std::numbers::pi / 180.0);
}

// The transitions of inside_light along [0, t_max]: a dense scan refined by bisection.
std::vector<double> transitions(const analytic::EyeRay& ray, const SpotLight& light, double t_max) {
    std::vector<double> result;
    constexpr int kSteps = 20000;
    bool previous = inside_light(ray, 0.0, light);
    for (int i = 1; i <= kSteps; ++i) {
        double a = t_max * (i - 1) / kSteps, b = t_max * i / kSteps;
        const bool current = inside_light(ray, b, light);
        if (current != previous) {
            for (int k = 0; k < 60; ++k) {
                const double m = 0.5 * (a + b);
                (inside_light(ray, m, light) == previous ? a : b) = m;
            }
            result.push_back(0.5 * (a + b));
        }
        previous = current;
    }
    return result;
}

// light_interval agrees with a brute-force scan of the exact cone and range.
TEST(InScattering, LightIntervalMatchesBruteForce) {
    std::mt19937 rng(11);
    for (int i = 0; i < 400; ++i) {
        const SpotLight light = random_light(rng);
        const analytic::EyeRay ray = random_ray(rng, light, i % 5);
        const double t_max = 30.0;
        const analytic::Interval interval = analytic::light_interval(ray, light, t_max);
        const std::vector<double> edges = transitions(ray, light, t_max);
        std::vector<double> expected;
        if (inside_light(ray, 0.0, light))
            expected.push_back(0.0);
        expected.insert(expected.end(), edges.begin(), edges.end());
        if (expected.size() % 2 == 1)
            expected.push_back(t_max);
        ASSERT_LE(expected.size(), 2u) << "the cone is convex: one interval";
        if (expected.empty()) {
            EXPECT_TRUE(interval.empty()) << i;
        } else {
            EXPECT_NEAR(interval.begin, expected[0], 1e-7) << i;
            EXPECT_NEAR(interval.end, expected[1], 1e-7) << i;
        }
    }
}

// The oracle: adaptive quadrature of e(z) over [z0, z1], split where the ray crosses the cone or
// the range (found by the scan, not by light_interval).
dvec3 quadrature(const analytic::EyeRay& ray, double z0, double z1, const SpotLight& light,
                 const Medium& medium) {
    std::vector<double> cuts = {z0};
    for (const double t : transitions(ray, light, z1)) {
        if (t > z0)
            cuts.push_back(t);
    }
    cuts.push_back(z1);
    dvec3 sum(0.0);
    for (int c = 0; c < 3; ++c) {
        for (size_t k = 0; k + 1 < cuts.size(); ++k) {
            sum[c] += analytic::integrate(
                [&](double z) { return analytic::scattering_density(ray, z, light, medium)[c]; },
                cuts[k], cuts[k + 1], 1e-12);
        }
    }
    return sum;
}

constexpr int kClosedFormRays = 600;

// Every closed form (and the quadrature fallback) matches the oracle to 1e-6 relative on random
// rays: camera inside the cone, rays through the light, γ -> 0, intervals crossing the cone edge.
TEST(InScattering, ClosedFormsMatchQuadrature) {
    std::mt19937 rng(12);
    int lit[4] = {0, 0, 0, 0};  // rays that see the light, per case
    for (int i = 0; i < kClosedFormRays; ++i) {
        const SpotLight light = random_light(rng);
        Medium medium;
        medium.sigma_s =
            glm::vec3(uniform(rng, 0.01, 0.3), uniform(rng, 0.01, 0.3), uniform(rng, 0.01, 0.3));
        medium.sigma_a =
            glm::vec3(uniform(rng, 0.0, 0.2), uniform(rng, 0.0, 0.2), uniform(rng, 0.0, 0.2));
        switch (i % 4) {
            case 0:  // Nilsson eq. 2.17
                medium.model = MediumModel::simplified;
                medium.a0 = float(uniform(rng, 0.1, 2.0));
                medium.a1 = float(uniform(rng, 0.2, 2.0));
                break;
            case 1:  // Sun et al. 2005
                medium.model = MediumModel::physical;
                break;
            case 2:  // anisotropic, pure 1/r²
                medium.model = MediumModel::simplified;
                medium.a0 = 0.0f;
                medium.a1 = 1.0f;
                medium.phase = kPhaseFunctions[1 + rng() % 6];
                medium.g = float(uniform(rng, -0.8, 0.8));
                break;
            default:  // no closed form: anisotropic physical, smooth cone edge
                medium.model = MediumModel::physical;
                medium.phase = kPhaseFunctions[1 + rng() % 6];
                medium.g = float(uniform(rng, -0.8, 0.8));
                break;
        }
        const analytic::EyeRay ray = random_ray(rng, light, (i / 4) % 5);
        const double z0 = uniform(rng, 0.0, 4.0), z1 = z0 + uniform(rng, 0.5, 25.0);
        const dvec3 closed = analytic::in_scattering(ray, z0, z1, light, medium);
        const dvec3 oracle = quadrature(ray, z0, z1, light, medium);
        for (int c = 0; c < 3; ++c) {
            ASSERT_TRUE(std::isfinite(closed[c]));
            EXPECT_NEAR(closed[c], oracle[c], 1e-6 * std::abs(oracle[c]) + 1e-14)
                << "case " << i % 4 << " ray kind " << (i / 4) % 5 << " channel " << c;
        }
        lit[i % 4] += oracle.x > 0.0;
    }
    for (const int count : lit) {
        EXPECT_GE(count, 30) << "every case must be exercised by rays that see the light";
    }
}

// The smooth falloff has no closed form: the quadrature path integrates it.
TEST(InScattering, SmoothFalloffIsIntegrated) {
    std::mt19937 rng(13);
    SpotLight light = random_light(rng);
    light.falloff_degrees = 0.5f * light.cone_half_angle_degrees;
    Medium medium;
    medium.sigma_s = glm::vec3(0.1f);
    const analytic::EyeRay ray = random_ray(rng, light, 0);
    const dvec3 closed = analytic::in_scattering(ray, 0.0, 20.0, light, medium);
    const dvec3 oracle = quadrature(ray, 0.0, 20.0, light, medium);
    EXPECT_NEAR(closed.x, oracle.x, 1e-6 * oracle.x);
}

}  // namespace
}  // namespace sl::test
