// The CPU reference: converged in the shadow-ray count, equal to a brute-force integral of
// e(z) times ray-cast visibility, finite everywhere (camera inside the beam, light in view),
// and cached on disk by the command line.

#include <array>
#include <cmath>
#include <cstdlib>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "reference/reference.h"
#include "scenes/scene_sections.h"
#include "tests/support.h"

namespace sl::test {
namespace {

using analytic::dvec3;

double relative_l2(const Image& a, const Image& b) {
    double diff = 0.0, norm = 0.0;
    for (size_t i = 0; i < a.rgb.size(); ++i) {
        diff += double(a.rgb[i] - b.rgb[i]) * double(a.rgb[i] - b.rgb[i]);
        norm += double(b.rgb[i]) * double(b.rgb[i]);
    }
    return std::sqrt(diff / norm);
}

// Doubling the shadow-ray count changes I_s by less than 1e-4 relative.
TEST(Reference, ConvergedInTheShadowRayCount) {
    const Scene scene = load_canonical("toplight");
    const reference::ReferenceRenderer renderer(scene);
    const Image a = renderer.render(64, 36, {.shadow_samples = 256});
    const Image b = renderer.render(64, 36, {.shadow_samples = 512});
    EXPECT_LT(relative_l2(a, b), 1e-4);
    double total = 0.0;
    for (const float v : b.rgb)
        total += v;
    EXPECT_GT(total, 0.0);
}

// Per pixel, the reference equals a brute-force midpoint sum of e(z) times the ray-cast
// visibility of each point (no transitions, no bisection, no closed forms) to 1e-3.
TEST(Reference, MatchesBruteForceIntegralOfVisibleScattering) {
    const Scene scene = load_canonical("toplight");
    const reference::ReferenceRenderer renderer(scene);
    const Camera& camera = scene.camera;
    const int width = 48, height = 27;
    const PixelUnprojector pixels(camera, width, height);
    int compared = 0;
    for (int y = 1; y < height; y += 3) {
        for (int x = 1; x < width; x += 3) {
            const dvec3 origin(camera.position);
            const analytic::EyeRay ray{origin, glm::normalize(pixels.point(x, y, 1.0) - origin)};
            const double t_max = renderer.first_hit(ray, 40.0);
            const dvec3 exact = renderer.in_scattering(ray, t_max, {});
            // Over the ray's part inside the cone and range (light_interval has its own
            // brute-force test): a short span at the end of a long ray still gets every sample.
            const analytic::Interval span = analytic::light_interval(ray, scene.light, t_max);
            constexpr int kSteps = 20000;
            dvec3 sum(0.0);
            const double step = span.empty() ? 0.0 : (span.end - span.begin) / kSteps;
            for (int k = 0; k < kSteps && step > 0.0; ++k) {
                const double z = span.begin + (k + 0.5) * step;
                const dvec3 e = analytic::scattering_density(ray, z, scene.light, scene.medium);
                if (e.x > 0.0 && !renderer.occluded(ray.origin + z * ray.direction,
                                                    dvec3(scene.light.position))) {
                    sum += e;
                }
            }
            sum *= step;
            EXPECT_NEAR(exact.x, sum.x, 1e-3 * sum.x + 1e-9) << "pixel " << x << ", " << y;
            compared += sum.x > 0.0;
        }
    }
    EXPECT_GT(compared, 40);
}

// A camera inside the lit volume with the light in view: every pixel finite and non-negative.
TEST(Reference, CameraInsideTheBeamLookingAtTheLightIsFinite) {
    Scene scene = load_canonical("toplight");
    scene.camera.position = glm::vec3(1.0f, 2.0f, -0.6f);  // under the light, inside the cone
    scene.camera.target = scene.light.position;
    scene.camera.up = glm::vec3(0.0f, 0.0f, 1.0f);
    const reference::ReferenceRenderer renderer(scene);
    const Image image = renderer.render(32, 32, {.shadow_samples = 64});
    for (const float v : image.rgb) {
        ASSERT_TRUE(std::isfinite(v));
        ASSERT_GE(v, 0.0f);
    }
}

// The cache key changes with anything the image depends on.
TEST(Reference, CacheKeyFollowsTheInputs) {
    const Scene scene = load_canonical("toplight");
    const uint64_t key = reference::reference_key(scene, 64, 36, {});
    EXPECT_EQ(key, reference::reference_key(scene, 64, 36, {}));
    EXPECT_NE(key, reference::reference_key(scene, 64, 37, {}));
    Scene moved = scene;
    moved.light.position.x += 0.01f;
    EXPECT_NE(key, reference::reference_key(moved, 64, 36, {}));
    Scene denser = scene;
    denser.medium.sigma_s *= 2.0f;
    EXPECT_NE(key, reference::reference_key(denser, 64, 36, {}));
    // A pyramid, a point light and a second light are other images.
    Scene pyramid = scene;
    pyramid.light.shape = SpotShape::pyramid;
    EXPECT_NE(key, reference::reference_key(pyramid, 64, 36, {}));
    PointLight point;
    point.position = scene.light.position;
    Scene lights = scene;
    lights.set_lights({scene.light, point});
    EXPECT_NE(key, reference::reference_key(lights, 64, 36, {}));
    Scene bright = lights;
    point.intensity *= 2.0f;
    bright.set_lights({scene.light, point});
    EXPECT_NE(reference::reference_key(lights, 64, 36, {}),
              reference::reference_key(bright, 64, 36, {}));
}

// toplight lit by a point light among its objects (the eye outside its cubes) instead.
Scene point_lit_toplight() {
    Scene scene = load_canonical("toplight");
    PointLight point;
    point.position = glm::vec3(0.3f, 2.6f, 0.2f);
    point.near = 0.4f;
    point.far = 6.0f;
    point.intensity = glm::vec3(30.0f);
    scene.set_lights({point});
    return scene;
}

// A point light (integrated whole, between its cubes) equals the six pyramidal spot lights that
// tile its cube (Moschos: "either conical or pyramidal"), shadows included, to the reference's
// own convergence: the faces' visibility sweeps sample other points along each ray.
TEST(Reference, APointLightEqualsItsSixPyramidalFaces) {
    const Scene point = point_lit_toplight();
    Scene faces = point;
    const std::array<SpotLight, 6> six = std::get<PointLight>(point.lights[0]).faces();
    faces.set_lights({six[0], six[1], six[2], six[3], six[4], six[5]});
    ASSERT_EQ(faces.spot_lights().size(), 6u);
    const Image whole = reference::ReferenceRenderer(point).render(64, 36, {});
    const Image sum = reference::ReferenceRenderer(faces).render(64, 36, {});
    EXPECT_LT(relative_l2(sum, whole), 1e-4);
    double total = 0.0;
    for (const float v : whole.rgb)
        total += v;
    EXPECT_GT(total, 0.0);
}

// toplight under a sun from above, slightly tilted, over the scene's default box.
Scene sunlit_toplight() {
    Scene scene = load_canonical("toplight");
    DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    sun.irradiance = glm::vec3(2.0f);
    sun.entry = glm::vec3(std::numeric_limits<float>::quiet_NaN());
    resolve_directional_light(sun, scene, "test");
    scene.set_lights({sun});
    return scene;
}

// A pyramid spot light D behind a parallel beam's entry plane whose square meets the beam's box
// there, with the box's range and the intensity that gives its irradiance at the entry plane.
SpotLight far_spot(const SpotLight& beam, const Medium& medium, double D) {
    const glm::dvec3 a = glm::normalize(glm::dvec3(beam.direction()));
    SpotLight spot = beam;
    spot.half_width = 0.0f;
    spot.position = glm::vec3(glm::dvec3(beam.position) - D * a);
    spot.target = glm::vec3(glm::dvec3(beam.position) + D * a);
    spot.cone_half_angle_degrees = float(glm::degrees(std::atan(double(beam.half_width) / D)));
    spot.near = float(D);
    spot.far = float(D + double(beam.far));
    const double scale = medium.model == MediumModel::physical
                             ? D * D * std::exp(double(medium.sigma_t().r) * D)
                             : double(medium.a1) * D * D + double(medium.a0);
    spot.intensity = glm::vec3(glm::dvec3(beam.intensity) * scale);
    return spot;
}

// A sun is the limit of a spot light moved far away against its beams, its intensity scaled to
// match (issue 47), shadows included: the reference's difference falls as 1/D (halves with
// each doubling), the shadows' slant and the falloff both being O(1/D).
TEST(Reference, ASunIsTheLimitOfAFarSpotLight) {
    const Scene sunlit = sunlit_toplight();
    const Image sun = reference::ReferenceRenderer(sunlit).render(48, 27, {});
    double total = 0.0;
    for (const float v : sun.rgb)
        total += v;
    ASSERT_GT(total, 0.0);
    std::vector<double> differences;
    for (const double D : {100.0, 200.0, 400.0}) {
        Scene spot = sunlit;
        spot.set_lights({far_spot(sunlit.light, sunlit.medium, D)});
        differences.push_back(
            relative_l2(reference::ReferenceRenderer(spot).render(48, 27, {}), sun));
    }
    EXPECT_LT(differences[0], 0.1);
    EXPECT_NEAR(differences[0] / differences[1], 2.0, 0.3)
        << differences[0] << " " << differences[1];
    EXPECT_NEAR(differences[1] / differences[2], 2.0, 0.3)
        << differences[1] << " " << differences[2];
}

// The reference is linear in the lights: two lights render the sum of each alone.
TEST(Reference, SeveralLightsAddUp) {
    const Scene point = point_lit_toplight();
    const Scene spot = load_canonical("toplight");
    Scene both = spot;
    both.set_lights({spot.light, point.lights[0]});
    const Image a = reference::ReferenceRenderer(spot).render(48, 27, {});
    const Image b = reference::ReferenceRenderer(point).render(48, 27, {});
    const Image together = reference::ReferenceRenderer(both).render(48, 27, {});
    Image sum = a;
    for (size_t i = 0; i < sum.rgb.size(); ++i)
        sum.rgb[i] += b.rgb[i];
    EXPECT_LT(relative_l2(together, sum), 1e-6);
}

}  // namespace
}  // namespace sl::test
