// Where a sun's shadow map lies for a frame (frame/shadow_fit.h): fitted to the part of the sun's
// box the camera's view pyramid reaches, it still holds every point the camera can see inside the
// box and every occluder between such a point and the light, over less of the box; a spot light's
// map is its pyramid, whatever the camera.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "frame/shadow_fit.h"
#include "tests/support.h"

namespace sl::test {
namespace {

constexpr float kAspect = 16.0f / 9.0f;

glm::dmat4 whole_box(const SpotLight& light) {
    return glm::dmat4(light.projection()) * glm::dmat4(light.view());
}

// The fitted map's share of the box's cross-section.
double area_share(const SpotLight& light, const Camera& camera) {
    const glm::dmat4 fit = glm::dmat4(frame::shadow_view_projection(light, camera, kAspect)) *
                           glm::inverse(whole_box(light));
    return 1.0 / (fit[0][0] * fit[1][1]);
}

// The boxes under a sun, and the camera somewhere in the sun's box looking down at one box
// through a narrow lens: it sees a small part of the box.
Scene narrow_view() {
    Scene scene = sun_placements().front().second;
    scene.camera.position = glm::vec3(1.5f, 2.5f, 2.0f);
    scene.camera.target = glm::vec3(1.0f, 0.0f, 0.5f);
    scene.camera.fov_y_degrees = 20.0f;
    scene.camera.far = 4.0f;
    return scene;
}

// Soundness, on random points of the view pyramid (from the eye to the far plane) inside the
// sun's box: each lies inside the fitted map's clip cube, and so does every point between it and
// the entry plane along the beams (its occluders, which must be in the map).
TEST(ShadowFit, ASunsMapHoldsWhatTheCameraSeesAndWhatShadowsIt) {
    std::vector<std::pair<std::string, Scene>> scenes = sun_placements();
    scenes.emplace_back("narrow view", narrow_view());
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const auto& [name, scene] : scenes) {
        const SpotLight& light = scene.light;
        ASSERT_TRUE(light.parallel()) << name;
        const glm::dmat4 whole = whole_box(light);
        const glm::dmat4 fitted(frame::shadow_view_projection(light, scene.camera, kAspect));
        const glm::dmat4 to_world =
            glm::inverse(glm::dmat4(scene.camera.projection(kAspect) * scene.camera.view()));
        const glm::dvec3 eye(scene.camera.position);
        int inside = 0;
        for (int i = 0; i < 20000; ++i) {
            const glm::dvec4 f =
                to_world * glm::dvec4(2.0 * unit(random) - 1.0, 2.0 * unit(random) - 1.0, 1.0, 1.0);
            const glm::dvec3 p = eye + unit(random) * (glm::dvec3(f) / f.w - eye);
            const glm::dvec3 box = glm::dvec3(whole * glm::dvec4(p, 1.0));
            if (std::max({std::abs(box.x), std::abs(box.y), std::abs(box.z)}) > 1.0) {
                continue;  // outside the sun's box: no light there to shadow
            }
            ++inside;
            for (const double towards_light : {0.0, 0.3, 0.7, 1.0}) {
                // From p back along the beams, towards_light of the way to the entry plane.
                glm::dvec3 q = box;
                q.z = box.z - towards_light * (box.z + 1.0);
                const glm::dvec3 map =
                    glm::dvec3(fitted * glm::inverse(whole) * glm::dvec4(q, 1.0));
                ASSERT_LE(std::max({std::abs(map.x), std::abs(map.y), std::abs(map.z)}), 1.0 + 1e-6)
                    << name << " point " << i << " at " << towards_light;
            }
        }
        EXPECT_GT(inside, 500) << name;
    }
}

// The fit pays: looking at one box through a narrow lens, the map covers a few percent of the
// box's cross-section (so its texels are that much finer); no view makes it cover more than the
// whole box.
TEST(ShadowFit, ASunsMapCoversOnlyWhatTheCameraCanSee) {
    const Scene scene = narrow_view();
    const double share = area_share(scene.light, scene.camera);
    std::printf("narrow view: the map covers %.4f of the sun's box\n", share);
    EXPECT_LT(share, 0.05);
    std::vector<std::pair<std::string, Scene>> scenes = sun_placements();
    scenes.emplace_back("house-morning", load_canonical("house-morning"));
    for (const auto& [name, placed] : scenes) {
        const double s = area_share(placed.light, placed.camera);
        std::printf("%-28s the map covers %.4f of the sun's box\n", name.c_str(), s);
        EXPECT_GT(s, 0.0) << name;
        EXPECT_LE(s, 1.0 + 1e-12) << name;
    }
}

// A camera that sees none of the box (it looks away from it, from outside) keeps the whole box;
// a spot light's map is its pyramid whatever the camera.
TEST(ShadowFit, WithoutAnyOfTheBoxInViewOrForASpotLightTheMapIsTheWholeInfluence) {
    Scene away = narrow_view();
    away.camera.position = glm::vec3(0.0f, 40.0f, 0.0f);
    away.camera.target = glm::vec3(0.0f, 80.0f, 0.0f);
    away.camera.up = glm::vec3(0.0f, 0.0f, 1.0f);
    EXPECT_EQ(frame::shadow_view_projection(away.light, away.camera, kAspect),
              glm::mat4(whole_box(away.light)));
    const Scene spot = boxes_scene(MediumModel::physical);
    EXPECT_EQ(frame::shadow_view_projection(spot.light, spot.camera, kAspect),
              glm::mat4(whole_box(spot.light)));
}

}  // namespace
}  // namespace sl::test
