// Paired frame measurement (methods/frame_measurement.h): a method's frames and a baseline's drawn
// in pairs in one context, the order alternating pair by pair (ABBA), and each pair's difference
// the method's frame less the baseline's of the same pair.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "frame/renderer.h"
#include "frame/volume_method.h"
#include "methods/frame_measurement.h"
#include "tests/gl_support.h"

namespace sl::test {
namespace {

// A method that draws nothing and records when it is drawn.
class Recorder final : public frame::VolumeMethod {
public:
    Recorder(std::string name, std::vector<std::string>& log)
        : VolumeMethod(std::move(name)), log_(log) {}
    void prepare_light(const Scene&) override {}
    std::unique_ptr<frame::FrameWork> cpu_update_light(const Scene&,
                                                       const SceneChange&) const override {
        return nullptr;
    }
    void apply_update_light(const Scene&, const SceneChange&,
                            std::unique_ptr<frame::FrameWork>) override {}
    void render(const frame::VolumeInputs&) override { log_.push_back(name()); }

private:
    std::vector<std::string>& log_;
};

TEST_F(GlTest, PairedFramesAlternateTheirOrderAndDifferPairByPair) {
    const Scene scene = boxes_scene(MediumModel::physical);
    frame::SceneRenderer renderer(scene, {.width = 32, .height = 18});
    std::vector<std::string> log;
    Recorder method("a", log), baseline("b", log);
    const methods::PairedMeasurement m =
        methods::measure_paired_frames(renderer, method, baseline, 1, 4);
    // One warm-up pair, four measured pairs (AB BA AB BA), then the method once more so that the
    // renderer holds its frame.
    const std::vector<std::string> expected = {"a", "b", "a", "b", "b", "a",
                                               "a", "b", "b", "a", "a"};
    EXPECT_EQ(log, expected);
    ASSERT_EQ(m.method.frame_ms.size(), 4u);
    ASSERT_EQ(m.baseline_ms.size(), 4u);
    ASSERT_EQ(m.difference_ms.size(), 4u);
    for (size_t i = 0; i < 4; ++i) {
        EXPECT_DOUBLE_EQ(m.difference_ms[i], m.method.frame_ms[i] - m.baseline_ms[i]);
        EXPECT_GT(m.baseline_ms[i], 0.0);
    }
}

}  // namespace
}  // namespace sl::test
