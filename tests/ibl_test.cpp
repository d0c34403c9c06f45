// The IBL maths on the CPU (ibl/): cube-map addressing, the microfacet terms, the DFG table, SH9
// and both prefilters, each against an oracle that needs no probe image (closed forms, numerical
// quadrature, brute-force integration of the lobe).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <random>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "ibl/cube_map.h"
#include "ibl/environment.h"
#include "ibl/microfacet.h"
#include "ibl/prefilter.h"
#include "ibl/sh9.h"
#include "scenes/scene_file.h"
#include "tests/support.h"

namespace sl::ibl {
namespace {

constexpr double kPi = std::numbers::pi;

// Composite Simpson on [a, b] with n (even) intervals.
template <typename F>
double simpson(F&& f, double a, double b, int n) {
    const double h = (b - a) / n;
    double sum = f(a) + f(b);
    for (int i = 1; i < n; ++i)
        sum += f(a + i * h) * (i % 2 ? 4.0 : 2.0);
    return sum * h / 3.0;
}

// A small, strongly varying environment: Blender's courtyard studio light at 16² per face.
const CubeMap& courtyard16() {
    static const CubeMap cube = [] {
        const SceneSearchPaths paths = SceneSearchPaths::defaults();
        return cube_from_equirect(load_equirect(paths.environments / "courtyard.exr"), 16, 0.0f, 4);
    }();
    return cube;
}

// cube_direction and cube_coordinates invert each other on every face (GL table 8.19 layout).
TEST(CubeMap, FaceAddressingRoundTrips) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.02f, 0.98f);
    for (int f = 0; f < 6; ++f) {
        for (int i = 0; i < 50; ++i) {
            const glm::vec2 st(u(rng), u(rng));
            const CubeCoordinates c = cube_coordinates(cube_direction(f, st));
            EXPECT_EQ(c.face, f);
            EXPECT_NEAR(c.st.x, st.x, 1e-5f);
            EXPECT_NEAR(c.st.y, st.y, 1e-5f);
        }
    }
    // GL's +X face: s grows towards -z, t towards -y.
    EXPECT_GT(cube_direction(0, {0.9f, 0.5f}).z, 0.0f - 1e-6f - 1.0f);
    EXPECT_LT(cube_direction(0, {0.9f, 0.5f}).z, 0.0f);
    EXPECT_LT(cube_direction(0, {0.5f, 0.9f}).y, 0.0f);
    EXPECT_GT(cube_direction(2, {0.5f, 0.9f}).z, 0.0f);  // +Y: t grows towards +z
}

// The exact texel solid angles tile the sphere: they sum to 4π at any resolution.
TEST(CubeMap, TexelSolidAnglesSumToFourPi) {
    for (int size : {1, 3, 16, 64}) {
        double sum = 0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                sum += 6.0 * texel_solid_angle(size, x, y);
        EXPECT_NEAR(sum, 4.0 * kPi, 1e-5) << size;
    }
}

// Equirectangular uv and direction invert each other, with and without rotation.
TEST(CubeMap, EquirectMappingRoundTrips) {
    for (float rotation : {0.0f, 37.0f}) {
        for (glm::vec2 uv :
             {glm::vec2(0.1f, 0.2f), glm::vec2(0.5f, 0.5f), glm::vec2(0.93f, 0.81f)}) {
            const glm::vec2 back = equirect_uv(equirect_direction(uv, rotation), rotation);
            EXPECT_NEAR(back.x, uv.x, 1e-5f);
            EXPECT_NEAR(back.y, uv.y, 1e-5f);
        }
    }
    EXPECT_NEAR(equirect_uv({0, 1, 0}).y, 0.0f, 1e-6f);   // zenith: top row
    EXPECT_NEAR(equirect_uv({0, 0, -1}).x, 0.5f, 1e-6f);  // -z: the image's centre
}

// ∫ D(h)(n·h) dω_h = 1 for Beckmann and GGX at several roughness values (Simpson in μ = cos θ:
// 2π ∫₀¹ D(μ) μ dμ).
TEST(Microfacet, DistributionsAreNormalised) {
    for (Distribution d : {Distribution::beckmann, Distribution::ggx}) {
        for (float alpha : {0.05f, 0.1f, 0.3f, 0.6f, 1.0f}) {
            const double integral =
                2.0 * kPi *
                simpson([&](double mu) { return double(distribution(d, alpha, float(mu))) * mu; },
                        0.0, 1.0, 200000);
            EXPECT_NEAR(integral, 1.0, 2e-3) << to_string(d) << " alpha " << alpha;
        }
    }
}

