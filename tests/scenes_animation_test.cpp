// Animation tracks in scene files (scenes/animation.h): interpolation, the canonical animated
// scenes, scene changes, and one clear error for every kind of bad animation input.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <variant>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "scenes/animation.h"
#include "scenes/scene_file.h"
#include "tests/support.h"

namespace sl {
namespace {

using test::TempDir;
using test::write_text;

// A two-object scene with an animation block appended.
std::string animated_scene(const std::string& animation) {
    return R"([camera]
position = [0.0, 2.0, 8.0]
target = [0.0, 1.0, 0.0]
[light]
position = [0.0, 6.0, 0.0]
target = [0.0, 0.0, 0.0]
cone_angle = 30.0
[[objects]]
name = "floor"
shape = "plane"
size = [8.0, 0.0, 8.0]
[[objects]]
name = "box"
shape = "box"
size = [1.0, 1.0, 1.0]
translate = [1.0, 0.5, 0.0]
rotate = [0.0, 30.0, 0.0]
)" + animation;
}

Scene parse(const std::string& text) {
    return parse_scene(text, "anim.toml", {}, SceneSearchPaths::defaults());
}

TEST(Animation, LinearTracksInterpolateHoldAndLeaveTheRestAlone) {
    const Scene scene = parse(animated_scene(R"(
[animation]
start = 0.0
end = 3.0
[[animation.light]]
time = 1.0
position = [0.0, 6.0, 0.0]
[[animation.light]]
time = 2.0
position = [2.0, 6.0, 0.0]
cone_angle = 20.0
[[animation.objects]]
name = "box"
time = 0.0
translate = [1.0, 0.5, 0.0]
[[animation.objects]]
name = "box"
time = 3.0
translate = [-2.0, 0.5, 0.0]
)"));
    ASSERT_TRUE(scene.animation);
    EXPECT_EQ(scene.animation->frame_count(), 91);  // 3 s at 30 fps, both ends
    // Held before the first key and after the last; linear between.
    EXPECT_EQ(scene_at(scene, 0.5).light.position, glm::vec3(0, 6, 0));
    EXPECT_NEAR(scene_at(scene, 1.25).light.position.x, 0.5f, 1e-6f);
    EXPECT_EQ(scene_at(scene, 3.0).light.position, glm::vec3(2, 6, 0));
    // A quantity keyed once is constant; one never keyed keeps the scene's value.
    EXPECT_EQ(scene_at(scene, 0.0).light.cone_half_angle_degrees, 20.0f);
    EXPECT_EQ(scene_at(scene, 1.5).light.target, scene.light.target);
    // Objects: the keyed part of the placement moves, the rest (rotate) stays, and the
    // transform is rebuilt from it.
    const Scene mid = scene_at(scene, 1.5);
    EXPECT_NEAR(mid.objects[1].placement.translate.x, -0.5f, 1e-6f);
    EXPECT_EQ(mid.objects[1].placement.rotate_degrees, glm::vec3(0, 30, 0));
    EXPECT_EQ(mid.objects[1].transform, mid.objects[1].placement.matrix());
    EXPECT_EQ(mid.objects[0].transform, scene.objects[0].transform);
}

TEST(Animation, CatmullRomPassesThroughEveryKeyAndIsSmooth) {
    Track<glm::vec3> track;
    for (int k = 0; k < 5; ++k) {
        track.times.push_back(0.5 * k * k);  // non-uniform spacing
        track.values.push_back(glm::vec3(std::sin(k), std::cos(k), float(k)));
    }
    for (size_t k = 0; k < track.times.size(); ++k) {
        EXPECT_EQ(track.at(track.times[k], Interpolation::catmull_rom), track.values[k]);
    }
    // C1 at the inner keys: one-sided difference quotients agree.
    for (size_t k = 1; k + 1 < track.times.size(); ++k) {
        const double t = track.times[k], h = 1e-4;
        const glm::vec3 left = (track.at(t, Interpolation::catmull_rom) -
                                track.at(t - h, Interpolation::catmull_rom)) /
                               float(h);
        const glm::vec3 right = (track.at(t + h, Interpolation::catmull_rom) -
                                 track.at(t, Interpolation::catmull_rom)) /
                                float(h);
        EXPECT_LT(glm::length(left - right), 2e-2f * (1.0f + glm::length(left))) << "key " << k;
    }
    // A linear track is piecewise linear: its midpoint is the average of the keys.
    const glm::vec3 mid = track.at(0.25, Interpolation::linear);
    EXPECT_LT(glm::length(mid - 0.5f * (track.values[0] + track.values[1])), 1e-6f);
}

TEST(Animation, CanonicalAnimatedScenesLoadAndMove) {
    for (const std::string& name : animated_scene_names()) {
        const Scene scene = load_scene(name, SceneSearchPaths::defaults());
        ASSERT_TRUE(scene.animation) << name;
        const Animation& a = *scene.animation;
        EXPECT_EQ(a.frame_count(), 121) << name;  // 4 s at 30 fps
        const Scene first = scene_at(scene, a.frame_time(0));
        const Scene later = scene_at(scene, a.frame_time(45));
        const SceneChange change = scene_change(first, later);
        EXPECT_TRUE(change.any()) << name;
        if (name == "toplight-orbit") {
            EXPECT_TRUE(change.light_geometry && change.objects.empty() && !change.camera);
            // The light circles at its height, 1.6 m from the axis.
            const glm::vec3 p = later.light.position;
            EXPECT_NEAR(std::hypot(p.x, p.z), 1.6, 0.02) << "orbit radius";
        } else if (name == "parallel-walk") {
            EXPECT_TRUE(change.camera && change.light_geometry && change.objects.empty());
        } else {
            EXPECT_EQ(change.objects.size(), 32u) << "every object but the floor moves";
            EXPECT_FALSE(change.light);
        }
    }
}

// The animated light scenes: parallel-lamps-swing's second lamp stays on its 1.2 m cord and
// points along it while the other lamps hang still; house-day's sun turns from the morning
// through the south at noon, its entry plane following.
TEST(Animation, TheLightScenesSwingALampAndTurnTheSun) {
    const Scene swing = load_scene("parallel-lamps-swing", SceneSearchPaths::defaults());
    ASSERT_TRUE(swing.animation);
    const glm::vec3 pivot(0.0f, 4.9f, 2.0f);
    for (const double t : {0.0, 0.5, 1.0, 1.7, 2.9, 3.5}) {
        const Scene s = scene_at(swing, t);
        ASSERT_EQ(s.lights.size(), swing.lights.size());
        for (size_t i = 0; i < s.lights.size(); ++i) {
            const auto& lamp = std::get<SpotLight>(s.lights[i]);
            if (i != 1) {
                EXPECT_EQ(lamp, std::get<SpotLight>(swing.lights[i])) << "lamp " << i + 1;
                continue;
            }
            // Catmull-Rom between keys on the arc: within a few mm of the cord's length.
            EXPECT_NEAR(glm::length(lamp.position - pivot), 1.2f, 0.01f) << "t = " << t;
            const glm::vec3 cord = glm::normalize(lamp.position - pivot);
            const glm::vec3 axis = glm::normalize(lamp.target - lamp.position);
            EXPECT_GT(glm::dot(glm::normalize(glm::vec3(cord.x, cord.y, 0.0f)),
                               glm::normalize(glm::vec3(axis.x, axis.y, 0.0f))),
                      0.999f)
                << "the beam along the cord at t = " << t;
        }
    }
    const Scene day = load_scene("house-day", SceneSearchPaths::defaults());
    ASSERT_TRUE(day.animation);
    EXPECT_EQ(day.animation->frame_count(), 181);  // 6 s at 30 fps
    const auto sun_at = [&](double t) {
        return std::get<DirectionalLight>(scene_at(day, t).lights[0]);
    };
    const DirectionalLight morning = sun_at(0.0), noon = sun_at(3.0), evening = sun_at(6.0);
    EXPECT_LT(morning.direction.x, -0.4f);
    EXPECT_NEAR(noon.direction.x, 0.0f, 1e-4f);
    EXPECT_GT(evening.direction.x, 0.4f);
    EXPECT_NE(morning.entry, evening.entry) << "the entry plane follows the sun";
    for (const DirectionalLight& sun : {morning, noon, evening}) {
        EXPECT_NEAR(glm::length(sun.direction), 1.0f, 1e-5f);
        EXPECT_LT(sun.direction.y, -0.3f) << "the sun is above the horizon";
    }
}

TEST(Animation, SceneChangeSaysWhatDiffers) {
    const Scene a = load_scene("toplight", SceneSearchPaths::defaults());
    Scene b = a;
    EXPECT_FALSE(scene_change(a, b).any());
    b.light.intensity *= 2.0f;
    EXPECT_TRUE(scene_change(a, b).light);
    EXPECT_FALSE(scene_change(a, b).regions()) << "a brighter light keeps its regions";
    b.light.position.x += 0.1f;
    EXPECT_TRUE(scene_change(a, b).regions());
    Scene c = a;
    c.objects[2].transform[3].x += 0.5f;
    EXPECT_EQ(scene_change(a, c).objects, std::vector<int>{2});
    EXPECT_TRUE(scene_change(a, c).regions());
    Scene d = a;
    d.camera.position.z += 1.0f;
    EXPECT_TRUE(scene_change(a, d).camera);
    EXPECT_FALSE(scene_change(a, d).regions());
}

// Each bad input: one error naming the file, the line and the key.
TEST(Animation, BadInputGivesOneClearErrorNamingFileLineAndKey) {
    struct Case {
        std::string animation;
        std::string expected;
    };
    const Case cases[] = {
        {"[animation]\n[[animation.light]]\ntime = 1.0\nposition = [0.0, 6.0, 0.0]\n"
         "[[animation.light]]\ntime = 0.5\nposition = [1.0, 6.0, 0.0]\n",
         "anim.toml:23: [[animation.light]] #2 time: 0.5 is not after the previous key's 1"},
        {"[animation]\n[[animation.objects]]\nname = \"teapot\"\ntime = 0.0\n"
         "translate = [0.0, 0.0, 0.0]\n",
         "anim.toml:20: [[animation.objects]] #1 name: the scene has no object 'teapot'"},
        {"[animation]\n[[animation.camera]]\ntime = 0.0\nposition = [nan, 1.0, 2.0]\n",
         "anim.toml:21: [[animation.camera]] #1 position: component 0 is not finite"},
        {"[animation]\nstart = 1.0\n[[animation.light]]\ntime = 0.5\ncone_angle = 20.0\n",
         "anim.toml:21: [[animation.light]] #1 time: 0.5 is before the animation's start 1"},
        {"[animation]\nend = 1.0\n[[animation.light]]\ntime = 2.0\ncone_angle = 20.0\n",
         "anim.toml:19: [animation] end: 1 is before the last key's time 2"},
        {"[animation]\n[[animation.light]]\ntime = 0.0\ncolour = [1.0, 1.0, 1.0]\n",
         "anim.toml:21: [[animation.light]] #1 colour: unknown key"},
        {"[animation]\n[[animation.light]]\nposition = [1.0, 6.0, 0.0]\n",
         "[[animation.light]] #1 time: missing: every key needs its time"},
        {"[animation]\nend = 2.0\n", "[animation] needs at least one key"},
        {"[animation]\ninterpolation = \"cubic\"\n[[animation.light]]\ntime = 0.0\n",
         "[animation] interpolation: unknown value 'cubic'"},
        {"[animation]\n[[animation.light]]\ntime = 0.0\ncone_angle = 95.0\n",
         "[[animation.light]] #1 cone_angle: must be in (0, 89]"},
        // Found by the fuzzer: a range too long for an int frame count.
        {"[animation]\n[[animation.light]]\ntime = 0.0\n[[animation.light]]\ntime = 2e113\n",
         "[animation] fps: 30 fps from 0 s to 2e+113 s is more than 1000000 frames"},
    };
    for (const Case& c : cases) {
        try {
            parse(animated_scene(c.animation));
            ADD_FAILURE() << "accepted:\n" << c.animation;
        } catch (const Error& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find(c.expected), std::string::npos)
                << "expected: " << c.expected << "\ngot: " << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        }
    }
}

// The same scene lit by [[lights]]: a spot, a point light and a sun.
std::string lights_scene(const std::string& animation) {
    return R"([camera]
position = [0.0, 2.0, 8.0]
target = [0.0, 1.0, 0.0]
[[lights]]
type = "spot"
position = [0.0, 6.0, 0.0]
target = [0.0, 0.0, 0.0]
cone_angle = 30.0
[[lights]]
type = "point"
position = [2.0, 3.0, 0.0]
intensity = [5.0, 5.0, 5.0]
[[lights]]
type = "directional"
direction = [0.0, -1.0, 0.0]
[[objects]]
name = "floor"
shape = "plane"
size = [8.0, 0.0, 8.0]
[[objects]]
name = "box"
shape = "box"
size = [1.0, 1.0, 1.0]
translate = [1.0, 0.5, 0.0]
)" + animation;
}

