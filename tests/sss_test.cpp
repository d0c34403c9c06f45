// Translucent materials on the CPU against closed forms and quadrature: the F_dr fit, the dipole's
// total reflectance, multipole limits, the layer combination and the uniform surface samples.

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/error.h"
#include "materials/scattering_material.h"
#include "scenes/scene_file.h"
#include "sss/diffusion.h"
#include "sss/layers.h"
#include "sss/surface_samples.h"

namespace sl::test {
namespace {

constexpr double pi = std::numbers::pi;

// ∫_0^∞ f(r) 2πr dr through r = s u/(1−u), Simpson in u on [0, 1): the tail maps into a finite
// interval, so the slowly decaying profiles of weakly absorbing materials converge too.
double plane_integral(const std::function<double(double)>& f, double scale, int samples = 200000) {
    return sss::simpson(
        [&](double u) {
            if (u >= 1.0)
                return 0.0;
            const double r = scale * u / (1.0 - u);
            const double dr = scale / ((1.0 - u) * (1.0 - u));
            return f(r) * 2.0 * pi * r * dr;
        },
        0.0, 1.0, samples);
}

TEST(SssDiffusion, FresnelFitAndBoundaryTermMatchTheSeed) {
    EXPECT_NEAR(sss::fresnel_diffuse_reflectance(1.3), 0.44476, 1e-4);
    EXPECT_NEAR(sss::boundary_term(1.3), 2.60206, 1e-4);
    EXPECT_NEAR(sss::boundary_term(1.5), 3.95950, 1e-4);
    // Matched media reflect (almost) nothing from either branch of the fit.
    EXPECT_NEAR(sss::fresnel_diffuse_reflectance(1.0), 0.0, 0.01);
    EXPECT_NEAR(sss::fresnel_diffuse_reflectance(0.9999), 0.0, 0.01);
}

// ∫ R_d(r) 2πr dr equals Jensen's closed form total diffuse reflectance.
TEST(SssDiffusion, DipoleIntegratesToTheClosedFormTotalReflectance) {
    for (const char* name : {"marble", "apple", "skin1", "ketchup", "skimmilk", "jade"}) {
        const sss::RgbDiffusion d = sss::RgbDiffusion::of(sss::material_preset(name));
        for (int c = 0; c < 3; ++c) {
            const double numeric =
                plane_integral([&](double r) { return sss::dipole_rd(r, d[c]); }, d[c].z_v);
            EXPECT_NEAR(numeric, sss::total_diffuse_reflectance(d[c]), 1e-4) << name << " " << c;
        }
    }
}

TEST(SssDiffusion, ConversionsOfSection421) {
    // σs' = σs (1 − g); table 4.3: marble's complex index gives σa = 2.1, 4.1, 7.1 per metre.
    EXPECT_EQ(sss::reduced_scattering({2.0, 3.0, 4.0}, 0.25), sss::dvec3(1.5, 2.25, 3.0));
    EXPECT_NEAR(sss::absorption_from_complex_ior(1.16979e-7, 700e-9), 2.1, 0.01);
    EXPECT_NEAR(sss::absorption_from_complex_ior(1.79447e-7, 550e-9), 4.1, 0.01);
    EXPECT_NEAR(sss::absorption_from_complex_ior(2.40125e-7, 425e-9), 7.1, 0.01);
    EXPECT_THROW(sss::material_preset("unobtainium"), Error);
    sss::ScatteringMaterial bad = sss::material_preset("marble");
    bad.sigma_a.y = std::nan("");
    EXPECT_THROW(sss::RgbDiffusion::of(bad), Error);
}

// Thick slabs reflect as the semi-infinite dipole and transmit nothing; thin ones transmit.
TEST(SssDiffusion, MultipoleTendsToTheDipoleAsTheSlabThickens) {
    const sss::RgbDiffusion d = sss::RgbDiffusion::of(sss::material_preset("marble"));
    for (int c = 0; c < 3; ++c) {
        const double mfp = 1.0 / d[c].sigma_t_reduced;
        double previous_T = INFINITY;
        for (const double thickness : {2.0, 10.0, 20.0, 80.0, 400.0}) {
            const double total_T = plane_integral(
                [&](double r) { return sss::multipole(r, thickness * mfp, d[c]).T; }, mfp, 20000);
            EXPECT_LT(total_T, previous_T) << "thickness " << thickness;
            previous_T = total_T;
        }
        EXPECT_LT(previous_T, 1e-3);
        for (const double r : {0.0, 0.3, 1.0, 3.0}) {
            const double dipole = sss::dipole_rd(r, d[c]);
            EXPECT_NEAR(sss::multipole(r, 400.0 * mfp, d[c]).R, dipole, 1e-6 * dipole + 1e-12)
                << "r " << r;
        }
    }
}

TEST(SssDiffusion, SplatRadiusLeavesEpsilonOfTheProfile) {
    const sss::RgbDiffusion d = sss::RgbDiffusion::of(sss::material_preset("marble"));
    for (const bool area_weighted : {false, true}) {
        const double r_max = sss::splat_radius(d, 0.01, area_weighted);
        for (int c = 0; c < 3; ++c) {
            auto f = [&](double r) {
                return sss::dipole_rd(r, d[c]) * (area_weighted ? 2 * pi * r : 1.0);
            };
            const double total = sss::simpson(f, 0.0, 200.0, 400000);
            EXPECT_LT((total - sss::simpson(f, 0.0, r_max, 100000)) / total, 0.0101);
        }
        // The widest channel needs all of it: at 0.95 r_max its tail is above ε.
        double worst = 0.0;
        for (int c = 0; c < 3; ++c) {
            auto f = [&](double r) {
                return sss::dipole_rd(r, d[c]) * (area_weighted ? 2 * pi * r : 1.0);
            };
            const double total = sss::simpson(f, 0.0, 200.0, 400000);
            worst = std::max(worst, (total - sss::simpson(f, 0.0, 0.95 * r_max, 100000)) / total);
        }
        EXPECT_GT(worst, 0.01);
    }
    // The tabulated profile reads the dipole at texel centres and zero from r_max on.
    const double r_max = sss::splat_radius(d);
    const sss::RadialProfile profile = sss::tabulate_dipole(d, r_max, 256);
    EXPECT_NEAR(profile.lookup(r_max * 10 / 255.0).x, sss::dipole_rd(r_max * 10 / 255.0, d).x,
                1e-5 * sss::dipole_rd(0.0, d).x);
    EXPECT_EQ(profile.lookup(r_max).x, 0.0f);
    EXPECT_EQ(profile.lookup(2.0 * r_max).y, 0.0f);
}

// Kubelka-Munk with a black second layer leaves the first layer's reflectance; the DC terms
// are the layers' total reflectance and transmittance.
TEST(SssLayers, CombinationHasItsLimits) {
    const sss::Diffusion d = sss::RgbDiffusion::of(sss::material_preset("skin1"))[0];
    const double thickness = 1.5;
    auto R1 = [&](double r) { return sss::multipole(r, thickness, d).R; };
    auto T1 = [&](double r) { return sss::multipole(r, thickness, d).T; };
    const double extent = 12.0;
    const sss::CombinedLayers one = sss::combine_layers({{R1, T1}}, extent, 256);
    const sss::CombinedLayers black =
        sss::combine_layers({{R1, T1}, {[](double) { return 0.0; }, T1}}, extent, 256);
    for (size_t k = 0; k < one.R.size(); k += 7) {
        EXPECT_NEAR(black.R[k], one.R[k], 1e-12 + 1e-9 * one.R[k]) << "R12 = R1 at k " << k;
    }
    // The DC term is ∫ R dA: against radial quadrature of the same truncated profile.
    auto truncated = [&](const std::function<double(double)>& f) {
        return [&, f](double r) { return r < extent ? f(r) : 0.0; };
    };
    const double total_R = plane_integral(truncated(R1), d.z_r);
    const double total_T = plane_integral(truncated(T1), d.z_r);
    EXPECT_NEAR(one.total_R, total_R, 0.01 * total_R);
    EXPECT_NEAR(one.total_T, total_T, 0.01 * total_T);
    // The inverse transform gives the profile back.
    EXPECT_NEAR(one.R[10], R1(10 * one.spacing), 1e-6 * R1(0.0));
    // Two layers: T12(0) ≤ T1 T2 / (1 − R1 R2) at DC, and the series adds reflectance.
    const sss::CombinedLayers two = sss::combine_layers({{R1, T1}, {R1, T1}}, extent, 256);
    EXPECT_NEAR(two.total_T, one.total_T * one.total_T / (1 - one.total_R * one.total_R), 1e-9);
    EXPECT_GT(two.total_R, one.total_R);
    EXPECT_THROW(sss::combine_layers({}, extent, 256), Error);
    EXPECT_THROW(sss::combine_layers({{R1, T1}}, extent, 7), Error);
}

TEST(SssLayers, LayeredProfileOfASemiInfiniteBaseIsItsDipole) {
    // One semi-infinite layer: the combined profile is the tabulated dipole.
    const sss::ScatteringMaterial marble = sss::material_preset("marble");
    const sss::RgbDiffusion d = sss::RgbDiffusion::of(marble);
    const double extent = 20.0;
    const sss::LayeredProfile p = sss::layered_profile({{marble, 0.0}}, extent, 256, 128);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(p.total_R[c], sss::total_diffuse_reflectance(d[c]), 0.02) << c;
        EXPECT_EQ(p.total_T[c], 0.0);
    }
    const double r = extent * 20 / 127.0;
    EXPECT_NEAR(p.reflectance.lookup(r).z, sss::dipole_rd(r, d[2]), 1e-3 * sss::dipole_rd(0, d[2]));
    EXPECT_THROW(sss::layered_profile({{marble, -1.0}}, extent), Error);
}

TEST(SssSamples, EliminationMakesRandomPointsUniform) {
    Mesh bunny = load_mesh(SceneSearchPaths::defaults().data / "meshes" / "bunny00.off");
    fit_mesh(bunny, 1.0f);
    const sss::SurfaceSamples candidates =
        sss::random_surface_points(bunny, glm::mat4(1.0f), 5000, 1);
    EXPECT_NEAR(candidates.area, bunny.area(), 1e-4 * bunny.area());
    const sss::SurfaceSamples random = sss::random_surface_points(bunny, glm::mat4(1.0f), 1000, 2);
    const sss::SurfaceSamples uniform = sss::eliminate_samples(candidates, 1000);
    ASSERT_EQ(uniform.positions.size(), 1000u);
    const sss::Uniformity before = sss::measure_uniformity(random.positions, random.area);
    const sss::Uniformity after = sss::measure_uniformity(uniform.positions, uniform.area);
    EXPECT_GT(after.relative_radius, 3.0 * before.relative_radius);
    EXPECT_GT(after.relative_radius, 0.3);
    EXPECT_LT(after.nearest_cv, 0.5 * before.nearest_cv);
    for (const glm::vec3& n : uniform.normals) {
        ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
    }
    EXPECT_THROW(sss::eliminate_samples(candidates, 6000), Error);
}

}  // namespace
}  // namespace sl::test