// sample_half_vector draws h with density D(h)(n·h): the fraction of samples with cos θ_h > c
// matches 2π ∫_c^1 D μ dμ.
TEST(Microfacet, HalfVectorSamplingFollowsTheDistribution) {
    const int n = 20000;
    for (Distribution d : {Distribution::beckmann, Distribution::ggx}) {
        for (float alpha : {0.1f, 0.5f}) {
            for (double c : {0.9, 0.99}) {
                int above = 0;
                for (int i = 0; i < n; ++i) {
                    above +=
                        sample_half_vector(d, alpha, hammersley(uint32_t(i), uint32_t(n))).z > c;
                }
                const double expected =
                    2.0 * kPi *
                    simpson(
                        [&](double mu) { return double(distribution(d, alpha, float(mu))) * mu; },
                        c, 1.0, 20000);
                EXPECT_NEAR(double(above) / n, expected, 2e-3) << to_string(d) << " " << alpha;
            }
        }
    }
}

// The cosine-weighted hemispherical average of Schlick's Fresnel is F0 + (1 − F0)/21.
TEST(Microfacet, SchlickHemisphericalAverage) {
    for (float f0 : {0.0f, 0.04f, 0.5f, 0.95f}) {
        const double average =
            2.0 * simpson([&](double mu) { return double(fresnel_schlick(f0, float(mu))) * mu; },
                          0.0, 1.0, 20000);
        EXPECT_NEAR(average, f0 + (1.0 - f0) / 21.0, 1e-6) << f0;
    }
}

// Moschos eq. 2.12 tends to 1 at normal incidence and to 0 at grazing; Smith GGX G1 likewise.
TEST(Microfacet, MaskingTermsHaveTheirLimits) {
    EXPECT_FLOAT_EQ(beckmann_g1(0.3f, 1.0f), 1.0f);
    EXPECT_LT(beckmann_g1(0.3f, 0.001f), 0.02f);
    EXPECT_NEAR(ggx_g1(0.3f, 1.0f), 1.0f, 1e-6f);
    EXPECT_LT(ggx_g1(0.3f, 0.01f), 0.07f);
    EXPECT_NEAR(ggx_g2(0.3f, 1.0f, 1.0f), 1.0f, 1e-6f);
}

// DFG table: A + B ≤ 1 everywhere (a single-scattering microfacet BRDF reflects at most what
// arrives), and (A, B) → (1, 0) as roughness → 0 at n·v = 1.
TEST(Microfacet, DfgTableIsBoundedAndHasItsSmoothLimit) {
    for (Distribution d : {Distribution::ggx, Distribution::beckmann}) {
        const DfgTable table = compute_dfg_table(d, 32, 1024);
        for (int j = 0; j < table.size; ++j)
            for (int i = 0; i < table.size; ++i) {
                const glm::vec2 ab = table.at(i, j);
                EXPECT_GE(ab.x, 0.0f);
                EXPECT_GE(ab.y, 0.0f);
                EXPECT_LE(ab.x + ab.y, 1.0f + 1e-3f) << i << "," << j;
            }
        for (float alpha : {1e-2f, 1e-3f, 1e-4f}) {
            const glm::vec2 ab = integrate_dfg(d, 1.0f, alpha, 1024);
            EXPECT_NEAR(ab.x, 1.0f, 10 * alpha);
            EXPECT_NEAR(ab.y, 0.0f, 10 * alpha);
        }
        const glm::vec2 corner = table.lookup(1.0f, 0.0f);  // a texel centre: exact
        EXPECT_NEAR(corner.x, 1.0f, 1e-4f);
        EXPECT_NEAR(corner.y, 0.0f, 1e-4f);
    }
}

// SH9 of radiance 1: L00 = 2√π, every other coefficient 0, irradiance π in every direction.
TEST(Sh9, ConstantRadiance) {
    const Sh9 sh = project_sh9(make_cube_map(32, [](glm::vec3) { return glm::vec3(1.0f); }));
    EXPECT_NEAR(sh.coefficients[0].x, 2.0 * std::sqrt(kPi), 1e-4);
    for (size_t i = 1; i < 9; ++i)
        EXPECT_NEAR(sh.coefficients[i].x, 0.0, 1e-5) << i;
    for (glm::vec3 n :
         {glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), glm::normalize(glm::vec3(1, -2, 3))})
        EXPECT_NEAR(sh.irradiance(n).x, kPi, 1e-4);
}

// SH9 of radiance max(z, 0): L00 = √π/2, L10 = √(π/3), L20 = √(5π)/8, the others 0.
TEST(Sh9, ClampedCosineRadiance) {
    const Sh9 sh =
        project_sh9(make_cube_map(128, [](glm::vec3 d) { return glm::vec3(std::max(d.z, 0.0f)); }));
    const double expected[9] = {
        std::sqrt(kPi) / 2, 0, std::sqrt(kPi / 3), 0, 0, 0, std::sqrt(5 * kPi) / 8, 0, 0};
    for (size_t i = 0; i < 9; ++i)
        EXPECT_NEAR(sh.coefficients[i].x, expected[i], 5e-4) << i;
}

