// `epipolar` (epipolar/epipolar.h) on the GPU against independent oracles (its slice geometry on
// the CPU is tests/epipolar_geometry_test.cpp): its min-max march against the plain march of the
// same rectified map; with interpolation off, `march` at the same steps; the unoccluded closed form
// through the interpolation; the reference as its sampling grows.

#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "core/error.h"
#include "core/metrics.h"
#include "epipolar/geometry.h"
#include "frame/renderer.h"
#include "methods/registry.h"
#include "reference/reference.h"
#include "tests/gl_support.h"

namespace sl::test {
namespace {

using namespace sl::epipolar;

using Epipolar = GlTest;

struct Render {
    frame::Frame frame;
    frame::MethodStatistics statistics;
};

Render render_with_statistics(const Scene& scene, const std::string& method, int width, int height,
                              const std::vector<std::pair<std::string, std::string>>& settings) {
    frame::SceneRenderer renderer(scene, {.width = width, .height = height});
    const auto volume_method = methods::create_volume_method(method);
    for (const auto& [name, value] : settings) {
        volume_method->set(name, value);
    }
    volume_method->prepare(scene);
    frame::Frame frame = renderer.render(*volume_method);
    return {std::move(frame), volume_method->statistics()};
}

double statistic(const frame::MethodStatistics& statistics, const std::string& name) {
    for (const auto& [key, value] : statistics) {
        if (key == name) {
            return value;
        }
    }
    ADD_FAILURE() << "no statistic " << name;
    return 0.0;
}

std::vector<std::pair<std::string, Scene>> oracle_scenes() {
    std::vector<std::pair<std::string, Scene>> scenes = light_placements();
    for (const char* name : {"toplight", "parallel", "multiple"}) {
        scenes.emplace_back(name, load_canonical(name));
    }
    for (const auto& [name, scene] : eye_and_light_views()) {
        scenes.emplace_back(name, scene);
    }
    // Yusov's sun: on screen, off it, behind the camera (the anti-solar point) and across the view
    // (parallel lines).
    for (auto& [name, scene] : sun_placements()) {
        if (name != "sun above (boxes)" && name != "sun left, above") {
            scenes.emplace_back(name, std::move(scene));
        }
    }
    return scenes;
}

// Every placement of a spot light and of a sun.
std::vector<std::pair<std::string, Scene>> placements() {
    std::vector<std::pair<std::string, Scene>> scenes = light_placements();
    for (auto& placed : sun_placements()) {
        scenes.push_back(std::move(placed));
    }
    return scenes;
}

// Chen et al.'s min-max march is exact: walking each slice's 1D min-max tree finds the same lit
// steps as testing every step against the rectified line, and adds their densities in the same
// order, so the two images are equal to float rounding (1e-6 of the peak); on every scene the
// tree reads fewer texels than the plain march tests steps.
TEST_F(Epipolar, MinMaxTreeMarchEqualsThePlainMarchOfTheRectifiedMap) {
    for (const auto& [name, scene] : oracle_scenes()) {
        const std::vector<std::pair<std::string, std::string>> common = {
            {"lit_integral", "samples"},
            {"samples", "48"},
            {"slices", "96"},
            {"samples_per_slice", "64"},
            {"shadow_size", "512"}};
        auto tree = common, plain = common;
        tree.emplace_back("minmax", "true");
        plain.emplace_back("minmax", "false");
        const Render a = render_with_statistics(scene, "epipolar", 96, 54, tree);
        const Render b = render_with_statistics(scene, "epipolar", 96, 54, plain);
        const double peak = image_peak(b.frame.in_scattering);
        ASSERT_GT(peak, 0.0) << name;
        EXPECT_LE(max_abs_difference(a.frame.in_scattering, b.frame.in_scattering), 1e-6 * peak)
            << name;
        const double lookups = statistic(a.statistics, "tree_lookups");
        const double steps = statistic(b.statistics, "tree_lookups");
        EXPECT_LT(lookups, steps) << name;
        std::printf("%-28s tree reads %.0f of %.0f steps (%.1f%%)\n", name.c_str(), lookups, steps,
                    100.0 * lookups / steps);
    }
}

// With interpolation off every pixel is marched directly through the frame's shadow map: the
// method is then `march` with the exact cone clip and the same steps (equal to float rounding),
// on every scene and with the light on and off the screen.
TEST_F(Epipolar, WithoutInterpolationItIsMarchAtTheSameSteps) {
    for (const auto& [name, scene] : oracle_scenes()) {
        const frame::Frame epipolar =
            render_method(scene, "epipolar", 80, 45,
                          {{"interpolation", "false"}, {"samples", "24"}, {"shadow", "pcf"}});
        const frame::Frame march = render_method(
            scene, "march", 80, 45, {{"clip", "cone"}, {"samples", "24"}, {"shadow", "pcf"}});
        const double peak = image_peak(march.in_scattering);
        ASSERT_GT(peak, 0.0) << name;
        EXPECT_LE(max_abs_difference(epipolar.in_scattering, march.in_scattering), 1e-6 * peak)
            << name;
    }
}

// Through the interpolation, on an unoccluded light (no objects: I_s is smooth but for the cone's
// or the sun's box's edge), the method stays within 2% (relative RMSE) of the closed form
// wherever the light's screen position is, inside the image, beyond a side or a corner, behind
// the camera, for a spot light and a sun: the unwarp finds each pixel's samples (a wrong slice or
// position is off by far more).
TEST_F(Epipolar, InterpolatesAnUnoccludedBeamWhereverTheLightIs) {
    for (auto [name, scene] : placements()) {
        scene.objects.clear();
        const Image exact = unoccluded_in_scattering(scene, 160, 90);
        const Render render = render_with_statistics(scene, "epipolar", 160, 90,
                                                     {{"slices", "256"},
                                                      {"samples_per_slice", "128"},
                                                      {"max_step", "4"},
                                                      {"samples", "32"}});
        const double error = compare_images(render.frame.in_scattering, exact).rel_rmse;
        std::printf("%-28s rel_rmse %.5f, fix-up pixels %.0f\n", name.c_str(), error,
                    statistic(render.statistics, "fixup_pixels"));
        EXPECT_LT(error, 0.02) << name;
        // Behind the camera the screen position is that of the point opposite the light.
        EXPECT_EQ(statistic(render.statistics, "light_on_screen") > 0.5,
                  name == "light on screen" || name == "light behind" || name == "sun on screen" ||
                      name == "sun behind")
            << name;
    }
}

// It converges to the exact reference as its slices, samples, refinement and steps grow: the
// error falls at every step and ends below 0.5%, with the light off the screen and on it (where
// I_s peaks as 1/h about the light's own pixel, the hardest case for interpolation), and with the
// sun on screen (Yusov's case: every slice starts at the sun's point).
TEST_F(Epipolar, ConvergesToTheReference) {
    for (const char* name : {"boxes", "light on screen", "sun on screen"}) {
        Scene scene = boxes_scene(MediumModel::physical);
        for (auto& [placement, placed] : placements()) {
            if (placement == name) {
                scene = placed;
            }
        }
        const Image exact = reference::ReferenceRenderer(scene).render(128, 72, {});
        std::vector<double> errors;
        for (const auto& [slices, per_slice, step, samples] :
             {std::tuple{32, 32, 16, 8}, std::tuple{128, 64, 8, 32}, std::tuple{512, 128, 2, 128},
              std::tuple{1024, 512, 1, 256}}) {
            const frame::Frame frame =
                render_method(scene, "epipolar", 128, 72,
                              {{"slices", std::to_string(slices)},
                               {"samples_per_slice", std::to_string(per_slice)},
                               {"max_step", std::to_string(step)},
                               {"samples", std::to_string(samples)}});
            errors.push_back(compare_images(frame.in_scattering, exact).rel_rmse);
        }
        std::printf("%s: epipolar error %.5f %.5f %.5f %.5f\n", name, errors[0], errors[1],
                    errors[2], errors[3]);
        for (size_t i = 1; i < errors.size(); ++i) {
            EXPECT_LT(errors[i], errors[i - 1]) << name << " step " << i;
        }
        EXPECT_LT(errors.back(), 0.005) << name;
    }
}

}  // namespace
}  // namespace sl::test
