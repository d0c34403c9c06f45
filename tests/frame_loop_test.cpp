// The per-frame update of every method and the frame loop (frame/frame_loop.h): a method brought to
// frame k by its updates renders what the same method prepared on the still scene at t_k renders,
// and the pipelined loop (CPU work of frame k+1 on a worker during frame k's draw) renders
// exactly the serial loop's frames.

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/metrics.h"
#include "frame/frame_loop.h"
#include "frame/renderer.h"
#include "methods/registry.h"
#include "scenes/animation.h"
#include "scenes/scene_file.h"
#include "tests/gl_support.h"

namespace sl::frame {
namespace {

using test::GlTest;

class FrameLoopTest : public GlTest {};

constexpr RenderOptions kSmall{.width = 96, .height = 54, .shadow = {.map_size = 512}};

std::vector<Image> play(const Scene& animated, VolumeMethod& method, FrameMode mode,
                        const std::vector<int>& frames) {
    const Animation& a = *animated.animation;
    Scene live = scene_at(animated, a.frame_time(frames.front()));
    SceneRenderer renderer(live, kSmall);
    method.prepare(live);
    std::vector<Image> images;
    FrameLoop loop(renderer, method, live, mode);
    loop.play(
        int(frames.size()),
        [&](int i) { return scene_at(animated, a.frame_time(frames[size_t(i)])); },
        [&](const FrameRecord& record) {
            EXPECT_GE(record.draw_ms, 0.0);
            EXPECT_EQ(record.update_on_worker, mode == FrameMode::pipelined && record.frame > 0);
            images.push_back(renderer.read_in_scattering());
        });
    return images;
}

// Every method but the reference (its per-frame cost is its own), on each canonical animation:
// updated to frame k, against prepared on the still scene at t_k by a fresh renderer.
TEST_F(FrameLoopTest, FrameKOfAnAnimationEqualsTheStillSceneAtItsTime) {
    for (const std::string& scene_name : animated_scene_names()) {
        const Scene animated = load_scene(scene_name, SceneSearchPaths::defaults());
        const std::vector<int> frames = {0, 37, 90};
        // Every method with its defaults, march clipped to the influence pyramid (planes it
        // takes from the frame's light in its update), and the region methods on the walk route
        // (the suite's software GL makes `auto` mesh).
        struct Case {
            std::string method, parameter, value;
        };
        std::vector<Case> cases;
        for (const std::string& name : methods::volume_method_names()) {
            if (name != "reference") {
                cases.push_back({name, "", ""});
            }
        }
        cases.push_back({"march", "clip", "pyramid"});
        for (const char* name : {"beamtree", "hybrid1", "hybrid2", "hybrid3"}) {
            cases.push_back({name, "route", "walk"});
        }
        for (const Case& c : cases) {
            auto create = [&] {
                auto method = methods::create_volume_method(c.method);
                if (!c.parameter.empty()) {
                    method->set(c.parameter, c.value);
                }
                return method;
            };
            const auto moving = create();
            const std::vector<Image> updated = play(animated, *moving, FrameMode::serial, frames);
            for (size_t i = 0; i < frames.size(); ++i) {
                const Scene still = scene_at(animated, animated.animation->frame_time(frames[i]));
                SceneRenderer renderer(still, kSmall);
                const auto fresh = create();
                fresh->prepare(still);
                renderer.draw(*fresh);
                const Image expected = renderer.read_in_scattering();
                // Jitter is off by default, so the frame index leaves no trace.
                EXPECT_LE(test::max_abs_difference(updated[i], expected),
                          1e-5 * (1.0 + test::image_peak(expected)))
                    << scene_name << " " << c.method << " " << c.parameter << "=" << c.value
                    << " frame " << frames[i];
            }
        }
    }
}

TEST_F(FrameLoopTest, PipelinedAndSerialModesGiveTheSameImages) {
    for (const char* scene_name : {"toplight-orbit", "multiple-moving"}) {
        const Scene animated = load_scene(scene_name, SceneSearchPaths::defaults());
        const std::vector<int> frames = {0, 1, 2, 10, 11, 60};
        for (const char* name : {"beamtree", "hybrid2", "hybrid3"}) {
            const auto serial_method = methods::create_volume_method(name);
            const auto pipelined_method = methods::create_volume_method(name);
            const std::vector<Image> serial =
                play(animated, *serial_method, FrameMode::serial, frames);
            const std::vector<Image> pipelined =
                play(animated, *pipelined_method, FrameMode::pipelined, frames);
            ASSERT_EQ(serial.size(), pipelined.size());
            for (size_t i = 0; i < serial.size(); ++i) {
                EXPECT_EQ(serial[i].rgb, pipelined[i].rgb)
                    << scene_name << " " << name << " frame " << frames[i];
            }
            // The frames differ from each other: the scene moves.
            EXPECT_GT(test::max_abs_difference(serial.front(), serial.back()), 0.0) << scene_name;
        }
    }
}

TEST_F(FrameLoopTest, AnUpdateThatFailsStopsTheLoopWithItsError) {
    const Scene animated = load_scene("toplight-orbit", SceneSearchPaths::defaults());
    const auto method = methods::create_volume_method("beamtree");
    Scene live = scene_at(animated, 0.0);
    SceneRenderer renderer(live, kSmall);
    method->prepare(live);
    for (const FrameMode mode : {FrameMode::serial, FrameMode::pipelined}) {
        FrameLoop loop(renderer, *method, live, mode);
        int drawn = 0;
        EXPECT_THROW(loop.play(
                         5,
                         [&](int k) {
                             Scene s = scene_at(animated, 0.1 * k);
                             if (k == 3) {
                                 // The light inside the box's outer volume: the tree refuses.
                                 s.light.position = glm::vec3(s.objects[2].transform[3]);
                             }
                             return s;
                         },
                         [&](const FrameRecord&) { ++drawn; }),
                     Error);
        EXPECT_LE(drawn, 3) << to_string(mode);
        method->prepare(live);
    }
}

}  // namespace
}  // namespace sl::frame
