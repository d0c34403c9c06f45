#include "sss/diffusion.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.h"

namespace sl::sss {

namespace {

constexpr double pi = std::numbers::pi;

// One pole's term (1 + σtr d) e^(−σtr d) / (4π d³), shared by the dipole and the multipole.
double pole(double distance, double sigma_tr) {
    return (1.0 + sigma_tr * distance) * std::exp(-sigma_tr * distance) /
           (4.0 * pi * distance * distance * distance);
}

}  // namespace

double fresnel_diffuse_reflectance(double eta) {
    // Egan & Hilgeman's fit (§3.4.1). For η > 1 with the coefficients of Jensen et al. 2001
    // (−1.440, 0.710, 0.668, 0.0636: F_dr(1.3) = 0.44476, A = 2.60206); the seed prints them as
    // −1.4399, 0.7099, 0.6681, which moves A(1.3) by 5e-4.
    if (eta < 1.0) {
        return -0.4399 + 0.7099 / eta - 0.3319 / (eta * eta) + 0.0636 / (eta * eta * eta);
    }
    return -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
}

double boundary_term(double eta) {
    const double fdr = fresnel_diffuse_reflectance(eta);
    return (1.0 + fdr) / (1.0 - fdr);
}

Diffusion Diffusion::of(double sigma_s_reduced, double sigma_a, double eta) {
    // §4.2.2: σt' = σs' + σa, σtr = √(3σt'σa), α' = σs'/σt', D = 1/(3σt'), z_r = 1/σt',
    // z_v = z_r + 4AD.
    Diffusion d;
    d.sigma_t_reduced = sigma_s_reduced + sigma_a;
    d.sigma_tr = std::sqrt(3.0 * d.sigma_t_reduced * sigma_a);
    d.albedo_reduced = sigma_s_reduced / d.sigma_t_reduced;
    d.D = 1.0 / (3.0 * d.sigma_t_reduced);
    d.A = boundary_term(eta);
    d.z_r = 1.0 / d.sigma_t_reduced;
    d.z_v = d.z_r + 4.0 * d.A * d.D;
    return d;
}

RgbDiffusion RgbDiffusion::of(const ScatteringMaterial& m) {
    validate(m);
    RgbDiffusion d;
    for (int c = 0; c < 3; ++c) {
        d.channel[c] = Diffusion::of(m.sigma_s_reduced[c], m.sigma_a[c], m.eta);
    }
    return d;
}

double dipole_rd(double r, const Diffusion& d) {
    // R_d(r) = α'/(4π) [z_r (σtr d_r + 1) e^(−σtr d_r)/d_r³ + z_v (σtr d_v + 1) e^(−σtr d_v)/d_v³]
    // (§3.4.1; the seed writes z_r as 1/σt' and z_v as (1 + 4A/3)/σt').
    const double d_r = std::sqrt(r * r + d.z_r * d.z_r);
    const double d_v = std::sqrt(r * r + d.z_v * d.z_v);
    return d.albedo_reduced * (d.z_r * pole(d_r, d.sigma_tr) + d.z_v * pole(d_v, d.sigma_tr));
}

dvec3 dipole_rd(double r, const RgbDiffusion& d) {
    return {dipole_rd(r, d[0]), dipole_rd(r, d[1]), dipole_rd(r, d[2])};
}

double total_diffuse_reflectance(const Diffusion& d) {
    // R_d = (α'/2)(1 + e^(−(4/3)A√(3(1−α')))) e^(−√(3(1−α'))).
    const double s = std::sqrt(3.0 * (1.0 - d.albedo_reduced));
    return 0.5 * d.albedo_reduced * (1.0 + std::exp(-4.0 / 3.0 * d.A * s)) * std::exp(-s);
}

ReflectanceTransmittance multipole(double r, double thickness, const Diffusion& d, int pairs) {
    // Eq. 3.5-3.6 with z_b = 2AD at both faces (a slab in air): z_r,i = 2i(d + 2z_b) + l,
    // z_v,i = 2i(d + 2z_b) − l − 2z_b, l = 1/σt'. Pair 0 is the dipole.
    const double l = d.z_r;
    const double z_b = 2.0 * d.A * d.D;
    ReflectanceTransmittance rt;
    for (int i = -pairs; i <= pairs; ++i) {
        const double shift = 2.0 * i * (thickness + 2.0 * z_b);
        const double z_ri = shift + l;
        const double z_vi = shift - l - 2.0 * z_b;
        rt.R += z_ri * pole(std::sqrt(r * r + z_ri * z_ri), d.sigma_tr) -
                z_vi * pole(std::sqrt(r * r + z_vi * z_vi), d.sigma_tr);
        const double t_ri = thickness - z_ri, t_vi = thickness - z_vi;
        rt.T += t_ri * pole(std::sqrt(r * r + t_ri * t_ri), d.sigma_tr) -
                t_vi * pole(std::sqrt(r * r + t_vi * t_vi), d.sigma_tr);
    }
    rt.R *= d.albedo_reduced;
    rt.T *= d.albedo_reduced;
    return rt;
}

double simpson(const std::function<double(double)>& f, double a, double b, int samples) {
    // Listing 5.1: (h/3)[f(a) + 4f(a+h) + 2f(a+2h) + ... + f(b)].
    samples = std::max(2, samples + (samples & 1));
    const double h = (b - a) / samples;
    double sum = f(a) + f(b);
    for (int i = 1; i < samples; ++i) {
        sum += (i % 2 == 0 ? 2.0 : 4.0) * f(a + i * h);
    }
    return sum * h / 3.0;
}

double splat_radius(const RgbDiffusion& d, double epsilon, bool area_weighted) {
    if (!(epsilon > 0.0 && epsilon < 1.0)) {
        fail("splat radius: epsilon must lie in (0, 1), got {}", epsilon);
    }
    double r_max = 0.0;
    for (int c = 0; c < 3; ++c) {
        const Diffusion& dc = d[c];
        auto f = [&](double r) { return dipole_rd(r, dc) * (area_weighted ? 2.0 * pi * r : 1.0); };
        const double r_inf = std::max(100.0, 50.0 * dc.z_v);
        // Cumulative composite Simpson over a fine grid in r; the profile is smooth (§4.3).
        constexpr int steps = 1 << 14;
        const double h = r_inf / steps;
        std::vector<double> cumulative(steps / 2 + 1, 0.0);
        for (int k = 1; k <= steps / 2; ++k) {
            const double a = (2 * k - 2) * h;
            cumulative[size_t(k)] =
                cumulative[size_t(k) - 1] + h / 3.0 * (f(a) + 4.0 * f(a + h) + f(a + 2 * h));
        }
        const double total = cumulative.back();
        size_t k = 0;
        while (k + 1 < cumulative.size() && (total - cumulative[k]) / total >= epsilon) {
            ++k;
        }
        r_max = std::max(r_max, 2.0 * double(k) * h);
    }
    return r_max;
}

glm::vec3 RadialProfile::lookup(double r) const {
    const double s = std::clamp(r / r_max, 0.0, 1.0) * double(texels.size() - 1);
    const size_t i = std::min(size_t(s), texels.size() - 2);
    const float t = float(s - double(i));
    return texels[i] * (1.0f - t) + texels[i + 1] * t;
}

RadialProfile tabulate_dipole(const RgbDiffusion& d, double r_max, int size) {
    if (size < 2 || !(r_max > 0.0)) {
        fail("dipole profile: needs at least 2 texels and r_max > 0");
    }
    RadialProfile p;
    p.r_max = r_max;
    p.texels.resize(size_t(size));
    for (int i = 0; i + 1 < size; ++i) {
        p.texels[size_t(i)] = glm::vec3(dipole_rd(r_max * i / (size - 1), d));
    }
    p.texels.back() = glm::vec3(0.0f);  // §5.2.2: beyond r_max the clamped lookup reads zero
    return p;
}

namespace {

glm::vec3 bilinear(const std::vector<glm::vec3>& values, int width, int height, double u,
                   double v) {
    const double s = std::clamp(u, 0.0, 1.0) * (width - 1);
    const double t = std::clamp(v, 0.0, 1.0) * (height - 1);
    const int i = std::min(int(s), width - 2), j = std::min(int(t), std::max(height - 2, 0));
    const float a = float(s - i), b = height > 1 ? float(t - j) : 0.0f;
    auto at = [&](int x, int y) { return values[size_t(std::min(y, height - 1) * width + x)]; };
    return (at(i, j) * (1 - a) + at(i + 1, j) * a) * (1 - b) +
           (at(i, j + 1) * (1 - a) + at(i + 1, j + 1) * a) * b;
}

}  // namespace

glm::vec3 SlabProfiles::lookup_R(double r, double d) const {
    return bilinear(R, width, height, r / r_max, (d - d_min) / (d_max - d_min));
}

glm::vec3 SlabProfiles::lookup_T(double r, double d) const {
    return bilinear(T, width, height, r / r_max, (d - d_min) / (d_max - d_min));
}

SlabProfiles tabulate_multipole(const RgbDiffusion& d, double r_max, double d_min, double d_max,
                                int width, int height, int pairs) {
    if (width < 2 || height < 2 || !(r_max > 0.0) || !(d_min > 0.0) || !(d_max > d_min)) {
        fail("multipole profiles: need 2x2 texels, r_max > 0 and 0 < d_min < d_max");
    }
    SlabProfiles p;
    p.r_max = r_max;
    p.d_min = d_min;
    p.d_max = d_max;
    p.width = width;
    p.height = height;
    p.R.assign(size_t(width * height), glm::vec3(0.0f));
    p.T.assign(size_t(width * height), glm::vec3(0.0f));
    for (int j = 0; j < height; ++j) {
        const double thickness = d_min + (d_max - d_min) * j / (height - 1);
        for (int i = 0; i + 1 < width; ++i) {
            const double r = r_max * i / (width - 1);
            for (int c = 0; c < 3; ++c) {
                const ReflectanceTransmittance rt = multipole(r, thickness, d[c], pairs);
                p.R[size_t(j * width + i)][c] = float(std::max(rt.R, 0.0));
                p.T[size_t(j * width + i)][c] = float(std::max(rt.T, 0.0));
            }
        }
    }
    return p;
}

std::vector<glm::vec3> disk_average(const std::function<glm::vec3(double)>& profile, double r_max,
                                    int texels, double rho) {
    std::vector<glm::vec3> out(size_t(texels), glm::vec3(0.0f));
    // Midpoint rule in polar coordinates around the source, area-weighted (s ds dφ), over the
    // half disk (the profile is symmetric about the line to x).
    constexpr int radial = 12, angular = 16;
    for (int i = 0; i + 1 < texels; ++i) {
        const double r = r_max * i / (texels - 1);
        glm::dvec3 sum(0.0);
        double weight = 0.0;
        for (int a = 0; a < radial; ++a) {
            const double s = rho * (a + 0.5) / radial;
            for (int b = 0; b < angular; ++b) {
                const double phi = pi * (b + 0.5) / angular;
                const double distance =
                    std::sqrt(std::max(0.0, r * r + s * s - 2.0 * r * s * std::cos(phi)));
                sum += glm::dvec3(profile(distance)) * s;
                weight += s;
            }
        }
        out[size_t(i)] = glm::vec3(sum / weight);
    }
    return out;
}

double FootprintLevels::radius(int k) const {
    const double t = double(k) / (levels - 1);
    return rho_max * t * t;
}

double FootprintLevels::coordinate(double rho) const {
    return std::sqrt(std::clamp(rho / rho_max, 0.0, 1.0)) * (levels - 1);
}

}  // namespace sl::sss