// SH9 of radiance z (pure band 1): irradiance (2π/3) n_z in every direction.
TEST(Sh9, LinearRadianceGivesExactIrradiance) {
    const Sh9 sh = project_sh9(make_cube_map(128, [](glm::vec3 d) { return glm::vec3(d.z); }));
    std::mt19937 rng(5);
    std::normal_distribution<float> g;
    for (int i = 0; i < 20; ++i) {
        const glm::vec3 n = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
        EXPECT_NEAR(sh.irradiance(n).x, 2.0 * kPi / 3.0 * n.z, 5e-4);
    }
}

PrefilterSettings settings(PrefilterMethod method, Distribution d, int samples, bool filtered) {
    PrefilterSettings s;
    s.method = method;
    s.distribution = d;
    s.samples = samples;
    s.filtered = filtered;
    s.min_face_size = 2;
    return s;
}

// A constant environment stays constant at every level of both prefilters (self-normalised
// estimators, filtered lookups of a constant).
TEST(Prefilter, ConstantEnvironmentStaysConstant) {
    const CubeMap constant =
        make_cube_map(32, [](glm::vec3) { return glm::vec3(0.7f, 1.3f, 2.0f); });
    for (const PrefilterSettings& s :
         {settings(PrefilterMethod::cone, Distribution::beckmann, 32, false),
          settings(PrefilterMethod::importance, Distribution::ggx, 64, true),
          settings(PrefilterMethod::importance, Distribution::beckmann, 64, true),
          settings(PrefilterMethod::importance, Distribution::ggx, 64, false)}) {
        const PrefilteredChain chain = prefilter(constant, s);
        EXPECT_EQ(int(chain.levels.size()), chain_length(s.method, 32, 2));
        for (size_t l = 0; l < chain.levels.size(); ++l) {
            EXPECT_EQ(chain.levels[l].size, 32 >> l);
            for (const Image& face : chain.levels[l].faces)
                for (size_t i = 0; i < face.rgb.size(); i += 3) {
                    ASSERT_NEAR(face.rgb[i], 0.7f, 1e-5f) << s.describe() << " level " << l;
                    ASSERT_NEAR(face.rgb[i + 1], 1.3f, 1e-5f);
                    ASSERT_NEAR(face.rgb[i + 2], 2.0f, 1e-5f);
                }
        }
    }
}

// Each importance-sampled level (GGX and Beckmann, filtered importance sampling, 1024 samples)
// is within 2% relative RMSE of the brute-force integral of its lobe over a 128²-per-face grid of
// the same environment (Blender's courtyard at 16² per face: sky, sun-lit walls, shade).
TEST(Prefilter, ImportanceSampledLevelsMatchBruteForce) {
    const CubeMap& source = courtyard16();
    for (Distribution d : {Distribution::ggx, Distribution::beckmann}) {
        const PrefilteredChain chain =
            prefilter(source, settings(PrefilterMethod::importance, d, 1024, true));
        ASSERT_EQ(chain.levels.size(), 4u);  // 16, 8, 4, 2
        for (size_t l = 1; l < chain.levels.size(); ++l) {
            const CubeMap truth =
                brute_force_level(source, chain.levels[l].size, d, chain.roughness[l], 128);
            const double error = relative_rmse(chain.levels[l], truth);
            EXPECT_LT(error, 0.02)
                << to_string(d) << " level " << l << " alpha " << chain.roughness[l];
            RecordProperty(fmt::format("{}_level{}_rel_rmse", to_string(d), l),
                           std::to_string(error));
        }
    }
}

// Moschos' cone levels follow figure 3.24: face size halves, roughness from the table; its lookup
// interpolates the table (algorithm 7) and the importance path's is √α (L − 1).
TEST(Prefilter, RoughnessToLevelMappings) {
    const CubeMap source = make_cube_map(64, [](glm::vec3 d) { return glm::vec3(d.y + 1.0f); });
    const PrefilteredChain cone =
        prefilter(source, settings(PrefilterMethod::cone, Distribution::beckmann, 8, false));
    ASSERT_EQ(cone.levels.size(), 7u);  // 64 .. 1
    EXPECT_FLOAT_EQ(cone.roughness[3], 0.1f);
    EXPECT_FLOAT_EQ(roughness_to_lod(cone, 0.1f), 3.0f);
    EXPECT_FLOAT_EQ(roughness_to_lod(cone, 0.15f), 3.5f);
    EXPECT_FLOAT_EQ(roughness_to_lod(cone, 0.9f), 6.0f);  // past the chain: its last level
    PrefilterSettings s = settings(PrefilterMethod::importance, Distribution::ggx, 8, true);
    s.min_face_size = 8;
    const PrefilteredChain importance = prefilter(source, s);
    ASSERT_EQ(importance.levels.size(), 4u);  // 64, 32, 16, 8
    for (size_t l = 0; l < importance.levels.size(); ++l)
        EXPECT_NEAR(roughness_to_lod(importance, importance.roughness[l]), float(l), 1e-5f);
}