// [[animation.light]] keys in a scene of [[lights]] move the entry `light = N` names, each light
// type by its own keys, each entry's times on their own: a swinging spot's target, a point
// light's position, a sun's direction (its default entry plane following it); the methods' spot
// lights follow, and the change is the light's geometry.
TEST(Animation, LightsKeysMoveTheEntryTheyName) {
    const Scene scene = parse(lights_scene(R"([animation]
[[animation.light]]
light = 1
time = 0.0
target = [-1.0, 0.0, 0.0]
[[animation.light]]
light = 3
time = 0.0
direction = [0.0, -1.0, 0.0]
[[animation.light]]
light = 1
time = 2.0
target = [1.0, 0.0, 0.0]
[[animation.light]]
light = 2
time = 1.0
position = [2.0, 3.0, 0.0]
intensity = [5.0, 5.0, 5.0]
[[animation.light]]
light = 2
time = 2.0
position = [-2.0, 3.0, 0.0]
intensity = [1.0, 1.0, 1.0]
[[animation.light]]
light = 3
time = 2.0
direction = [-1.0, -1.0, 0.0]
irradiance = [2.0, 2.0, 2.0]
)"));
    ASSERT_TRUE(scene.animation);
    EXPECT_TRUE(scene.animation->moves_light());
    const Scene start = scene_at(scene, 0.0), middle = scene_at(scene, 1.0),
                end = scene_at(scene, 2.0);
    EXPECT_EQ(std::get<SpotLight>(middle.lights[0]).target, glm::vec3(0.0f));
    EXPECT_EQ(std::get<SpotLight>(end.lights[0]).target, glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(std::get<PointLight>(middle.lights[1]).position, glm::vec3(2.0f, 3.0f, 0.0f));
    EXPECT_EQ(std::get<PointLight>(end.lights[1]).position, glm::vec3(-2.0f, 3.0f, 0.0f));
    EXPECT_EQ(std::get<PointLight>(end.lights[1]).intensity, glm::vec3(1.0f));
    const auto& sun = std::get<DirectionalLight>(end.lights[2]);
    EXPECT_LT(glm::length(sun.direction - glm::normalize(glm::vec3(-1.0f, -1.0f, 0.0f))), 1e-6f);
    EXPECT_EQ(sun.irradiance, glm::vec3(2.0f));
    // The entry plane follows: the region's corner nearest the turned sun (at the start, the
    // scene's sun straight down, it was on the region's top at its -x side).
    EXPECT_EQ(std::get<DirectionalLight>(start.lights[2]).entry.x, sun.region.min.x);
    EXPECT_EQ(sun.entry, glm::vec3(sun.region.max.x, sun.region.max.y, sun.entry.z));
    EXPECT_EQ(end.light, end.spot_lights()[0]);
    EXPECT_EQ(end.spot_lights().size(), 8u);
    const SceneChange change = scene_change(start, end);
    EXPECT_TRUE(change.light_geometry);
    EXPECT_FALSE(change.camera);
    EXPECT_TRUE(change.objects.empty());
}

// Each light type takes its own keys, and a scene of [[lights]] needs `light = N` in range.
TEST(Animation, LightsKeysAreCheckedAgainstTheLightTheyName) {
    const std::pair<std::string, std::string> cases[] = {
        {"[animation]\n[[animation.light]]\ntime = 0.0\ntarget = [1.0, 0.0, 0.0]\n",
         "[[animation.light]] #1 light: missing: which [[lights]] entry the key moves, 1 to 3"},
        {"[animation]\n[[animation.light]]\nlight = 4\ntime = 0.0\n",
         "[[animation.light]] #1 light: expected an integer in [1, 3]"},
        {"[animation]\n[[animation.light]]\nlight = 2\ntime = 0.0\ntarget = [1.0, 0.0, 0.0]\n",
         "[[animation.light]] #1 target: light 2 is a point light, which takes position and "
         "intensity"},
        {"[animation]\n[[animation.light]]\nlight = 3\ntime = 0.0\nposition = [1.0, 0.0, 0.0]\n",
         "[[animation.light]] #1 position: light 3 is a directional light, which takes "
         "direction and irradiance"},
        {"[animation]\n[[animation.light]]\nlight = 1\ntime = 0.0\ndirection = [1.0, 0.0, 0.0]\n",
         "[[animation.light]] #1 direction: light 1 is a spot light"},
        {"[animation]\n[[animation.light]]\nlight = 3\ntime = 0.0\ndirection = [0.0, 0.0, 0.0]\n",
         "[[animation.light]] #1 direction: must not be [0, 0, 0]"},
    };
    for (const auto& [animation, expected] : cases) {
        try {
            parse(lights_scene(animation));
            ADD_FAILURE() << "accepted:\n" << animation;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos)
                << "expected: " << expected << "\ngot: " << e.what();
        }
    }
    // A scene of one [light] takes no `light` key.
    try {
        parse(animated_scene("[animation]\n[[animation.light]]\nlight = 1\ntime = 0.0\n"));
        ADD_FAILURE() << "accepted a light key with [light]";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("its keys need no `light`"), std::string::npos)
            << e.what();
    }
    // A sun turned through zero is refused at that time.
    const Scene through = parse(lights_scene(
        "[animation]\n[[animation.light]]\nlight = 3\ntime = 0.0\ndirection = [1.0, -1.0, "
        "0.0]\n[[animation.light]]\nlight = 3\ntime = 2.0\ndirection = [-1.0, 1.0, 0.0]\n"));
    EXPECT_THROW(scene_at(through, 1.0), Error);
    EXPECT_NO_THROW(scene_at(through, 0.5));
}

