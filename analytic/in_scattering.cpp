#include "analytic/in_scattering.h"

#include <algorithm>
#include <cmath>
#include <limits>
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
// closest to L, and h = r0, the distance of the ray from L; below `grazing` (relative to L's
// distance) the forms in 1/h lose their accuracy (γ → 0).
struct Closest {
    double z_s;
    double h;
    double grazing;
};

Closest closest_approach(const EyeRay& ray, const dvec3& light) {
    const dvec3 delta = light - ray.origin;
    const double z_s = glm::dot(delta, ray.direction);
    const dvec3 off = delta - z_s * ray.direction;
    return {z_s, glm::length(off), 1e-7 * std::max(glm::length(delta), 1.0)};
}

}  // namespace

namespace {

// e(z) of a light at `position` shining `intensity` towards p, whatever its cone and range.
dvec3 unbounded_density(const EyeRay& ray, double z, const dvec3& position, const dvec3& intensity,
                        const Medium& medium) {
    const dvec3 p = ray.origin + z * ray.direction;
    const dvec3 from_light = p - position;
    const double r = glm::length(from_light);
    if (!(r > 0.0)) {
        return dvec3(0.0);
    }
    // The scattering angle between the light's travel (L to p) and the way to the eye (-V).
    const double cos_alpha = -glm::dot(from_light / r, ray.direction);
    const double p_alpha = phase(medium.phase, medium.g, cos_alpha);
    const dvec3 sigma_s(medium.sigma_s);
    if (medium.model == MediumModel::simplified) {
        // Nilsson eq. 2.12-2.15: T = 1 and I_p = I(Ω) / (a1 r² + a0).
        return sigma_s * p_alpha * intensity / (double(medium.a1) * r * r + double(medium.a0));
    }
    // Nilsson eq. 2.6-2.8: T(z) σs p I(Ω) T(r) / r².
    const dvec3 sigma_t(medium.sigma_t());
    return glm::exp(-sigma_t * (z + r)) * sigma_s * p_alpha * intensity / (r * r);
}

}  // namespace

dvec3 scattering_density(const EyeRay& ray, double z, const SpotLight& light,
                         const Medium& medium) {
    const dvec3 p = ray.origin + z * ray.direction;
    const dvec3 from_light = p - dvec3(light.position);
    const double axial = glm::dot(from_light, axis(light));
    if (axial < light.near || axial > light.far) {
        return dvec3(0.0);
    }
    if (light.parallel()) {
        if (light.cone_factor(p) == 0.0) {
            return dvec3(0.0);
        }
        // Parallel beams: the scattering angle is the same everywhere, the irradiance E at the
        // entry plane, T(z) T(s) with s = axial the light's path in the medium (physical), or
        // E alone (simplified: no attenuation, eq. 2.15, and no falloff with distance).
        const double cos_alpha = -glm::dot(axis(light), ray.direction);
        const dvec3 source = dvec3(medium.sigma_s) * phase(medium.phase, medium.g, cos_alpha) *
                             dvec3(light.intensity);
        if (medium.model == MediumModel::simplified) {
            return source;
        }
        return glm::exp(-dvec3(medium.sigma_t()) * (z + axial)) * source;
    }
    // The cone factor in double precision (SpotLight::cone_factor's float would leave noise
    // the quadrature cannot converge on).
    const double cone = light.cone_factor(p);
    if (cone == 0.0) {
        return dvec3(0.0);
    }
    return cone * unbounded_density(ray, z, dvec3(light.position), dvec3(light.intensity), medium);
}

dvec3 scattering_density(const EyeRay& ray, double z, const PointLight& light,
                         const Medium& medium) {
    if (!light.in_range(ray.origin + z * ray.direction)) {
        return dvec3(0.0);
    }
    return unbounded_density(ray, z, dvec3(light.position), dvec3(light.intensity), medium);
}

double simplified_cos_alpha(double kappa, double beta) {
    const double sb = std::sin(beta), cb = std::cos(beta);
    const double norm = std::sqrt(kappa * kappa * cb * cb + sb * sb);
    return norm > 0.0 ? -sb / norm : 0.0;
}