// The seed's cone prefilter blurs more with each level: the peak of a bright 8° cap falls once
// the cone outgrows the cap and never rises again, and the threads do not change the result.
TEST(Prefilter, ConeLevelsBlurProgressivelyAndDeterministically) {
    const float cap = std::cos(8.0f * float(kPi) / 180.0f);
    const CubeMap source =
        make_cube_map(64, [&](glm::vec3 d) { return glm::vec3(d.z > cap ? 1000.0f : 1.0f); });
    PrefilterSettings s = settings(PrefilterMethod::cone, Distribution::beckmann, 512, false);
    const PrefilteredChain chain = prefilter(source, s);
    s.threads = 1;
    const PrefilteredChain single = prefilter(source, s);
    std::vector<float> peaks;  // on faces of 4 texels or more (coarser ones miss the axis)
    for (size_t l = 1; l < chain.levels.size() && chain.levels[l].size >= 4; ++l) {
        peaks.push_back(chain.levels[l].sample({0, 0, 1}).x);
        if (l > 1) {
            EXPECT_LE(peaks.back(), peaks[peaks.size() - 2] * 1.05f) << "level " << l;
        }
        for (int f = 0; f < 6; ++f)
            EXPECT_EQ(chain.levels[l].faces[size_t(f)].rgb, single.levels[l].faces[size_t(f)].rgb);
    }
    EXPECT_GT(peaks.front(), 900.0f);         // 1° cone inside the cap
    EXPECT_LT(peaks.back(), 0.3f * 1000.0f);  // 32° cone: mostly the dim surroundings
}

// The chain is cached on disk by source and settings: a second request reads it back (no bake
// time) equal to the first, and different settings bake again.
TEST(Prefilter, CacheReadsBackTheSameChain) {
    test::TempDir dir;
    ::setenv("SHAFTLAB_CACHE", dir.path().c_str(), 1);
    const CubeMap& source = courtyard16();
    const PrefilterSettings s = settings(PrefilterMethod::importance, Distribution::ggx, 32, true);
    const PrefilteredChain baked = cached_prefilter(source, "courtyard16", s);
    EXPECT_TRUE(std::filesystem::exists(prefilter_cache_file("courtyard16", s)));
    const PrefilteredChain read = cached_prefilter(source, "courtyard16", s);
    EXPECT_EQ(read.seconds, 0.0);
    ASSERT_EQ(read.levels.size(), baked.levels.size());
    for (size_t l = 0; l < read.levels.size(); ++l) {
        EXPECT_EQ(read.roughness[l], baked.roughness[l]);
        for (int f = 0; f < 6; ++f)
            EXPECT_EQ(read.levels[l].faces[size_t(f)].rgb, baked.levels[l].faces[size_t(f)].rgb);
    }
    PrefilterSettings other = s;
    other.samples = 33;
    EXPECT_NE(prefilter_cache_file("courtyard16", s), prefilter_cache_file("courtyard16", other));
    ::unsetenv("SHAFTLAB_CACHE");
}

// Bad environments get one clear error: not 2:1, a NaN, a negative radiance.
TEST(Environment, BadImagesAreRejected) {
    test::TempDir dir;
    auto expect_error = [&](const Image& image, const std::string& fragment) {
        const auto path = dir.path() / "env.exr";
        test::write_unchecked_exr(image, path);
        try {
            load_equirect(path);
            ADD_FAILURE() << "no error for " << fragment;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
        }
    };
    expect_error(Image(8, 8), "2:1");
    Image nan(8, 4);
    nan.set(3, 2, glm::vec3(0.5f, std::nanf(""), 0.5f));
    expect_error(nan, "pixel (3, 2)");
    Image negative(8, 4);
    negative.set(2, 2, glm::vec3(1.0f));
    negative.set(1, 1, glm::vec3(-1.0f));
    expect_error(negative, "non-negative");
    Image huge(8, 4);
    huge.set(6, 1, glm::vec3(2e18f));
    expect_error(huge, "pixel (6, 1) has radiance 2e+18");
}

}  // namespace
}  // namespace sl::ibl
