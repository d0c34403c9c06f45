// The GPU frame against independent CPU oracles: surface radiance and shadows against a
// brute-force ray caster and the closed-form shading of every floor pixel, determinism, and the
// GPU tone map against the CPU one.

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "core/error.h"
#include "core/image.h"
#include "core/metrics.h"
#include "frame/renderer.h"
#include "methods/registry.h"
#include "reference/reference.h"
#include "scenes/mesh.h"
#include "tests/gl_support.h"

namespace sl::test {
namespace {

using Render = GlTest;

frame::Frame render(const Scene& scene, const frame::RenderOptions& options) {
    frame::SceneRenderer renderer(scene, options);
    const auto method = methods::create_volume_method("none");
    method->prepare(scene);
    return renderer.render(*method);
}

// The same scene renders bit-identically twice, with two separate renderers.
TEST_F(Render, SameSceneRendersBitIdenticallyTwice) {
    const Scene scene = load_canonical("toplight");
    const frame::RenderOptions options{.width = 96, .height = 54};
    const frame::Frame a = render(scene, options);
    const frame::Frame b = render(scene, options);
    EXPECT_EQ(a.radiance.rgb, b.radiance.rgb);
    EXPECT_EQ(a.display_srgb8, b.display_srgb8);
}

// A method that refuses its parameters in the middle of a frame (lightvolume with one vertex per
// side) leaves the context as a finished frame would: the next renderer's frame is bit-identical
// to one made before. (It once left depth writes off, so the next shadow map was never cleared and
// its light volume collapsed to nothing.)
TEST_F(Render, AFrameAbortedByItsMethodLeavesTheNextFrameIntact) {
    const Scene scene = load_canonical("toplight");
    const frame::Frame before = render_method(scene, "lightvolume", 96, 54);
    EXPECT_THROW(render_method(scene, "lightvolume", 96, 54, {{"resolution", "1"}}), sl::Error);
    const frame::Frame after = render_method(scene, "lightvolume", 96, 54);
    EXPECT_EQ(before.in_scattering.rgb, after.in_scattering.rgb);
    EXPECT_EQ(before.radiance.rgb, after.radiance.rgb);
}

// With the `none` method, I_s is zero and the composite is exactly the surface pass; the GPU tone
// map agrees with the CPU one (core/image.cpp) to one 8-bit step.
TEST_F(Render, CompositeIsSurfacePlusInScatteringAndToneMapsLikeTheCpu) {
    const Scene scene = load_canonical("multiple");
    const frame::Frame frame = render(scene, {.width = 80, .height = 45});
    EXPECT_EQ(frame.radiance.rgb, frame.surface.rgb);
    for (const float v : frame.in_scattering.rgb) {
        ASSERT_EQ(v, 0.0f);
    }
    const std::vector<unsigned char> cpu =
        tone_map_srgb8(frame.radiance, ToneMap{scene.camera.exposure});
    ASSERT_EQ(cpu.size(), frame.display_srgb8.size());
    int worst = 0;
    for (size_t i = 0; i < cpu.size(); ++i) {
        worst = std::max(worst, std::abs(int(cpu[i]) - int(frame.display_srgb8[i])));
    }
    EXPECT_LE(worst, 1);  // float rounding of pow() on llvmpipe vs libm
}

struct FloorSample {
    int x, y;
    glm::vec3 expected;
    glm::vec3 rendered;
};
struct FloorCheck {
    std::vector<FloorSample> lit, shadowed, outside;
    int mismatches = 0;
    int checked = 0;
};

// Casts the ray through every `step`-th pixel centre onto the floor (y = 0) and computes, on the
// CPU, the radiance the surface pass must produce there: Lambert with the cone of Nilsson eq.
// 2.9, the falloff of eq. 2.8 / 2.13, visibility by ray casting, ambient, and T(Z), summed over
// the scene's spot lights (a point light's six faces). Pixels that see an object rather than the
// floor, lie within `edge` metres of a shadow boundary or within 0.75° of a cone's edge are
// skipped: there the shadow map's resolution decides. A pyramid's sides are not skipped: where a
// point light's faces meet, the light goes on.
FloorCheck check_floor(const Scene& scene, const frame::RenderOptions& options, int step,
                       float edge) {
    const frame::Frame frame = render(scene, options);
    const CpuRayCaster caster(scene);
    const PixelUnprojector pixels(scene.camera, options.width, options.height);
    const Object& floor = scene.objects.front();
    EXPECT_EQ(floor.name, "floor");
    const glm::vec3 albedo = scene.materials[size_t(floor.material)].albedo;
    const Bounds floor_bounds = floor.mesh->bounds();
    const std::vector<SpotLight> lights = scene.spot_lights();
    const SpotLight& light = scene.light;  // every light is at its position

    auto sees_light = [&](glm::vec3 p) { return !caster.blocked(p, light.position); };
    FloorCheck check;
    for (int y = step / 2; y < options.height; y += step) {
        for (int x = step / 2; x < options.width; x += step) {
            const glm::vec3 o(pixels.point(x, y, -1.0));
            const glm::vec3 d = glm::vec3(pixels.point(x, y, 1.0)) - o;
            if (d.y >= 0.0f) {
                continue;
            }
            const glm::vec3 p = o + (-o.y / d.y) * d;
            if (std::abs(p.x) > floor_bounds.max.x - 0.1f ||
                std::abs(p.z) > floor_bounds.max.z - 0.1f ||
                caster.blocked(scene.camera.position, p)) {
                continue;
            }
            bool near_cone_edge = false;
            for (const SpotLight& spot : lights) {
                const float angle = glm::degrees(
                    std::acos(glm::dot(glm::normalize(p - spot.position), spot.direction())));
                near_cone_edge |= spot.shape == SpotShape::cone &&
                                  std::abs(angle - spot.cone_half_angle_degrees) < 0.75f;
            }
            if (near_cone_edge) {
                continue;
            }
            const bool visible = sees_light(p);
            bool near_boundary = false;
            for (const glm::vec3 offset : {glm::vec3(edge, 0, 0), glm::vec3(-edge, 0, 0),
                                           glm::vec3(0, 0, edge), glm::vec3(0, 0, -edge)}) {
                near_boundary |= sees_light(p + offset) != visible;
            }
            if (near_boundary) {
                continue;
            }
            const glm::vec3 to_light = light.position - p;
            const float r = glm::length(to_light);
            const float cos_theta = std::max(0.0f, to_light.y / r);
            float emitted = 0.0f;  // the cone factors within range, summed over the lights
            glm::vec3 irradiance(0.0f);
            for (const SpotLight& spot : lights) {
                const float axial = glm::dot(-to_light, spot.direction());
                const float in_range = axial >= spot.near && axial <= spot.far ? 1.0f : 0.0f;
                emitted += spot.cone_factor(p) * in_range;
                irradiance += spot.intensity * spot.cone_factor(p) * in_range *
                              scene.medium.light_falloff(r) * cos_theta * (visible ? 1.0f : 0.0f);
            }
            const glm::vec3 radiance =
                albedo / std::numbers::pi_v<float> * irradiance + albedo * scene.ambient;
            const glm::vec3 expected =
                radiance * scene.medium.transmittance(glm::length(p - scene.camera.position));
            const FloorSample sample{x, y, expected, frame.surface.at(x, y)};
            ++check.checked;
            const glm::vec3 error = glm::abs(sample.rendered - expected);
            if (glm::any(glm::greaterThan(error, 0.01f * expected + 2e-4f))) {
                ++check.mismatches;
                if (check.mismatches <= 5) {
                    ADD_FAILURE() << "pixel (" << x << ", " << y << ") floor point (" << p.x << ", "
                                  << p.z << "): rendered " << sample.rendered.r << ", expected "
                                  << expected.r;
                }
            }
            if (emitted == 0.0f) {
                check.outside.push_back(sample);
            } else {
                (visible ? check.lit : check.shadowed).push_back(sample);
            }
        }
    }
    return check;
}

glm::vec3 mean_rendered(const std::vector<FloorSample>& samples) {
    glm::vec3 sum(0.0f);
    for (const FloorSample& s : samples) {
        sum += s.rendered;
    }
    return sum / float(std::max<size_t>(1, samples.size()));
}

// A small toplight render: the floor is lit inside the cone, dark outside, and shadowed under the
// objects, and every floor pixel away from edges has the radiance the CPU computes for it.
TEST_F(Render, ToplightFloorMatchesCpuShadingAndVisibility) {
    const Scene scene = load_canonical("toplight");
    const FloorCheck check = check_floor(scene, {.width = 192, .height = 108}, 2, 0.06f);
    EXPECT_GE(check.lit.size(), 300u);
    EXPECT_GE(check.shadowed.size(), 20u);
    EXPECT_GE(check.outside.size(), 300u);
    EXPECT_EQ(check.mismatches, 0) << "of " << check.checked << " floor pixels";
    const float lit = mean_rendered(check.lit).g;
    EXPECT_GT(lit, 20.0f * mean_rendered(check.outside).g);
    EXPECT_GT(lit, 10.0f * mean_rendered(check.shadowed).g);
}

// The same under a point light over the toplight scene's floor, where its faces meet along lines
// across the floor (|x| or |z| from its foot equal to its height): the light goes on across them,
// where a surface's shadow lookup, moved off the floor by the normal offset, leaves its face's map
// and must read the map's edge (shadow.glsl), and the floor is lit by each face up to its side.
TEST_F(Render, FloorUnderAPointLightHasNoSeamsBetweenItsFaces) {
    Scene scene = load_canonical("toplight");
    PointLight point;
    point.position = glm::vec3(0.4f, 2.5f, 0.3f);
    point.near = 0.1f;
    point.far = 4.0f;  // the floor within 4 m of its foot: no grazing shadows
    point.intensity = glm::vec3(40.0f);
    scene.set_lights({point});
    const FloorCheck check = check_floor(scene, {.width = 192, .height = 108}, 1, 0.06f);
    EXPECT_GE(check.lit.size(), 2000u);
    EXPECT_GE(check.shadowed.size(), 100u);
    EXPECT_EQ(check.mismatches, 0) << "of " << check.checked << " floor pixels";
}

// The same with hard shadows and the physical medium model (transmittance on the light path
// and on the eye path, Nilsson eq. 2.6-2.8), on the parallel scene.
TEST_F(Render, ParallelFloorMatchesCpuWithHardShadowsAndPhysicalMedium) {
    Scene scene = load_canonical("parallel");
    scene.medium.model = MediumModel::physical;
    scene.medium.sigma_a = glm::vec3(0.02f, 0.03f, 0.05f);
    frame::RenderOptions options{.width = 160, .height = 90};
    options.shadow.filter = frame::ShadowFilter::hard;
    const FloorCheck check = check_floor(scene, options, 1, 0.08f);
    EXPECT_GE(check.lit.size(), 100u);
    EXPECT_GE(check.shadowed.size(), 20u);
    EXPECT_GE(check.outside.size(), 100u);
    EXPECT_EQ(check.mismatches, 0) << "of " << check.checked << " floor pixels";
}

// A box `distance` below a light whose range starts at 1 m, over a floor; at 0.5 m (a
// 0.4 x 0.2 x 0.4 box) it lies between the light and its near plane. The box is
// scaled with its distance, so that it casts the same shadow (the same solid angle from the light)
// wherever it is. The light's range bounds where it scatters, not what casts shadows.
Scene near_occluder_scene(float distance) {
    Scene scene;
    scene.name = "nearocc";
    scene.camera.position = glm::vec3(0.0f, 2.5f, 9.0f);
    scene.camera.target = glm::vec3(0.0f, 2.5f, 0.0f);
    scene.camera.fov_y_degrees = 50.0f;
    scene.light.position = glm::vec3(0.0f, 6.0f, 0.0f);
    scene.light.target = glm::vec3(0.0f);
    scene.light.cone_half_angle_degrees = 30.0f;
    scene.light.near = 1.0f;
    scene.light.far = 9.0f;
    scene.light.intensity = glm::vec3(100.0f);
    scene.medium.sigma_s = glm::vec3(0.1f);
    scene.materials.push_back(Material{.name = "default"});
    Object floor;
    floor.name = "floor";
    floor.mesh = std::make_shared<const Mesh>(make_plane({40.0f, 40.0f}));
    scene.objects.push_back(floor);
    Object blocker;
    blocker.name = "blocker";
    const float scale = distance / 0.5f;
    blocker.mesh = std::make_shared<const Mesh>(make_box(scale * glm::vec3(0.4f, 0.2f, 0.4f)));
    blocker.transform =
        glm::translate(glm::mat4(1.0f), glm::vec3(0.15f * scale, 6.0f - distance, 0.0f));
    scene.objects.push_back(blocker);
    return scene;
}

// The floor under the box is shadowed, pixel by pixel as the CPU ray caster sees it, with every
// shadow filter.
TEST_F(Render, AnOccluderInFrontOfTheNearPlaneShadowsTheFloor) {
    const Scene scene = near_occluder_scene(0.5f);
    for (const frame::ShadowFilter filter :
         {frame::ShadowFilter::hard, frame::ShadowFilter::pcf, frame::ShadowFilter::vsm}) {
        frame::RenderOptions options{.width = 160, .height = 90};
        options.shadow.filter = filter;
        const FloorCheck check = check_floor(scene, options, 1, 0.08f);
        EXPECT_GE(check.shadowed.size(), 20u) << int(filter);
        EXPECT_EQ(check.mismatches, 0) << "filter " << int(filter) << ", of " << check.checked;
    }
}

// Every method, with every shadow filter it takes, sees a box in front of the near plane as it
// sees the same shadow cast from inside the range (the box 1.5 m below the light): its I_s error
// against the reference (160x90, relative RMSE) is at most 1.2x the in-range one's + 0.01 (froxel's
// grid leaves 40% on both). Before the shadow map clamped such occluders to its near plane
// instead of clipping them, the error was 131% (the shaft below the box lit) for every
// shadow-map method.
TEST_F(Render, EveryMethodSeesAnOccluderInFrontOfTheNearPlane) {
    const Scene near = near_occluder_scene(0.5f), inside = near_occluder_scene(1.5f);
    const Image near_exact = reference::ReferenceRenderer(near).render(160, 90, {});
    const Image inside_exact = reference::ReferenceRenderer(inside).render(160, 90, {});
    for (const std::string& name : methods::volume_method_names()) {
        if (name == "none" || name == "reference")
            continue;
        const bool filtered = methods::create_volume_method(name)->has_parameter("shadow");
        for (const char* filter : {"hard", "pcf", "vsm"}) {
            if (!filtered && std::string(filter) != "pcf")
                continue;
            std::vector<std::pair<std::string, std::string>> settings;
            if (filtered)
                settings.emplace_back("shadow", filter);
            const double near_error =
                compare_images(render_method(near, name, 160, 90, settings).in_scattering,
                               near_exact)
                    .rel_rmse;
            const double inside_error =
                compare_images(render_method(inside, name, 160, 90, settings).in_scattering,
                               inside_exact)
                    .rel_rmse;
            EXPECT_LE(near_error, 1.2 * inside_error + 0.01)
                << name << " shadow " << filter << ": in range " << inside_error;
            std::printf("%s %s: near %.2e, in range %.2e\n", name.c_str(), filter, near_error,
                        inside_error);
        }
    }
}

// Glass (Material::casts_shadow = false) lets the light through in every method and in the
// reference: a glass slab between the light and the boxes, out of the camera's view, leaves every
// method's I_s as it is without the slab (to float rounding), while the same slab casting shadows
// changes the reference's by far more (the control that makes the test able to fail).
TEST_F(Render, GlassCastsNoShadowInAnyMethodOrTheReference) {
    const Scene plain = boxes_scene(MediumModel::simplified);
    Scene glass = plain, opaque = plain;
    for (Scene* scene : {&glass, &opaque}) {
        scene->materials.push_back(Material{.name = "glass", .casts_shadow = scene == &opaque});
        Object slab;
        slab.name = "slab";
        slab.mesh = std::make_shared<const Mesh>(make_box(glm::vec3(2.5f, 0.05f, 2.5f)));
        slab.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.4f, 5.0f, -0.25f));
        slab.material = 1;
        scene->objects.push_back(slab);
    }
    const int w = 96, h = 54;
    const Image exact = reference::ReferenceRenderer(plain).render(w, h, {});
    const double peak = image_peak(exact);
    EXPECT_LE(max_abs_difference(reference::ReferenceRenderer(glass).render(w, h, {}), exact),
              1e-6 * peak);
    EXPECT_GE(max_abs_difference(reference::ReferenceRenderer(opaque).render(w, h, {}), exact),
              0.2 * peak);
    for (const std::string& name : methods::volume_method_names()) {
        if (name == "none" || name == "reference")
            continue;
        const Image without = render_method(plain, name, w, h).in_scattering;
        const Image with = render_method(glass, name, w, h).in_scattering;
        EXPECT_LE(max_abs_difference(with, without), 1e-5 * image_peak(without)) << name;
        const Image shadowed = render_method(opaque, name, w, h).in_scattering;
        EXPECT_GE(max_abs_difference(shadowed, without), 0.1 * image_peak(without)) << name;
    }
}

}  // namespace
}  // namespace sl::test