Interval light_interval(const EyeRay& ray, const SpotLight& light, double t_max) {
    if (light.shape == SpotShape::pyramid) {
        return pyramid_interval(ray, light, t_max);
    }
    return cone_interval(ray, light, glm::radians(double(light.cone_half_angle_degrees)), t_max);
}

namespace {

// Clips [lo, hi] to where a + b·t >= 0; false when nothing is left.
bool clip_linear(double a, double b, double& lo, double& hi) {
    if (b == 0.0) {
        return a >= 0.0 && hi > lo;
    }
    const double root = -a / b;
    if (b > 0.0) {
        lo = std::max(lo, root);
    } else {
        hi = std::min(hi, root);
    }
    return hi > lo;
}

}  // namespace

Interval pyramid_interval(const EyeRay& ray, const SpotLight& light, double t_max) {
    // Six half-spaces, each linear in t: near <= dot(q, a) <= far, and ±dot(q, s) <= tan θ
    // dot(q, a) for the sides s = r, u, with q = w + tV (the frame of SpotLight::cone_factor).
    const dvec3 a = axis(light);
    const dvec3 up(light.up());
    const dvec3 u = glm::normalize(up - glm::dot(up, a) * a);
    const dvec3 r = glm::cross(a, u);
    // Parallel beams: the sides are parallel to the axis, |dot(q, s)| <= the half-width.
    const double slope =
        light.parallel() ? 0.0 : std::tan(glm::radians(double(light.cone_half_angle_degrees)));
    const double width = light.parallel() ? double(light.half_width) : 0.0;
    const dvec3 w = ray.origin - dvec3(light.position);
    const dvec3& v = ray.direction;
    double lo = 0.0, hi = t_max;
    const double wa = glm::dot(w, a), va = glm::dot(v, a);
    bool inside =
        clip_linear(wa - light.near, va, lo, hi) && clip_linear(light.far - wa, -va, lo, hi);
    for (const dvec3& side : {r, -r, u, -u}) {
        inside = inside && clip_linear(slope * wa + width - glm::dot(w, side),
                                       slope * va - glm::dot(v, side), lo, hi);
    }
    return inside ? Interval{lo, hi} : Interval{};
}