TEST(Animation, TimesOutsideTheRangeAndOvershootsAreRefused) {
    const Scene scene = parse(animated_scene(R"(
[animation]
end = 3.0
interpolation = "catmull-rom"
[[animation.light]]
time = 0.0
cone_angle = 80.0
[[animation.light]]
time = 1.0
cone_angle = 80.0
[[animation.light]]
time = 2.0
cone_angle = 2.0
[[animation.light]]
time = 3.0
cone_angle = 2.0
)"));
    EXPECT_THROW(scene_at(scene, -0.1), Error);
    EXPECT_THROW(scene_at(scene, 3.5), Error);
    EXPECT_THROW(scene_at(scene, std::nan("")), Error);
    try {
        // Catmull-Rom overshoots below 0 degrees after the steep fall to 2.
        for (int k = 0; k <= 90; ++k) {
            scene_at(scene, k / 30.0);
        }
        ADD_FAILURE() << "an overshoot outside (0, 89) degrees was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("the cone angle left (0, 89) degrees"),
                  std::string::npos)
            << e.what();
    }
}

TEST(Animation, PathFilesHoldTheSameFormat) {
    TempDir dir;
    const Scene scene = load_scene("toplight", SceneSearchPaths::defaults());
    write_text(dir / "path.toml",
               "[animation]\nfps = 10\n[[animation.camera]]\ntime = 0.0\nposition = [0.0, 2.4, "
               "9.0]\n[[animation.camera]]\ntime = 1.0\nposition = [2.0, 2.4, 9.0]\n");
    const Animation path = load_animation_file(dir / "path.toml", scene);
    EXPECT_EQ(path.frame_count(), 11);
    EXPECT_NEAR(scene_at(scene, path, 0.5).camera.position.x, 1.0f, 1e-6f);
    write_text(dir / "none.toml", "[camera]\nposition = [0.0, 1.0, 2.0]\n");
    EXPECT_THROW(load_animation_file(dir / "none.toml", scene), Error);
    EXPECT_THROW(load_animation_file(dir / "absent.toml", scene), Error);
}

}  // namespace
}  // namespace sl
