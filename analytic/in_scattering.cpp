#include "analytic/in_scattering.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "analytic/phase_functions.h"
#include "analytic/quadrature.h"

namespace sl::analytic {

namespace {

constexpr double kPi = std::numbers::pi;

dvec3 axis(const SpotLight& light) {
    return glm::normalize(dvec3(light.direction()));
}

// Geometry of the ray relative to the light (Nilsson eq. 2.16): z_s, the distance along the ray
// closest to L, and h = r0, the distance of the ray from L.
struct Closest {
    double z_s;
    double h;
};

Closest closest_approach(const EyeRay& ray, const dvec3& light) {
    const dvec3 delta = light - ray.origin;
    const double z_s = glm::dot(delta, ray.direction);
    const dvec3 off = delta - z_s * ray.direction;
    return {z_s, glm::length(off)};
}

}  // namespace

dvec3 scattering_density(const EyeRay& ray, double z, const SpotLight& light,
                         const Medium& medium) {
    const dvec3 p = ray.origin + z * ray.direction;
    const dvec3 from_light = p - dvec3(light.position);
    const double r = glm::length(from_light);
    const double axial = glm::dot(from_light, axis(light));
    if (!(r > 0.0) || axial < light.near || axial > light.far) {
        return dvec3(0.0);
    }
    const double cone = light.cone_factor(glm::vec3(p));
    if (cone == 0.0) {
        return dvec3(0.0);
    }
    // The scattering angle between the light's travel (L to p) and the way to the eye (-V).
    const double cos_alpha = -glm::dot(from_light / r, ray.direction);
    const double p_alpha = phase(medium.phase, medium.g, cos_alpha);
    const dvec3 sigma_s(medium.sigma_s), intensity(light.intensity);
    if (medium.model == MediumModel::simplified) {
        // Nilsson eq. 2.12-2.15: T = 1 and I_p = I(Ω) / (a1 r² + a0).
        return sigma_s * p_alpha * intensity * cone /
               (double(medium.a1) * r * r + double(medium.a0));
    }
    // Nilsson eq. 2.6-2.8: T(z) σs p I(Ω) T(r) / r².
    const dvec3 sigma_t(medium.sigma_t());
    return glm::exp(-sigma_t * (z + r)) * sigma_s * p_alpha * intensity * cone / (r * r);
}

Interval light_interval(const EyeRay& ray, const SpotLight& light, double t_max) {
    const dvec3 a = axis(light);
    const dvec3 w = ray.origin - dvec3(light.position);
    const double cos_cone = std::cos(glm::radians(double(light.cone_half_angle_degrees)));
    double lo = 0.0, hi = t_max;
    // Range along the axis: near <= dot(w + t V, a) <= far.
    const double da = glm::dot(ray.direction, a), wa = glm::dot(w, a);
    if (std::abs(da) < 1e-15) {
        if (wa < light.near || wa > light.far)
            return {};
    } else {
        double t0 = (light.near - wa) / da, t1 = (light.far - wa) / da;
        if (t0 > t1)
            std::swap(t0, t1);
        lo = std::max(lo, t0);
        hi = std::min(hi, t1);
    }
    if (!(hi > lo)) {
        return {};
    }
    // Inside the one-sided cone: f(t) = (dot(q, a))² - cos² |q|² >= 0 with dot(q, a) >= 0,
    // q = w + tV. f is quadratic in t; the cone is convex, so the inside is one interval, and
    // within the range above dot(q, a) >= near > 0 holds already.
    const double c2 = cos_cone * cos_cone;
    const double A = da * da - c2;
    const double B = 2.0 * (da * wa - c2 * glm::dot(ray.direction, w));
    const double C = wa * wa - c2 * glm::dot(w, w);
    auto inside = [&](double t) { return (A * t + B) * t + C >= 0.0; };
    if (std::abs(A) < 1e-14) {
        // Parallel to a generator: linear.
        if (std::abs(B) < 1e-300) {
            return C >= 0.0 ? Interval{lo, hi} : Interval{};
        }
        const double root = -C / B;
        if (B > 0.0)
            lo = std::max(lo, root);
        else
            hi = std::min(hi, root);
        return hi > lo ? Interval{lo, hi} : Interval{};
    }
    const double discriminant = B * B - 4.0 * A * C;
    if (discriminant < 0.0) {
        return inside(0.5 * (lo + hi)) ? Interval{lo, hi} : Interval{};
    }
    // Numerically stable roots.
    const double q = -0.5 * (B + std::copysign(std::sqrt(discriminant), B));
    double r0 = q / A, r1 = q != 0.0 ? C / q : r0;
    if (r0 > r1)
        std::swap(r0, r1);
    if (A < 0.0) {
        // Inside between the roots (the cone opens wider than the ray's angle to the axis).
        lo = std::max(lo, r0);
        hi = std::min(hi, r1);
        return hi > lo ? Interval{lo, hi} : Interval{};
    }
    // A > 0: inside outside the roots; within the range only one side can be on the forward
    // nappe, so keep the side whose midpoint is inside.
    const Interval before{lo, std::min(hi, r0)}, after{std::max(lo, r1), hi};
    if (!before.empty() && inside(0.5 * (before.begin + before.end)))
        return before;
    if (!after.empty() && inside(0.5 * (after.begin + after.end)))
        return after;
    return {};
}

dvec3 in_scattering(const EyeRay& ray, double z0, double z1, const SpotLight& light,
                    const Medium& medium) {
    const Interval lit = light_interval(ray, light, std::max(z0, z1));
    z0 = std::max(z0, lit.begin);
    z1 = std::min(z1, lit.end);
    if (!(z1 > z0)) {
        return dvec3(0.0);
    }
    const dvec3 L(light.position);
    const Closest closest = closest_approach(ray, L);
    const double distance = glm::length(L - ray.origin);
    const bool hard_edge = light.falloff_degrees <= 0.0f;
    const bool isotropic = medium.phase == PhaseFunction::isotropic;
    // Below this distance from L (relative) the closed forms lose their accuracy (γ → 0).
    const bool grazing = closest.h <= 1e-7 * std::max(distance, 1.0);
    dvec3 result(0.0);
    for (int c = 0; c < 3; ++c) {
        const double sigma_s = medium.sigma_s[c];
        const double intensity = light.intensity[c];
        if (sigma_s == 0.0 || intensity == 0.0) {
            continue;
        }
        if (hard_edge && !grazing && medium.model == MediumModel::simplified && isotropic) {
            const double a0 = medium.a0, a1 = medium.a1;
            if (a1 == 0.0) {
                result[c] = sigma_s * intensity / (4.0 * kPi * a0) * (z1 - z0);
                continue;
            }
            // Nilsson eq. 2.17.
            const double C = std::sqrt(a1 * (a1 * closest.h * closest.h + a0));
            result[c] =
                sigma_s * intensity / (4.0 * kPi * C) *
                (std::atan(a1 * (z1 - closest.z_s) / C) - std::atan(a1 * (z0 - closest.z_s) / C));
            continue;
        }
        if (hard_edge && !grazing && medium.model == MediumModel::physical && isotropic) {
            const double sigma_t = medium.sigma_t()[c];
            if (sigma_t > 0.0) {
                // Sun et al. 2005: G(x) = A0 F(A1, ξ(x)), F(u, v) = ∫_0^v exp(-u tan ζ) dζ,
                // Tsv = σt d, A0 = σs σt I e^(-Tsv cos γ) / (2π Tsv sin γ), A1 = Tsv sin γ,
                // ξ(x) = π/4 + ½ atan((σt x - Tsv cos γ) / (Tsv sin γ)). d cos γ = z_s and
                // d sin γ = h, so Tsv cos γ = σt z_s and Tsv sin γ = σt h.
                const double a0 = sigma_s * sigma_t * intensity * std::exp(-sigma_t * closest.z_s) /
                                  (2.0 * kPi * sigma_t * closest.h);
                const double a1 = sigma_t * closest.h;
                auto xi = [&](double x) {
                    return 0.25 * kPi + 0.5 * std::atan((x - closest.z_s) / closest.h);
                };
                const double f =
                    integrate([&](double zeta) { return std::exp(-a1 * std::tan(zeta)); }, xi(z0),
                              xi(z1), 1e-14);
                result[c] = a0 * f;
                continue;
            }
        }
        if (hard_edge && !grazing && medium.model == MediumModel::simplified && medium.a0 == 0.0f) {
            // e = σs p(α) I / (a1 r²) with r = h / cos θ, z - z_s = h tan θ: dz / r² = dθ / h and
            // cos α = -sin θ, so ∫ e dz = σs I / (a1 h) ∫ p(-sin θ) dθ.
            auto theta = [&](double x) { return std::atan((x - closest.z_s) / closest.h); };
            const double p_integral =
                integrate([&](double t) { return phase(medium.phase, medium.g, -std::sin(t)); },
                          theta(z0), theta(z1), 1e-14);
            result[c] = sigma_s * intensity / (double(medium.a1) * closest.h) * p_integral;
            continue;
        }
        // No closed form: adaptive quadrature of e(z) itself.
        result[c] = integrate(
            [&](double z) { return scattering_density(ray, z, light, medium)[c]; }, z0, z1, 1e-12);
    }
    return result;
}

}  // namespace sl::analytic