int point_light_intervals(const EyeRay& ray, const PointLight& light, double t_max,
                          Interval out[2]) {
    // Inside the far cube: three slabs; outside the near cube: the complement of three slabs,
    // which cuts the far cube's interval into at most two.
    const dvec3 w = ray.origin - dvec3(light.position);
    const dvec3& v = ray.direction;
    auto slabs = [&](double half, double lo, double hi) -> Interval {
        for (int k = 0; k < 3; ++k) {
            if (!clip_linear(half - w[k], -v[k], lo, hi) ||
                !clip_linear(half + w[k], v[k], lo, hi)) {
                return {};
            }
        }
        return {lo, hi};
    };
    const Interval outer = slabs(light.far, 0.0, t_max);
    if (outer.empty()) {
        return 0;
    }
    // The near cube's interval over the whole line, so that its ends are where the ray crosses it.
    const Interval inner =
        slabs(light.near, -std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
    if (inner.empty()) {
        out[0] = outer;
        return 1;
    }
    int count = 0;
    for (const Interval part : {Interval{outer.begin, std::min(outer.end, inner.begin)},
                                Interval{std::max(outer.begin, inner.end), outer.end}}) {
        if (!part.empty()) {
            out[count++] = part;
        }
    }
    return count;
}

Interval cone_interval(const EyeRay& ray, const SpotLight& light, double half_angle, double t_max) {
    const dvec3 a = axis(light);
    const dvec3 w = ray.origin - dvec3(light.position);
    const double cos_cone = std::cos(half_angle);
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
    if (!(hi > lo) || !(half_angle > 0.0)) {
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

namespace {

// The hard-edge closed forms per channel, or quadrature of e(z) where none holds. [z0, z1] lies
// inside the cone interval already.
dvec3 hard_edge_integral(const EyeRay& ray, double z0, double z1, const dvec3& position,
                         const dvec3& light_intensity, const Medium& medium) {
    const Closest closest = closest_approach(ray, position);
    const double h = closest.h, z_s = closest.z_s, grazing = closest.grazing;
    const bool isotropic = medium.phase == PhaseFunction::isotropic;
    const double a0 = medium.a0, a1 = medium.a1;
    auto p = [&](double cos_alpha) { return phase(medium.phase, medium.g, cos_alpha); };
    dvec3 result(0.0);
    for (int c = 0; c < 3; ++c) {
        const double sigma_s = medium.sigma_s[c];
        const double intensity = light_intensity[c];
        if (sigma_s == 0.0 || intensity == 0.0) {
            continue;
        }
        if (medium.model == MediumModel::simplified && isotropic && a1 > 0.0 &&
            (a0 > 0.0 || h > grazing)) {
            // Nilsson eq. 2.17.
            const double C = std::sqrt(a1 * (a1 * h * h + a0));
            result[c] = sigma_s * intensity / (4.0 * kPi * C) *
                        (std::atan(a1 * (z1 - z_s) / C) - std::atan(a1 * (z0 - z_s) / C));
            continue;
        }
        if (medium.model == MediumModel::simplified && isotropic && a1 == 0.0) {
            result[c] = sigma_s * intensity / (4.0 * kPi * a0) * (z1 - z0);
            continue;
        }
        const double H = a1 > 0.0 ? std::sqrt(h * h + a0 / a1) : 0.0;
        if (medium.model == MediumModel::simplified && a1 > 0.0 && H > grazing) {
            // e = σs p(α) I / (a1 r² + a0), r² = h² + x², x = z - z_s. With H² = h² + a0 / a1,
            // a1 r² + a0 = a1 (x² + H²); x = H tan β gives dz / (a1 (x² + H²)) = dβ / (a1 H).
            // The scattering angle between the light's travel (L to p) and the way to the eye
            // (-V): cos α = -x / r = -sin β / sqrt(κ² cos² β + sin² β), κ = h / H. So
            // ∫ e dz = σs I / (a1 H) ∫ p(cos α(κ, β)) dβ; κ = 1 when a0 = 0. For κ -> 0 (the
            // ray passes near L) cos α turns from +1 to -1 around β = 0: split there.
            const double kappa = h / H;
            auto integrand = [&](double beta) { return p(simplified_cos_alpha(kappa, beta)); };
            const double b0 = std::atan((z0 - z_s) / H), b1 = std::atan((z1 - z_s) / H);
            double sum = 0.0;
            if (b0 < 0.0 && b1 > 0.0) {
                sum = integrate(integrand, b0, 0.0, 1e-14) + integrate(integrand, 0.0, b1, 1e-14);
            } else {
                sum = integrate(integrand, b0, b1, 1e-14);
            }
            result[c] = sigma_s * intensity / (a1 * H) * sum;
            continue;
        }
        if (medium.model == MediumModel::physical && h > grazing) {
            // Sun et al. 2005, with a phase function. e = σs p(α) I e^(-σt (z + r)) / r². With
            // z - z_s = h tan θ (θ the angle at L from the ray's closest point), r = h / cos θ
            // and dz / r² = dθ / h. Sun's angle variable is ξ = π/4 + θ / 2, so dθ = 2 dξ and
            // z + r = z_s + h (tan θ + sec θ) = z_s + h tan ξ (tan θ + sec θ = tan(π/4 + θ/2)).
            // The scattering angle: cos α = -x / r = -sin θ = -sin(2ξ - π/2) = cos 2ξ, so
            // α = θ(ζ) = 2ζ along the ray, a function of the angle variable alone, and
            // ∫ e dz = 2 σs I / h ∫_{ξ0}^{ξ1} e^(-σt (z_s + h tan ζ)) p(cos 2ζ) dζ
            //        = 2 σs I e^(-σt z_s) / h (F_p(σt h, ξ1) - F_p(σt h, ξ0)),
            // with F_p(u, v) = ∫_0^v e^(-u tan ζ) p(cos 2ζ) dζ; for p = 1/4π this is Sun's
            // A0 F(A1, ξ). The exponent is kept whole here: z + r >= 0 on the ray, so nothing
            // overflows however dense the medium.
            const double sigma_t = medium.sigma_t()[c];
            // ξ = π/4 + atan((z - z_s) / h) / 2, as atan2: it keeps its digits where it nears
            // 0 (toward the light) or π/2 (away from it).
            auto xi = [&](double z) { return 0.5 * std::atan2(h, z_s - z); };
            const double f = integrate(
                [&](double zeta) {
                    return std::exp(-sigma_t * (z_s + h * std::tan(zeta))) *
                           p(std::cos(2.0 * zeta));
                },
                xi(z0), xi(z1), 1e-14);
            result[c] = 2.0 * sigma_s * intensity / h * f;
            continue;
        }
        // No closed form: adaptive quadrature of e(z) itself.
        result[c] = integrate(
            [&](double z) {
                return unbounded_density(ray, z, position, light_intensity, medium)[c];
            },
            z0, z1, 1e-12);
    }
    return result;
}

// A smooth edge's integral over [z0, z1]: the hard edge's closed form over the inner cone (half-
// angle cone - falloff, factor 1), plus shell(interval) for each of the ray's two shell intervals
// between the inner and the outer cone (from t = 0 on, so that the GPU's pieces, which cannot see
// z0, are the same), with `closest` of the ray.
template <typename Shell>
dvec3 smooth_edge_integral(const EyeRay& ray, double z0, double z1, const SpotLight& light,
                           const Medium& medium, const Shell& shell) {
    constexpr double kUnbounded = 1e30;  // the range's far plane bounds the interval
    const double cone = glm::radians(double(light.cone_half_angle_degrees));
    const double inner_angle = cone - glm::radians(double(light.falloff_degrees));
    const Interval outer = cone_interval(ray, light, cone, kUnbounded);
    Interval inner =
        inner_angle > 0.0 ? cone_interval(ray, light, inner_angle, kUnbounded) : Interval{};
    inner = {std::max(inner.begin, outer.begin), std::min(inner.end, outer.end)};
    if (inner.empty()) {
        inner = {outer.end, outer.end};
    }
    dvec3 result = in_scattering_hard_edge(ray, std::max(z0, inner.begin), std::min(z1, inner.end),
                                           light, medium);
    const Closest closest = closest_approach(ray, dvec3(light.position));
    for (const Interval part :
         {Interval{outer.begin, inner.begin}, Interval{inner.end, outer.end}}) {
        if (!part.empty()) {
            result += shell(part, closest);
        }
    }
    return result;
}

}  // namespace

namespace {

dvec3 parallel_integral(const EyeRay& ray, double z0, double z1, const SpotLight& light,
                        const Medium& medium) {
    // e(z) = σs p(cos α) E T(z) T(s(z)) with cos α = -a·V constant and s(z) = a·(O - P) + z a·V
    // linear: ∫ e dz = σs p E e^(-σt a·(O - P)) ∫ e^(-k z) dz, k = σt (1 + a·V) >= 0, written
    // with expm1 so that k -> 0 (a ray along the light, or no extinction) keeps its digits.
    const dvec3 a = axis(light);
    const double va = glm::dot(a, ray.direction);
    const double wa = glm::dot(a, ray.origin - dvec3(light.position));
    const dvec3 source =
        dvec3(medium.sigma_s) * phase(medium.phase, medium.g, -va) * dvec3(light.intensity);
    const double length = z1 - z0;
    if (medium.model == MediumModel::simplified) {
        return source * length;
    }
    dvec3 result;
    for (int c = 0; c < 3; ++c) {
        const double sigma_t = double(medium.sigma_t()[c]);
        const double k = sigma_t * std::max(0.0, 1.0 + va);
        const double integral = k > 0.0 ? -std::expm1(-k * length) / k : length;
        result[c] = source[c] * std::exp(-sigma_t * wa - k * z0) * integral;
    }
    return result;
}

}  // namespace

dvec3 in_scattering_hard_edge(const EyeRay& ray, double z0, double z1, const SpotLight& light,
                              const Medium& medium) {
    const Interval lit = light_interval(ray, light, std::max(z0, z1));
    z0 = std::max(z0, lit.begin);
    z1 = std::min(z1, lit.end);
    if (!(z1 > z0)) {
        return dvec3(0.0);
    }
    if (light.parallel()) {
        return parallel_integral(ray, z0, z1, light, medium);
    }
    return hard_edge_integral(ray, z0, z1, dvec3(light.position), dvec3(light.intensity), medium);
}

dvec3 in_scattering(const EyeRay& ray, double z0, double z1, const PointLight& light,
                    const Medium& medium) {
    Interval parts[2];
    const int count = point_light_intervals(ray, light, std::max(z0, z1), parts);
    dvec3 sum(0.0);
    for (int i = 0; i < count; ++i) {
        const double a = std::max(z0, parts[i].begin), b = std::min(z1, parts[i].end);
        if (b > a) {
            sum += hard_edge_integral(ray, a, b, dvec3(light.position), dvec3(light.intensity),
                                      medium);
        }
    }
    return sum;
}

dvec3 in_scattering(const EyeRay& ray, double z0, double z1, const SpotLight& light,
                    const Medium& medium) {
    if (!light.smooth_edge()) {
        return in_scattering_hard_edge(ray, z0, z1, light, medium);
    }
    // The shell by quadrature of e(z), cut where the cone factor has its kinks (the inner and
    // outer cones).
    return smooth_edge_integral(ray, z0, z1, light, medium, [&](Interval shell, Closest closest) {
        const double a = std::max(z0, shell.begin), b = std::min(z1, shell.end);
        dvec3 sum(0.0);
        if (!(b > a))
            return sum;
        const double h = closest.h, z_s = closest.z_s;
        for (int c = 0; c < 3; ++c) {
            auto e = [&](double z) { return scattering_density(ray, z, light, medium)[c]; };
            if (h <= closest.grazing) {
                sum[c] = integrate(e, a, b, 1e-12);
                continue;
            }
            // In the angle at L, z = z_s + h tan θ: e dz = e(z(θ)) h sec² θ dθ has no 1/r² peak
            // (e r² is bounded), so the quadrature converges in a few pieces.
            sum[c] = integrate(
                [&](double t) {
                    const double cos_t = std::cos(t);
                    return e(z_s + h * std::tan(t)) * h / (cos_t * cos_t);
                },
                std::atan((a - z_s) / h), std::atan((b - z_s) / h), 1e-12);
        }
        return sum;
    });
}

dvec3 in_scattering_pieces(const EyeRay& ray, double z0, double z1, const SpotLight& light,
                           const Medium& medium, int pieces) {
    if (!light.smooth_edge()) {
        return in_scattering_hard_edge(ray, z0, z1, light, medium);
    }
    return smooth_edge_integral(ray, z0, z1, light, medium, [&](Interval shell, Closest closest) {
        closest.h = std::max(closest.h, 1e-9);
        // Equal pieces of the angle at L, θ = atan((z - z_s) / h): e dz is nearly uniform in θ
        // (exactly so for 1/r² alone), so each piece carries a like share of the integral.
        const double t0 = std::atan((shell.begin - closest.z_s) / closest.h);
        const double t1 = std::atan((shell.end - closest.z_s) / closest.h);
        auto z_at = [&](double t) { return closest.z_s + closest.h * std::tan(t); };
        dvec3 sum(0.0);
        for (int k = 0; k < pieces; ++k) {
            const double ta = t0 + (t1 - t0) * k / pieces;
            const double tb = t0 + (t1 - t0) * (k + 1) / pieces;
            const double a = k == 0 ? shell.begin : z_at(ta);
            const double b = k + 1 == pieces ? shell.end : z_at(tb);
            const double lo = std::max(z0, a), hi = std::min(z1, b);
            if (!(hi > lo))
                continue;
            const double weight =
                light.cone_factor(ray.origin + z_at(0.5 * (ta + tb)) * ray.direction);
            if (weight > 0.0)
                sum += weight * hard_edge_integral(ray, lo, hi, dvec3(light.position),
                                                   dvec3(light.intensity), medium);
        }
        return sum;
    });
}

}  // namespace sl::analytic
