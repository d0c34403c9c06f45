// `epipolar` (epipolar/epipolar.h) against independent oracles: its slice geometry on the CPU
// (the slices tile the image, the unwarp finds them, and every eye ray of a slice projects onto
// the slice's shadow-map line); its min-max march against the plain march of the same rectified
// map; with interpolation off, `march` at the same steps; the unoccluded closed form through the
// interpolation; the reference as its sampling grows.

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
#include "tests/support.h"

namespace sl::test {
namespace {

using namespace sl::epipolar;

Views views_of(const Scene& scene, int width, int height) {
    return {.view_projection = glm::dmat4(scene.camera.projection(float(width) / float(height)) *
                                          scene.camera.view()),
            .light_view_projection = glm::dmat4(scene.light.projection() * scene.light.view()),
            .camera = glm::dvec3(scene.camera.position),
            .light = glm::dvec3(scene.light.position),
            .width = width,
            .height = height};
}

// The boxes scene seen so that the light's screen position lies inside the image, beyond each
// side and corner, behind the camera, and (nearly) in the camera's plane. Named.
std::vector<std::pair<std::string, Scene>> light_placements() {
    std::vector<std::pair<std::string, Scene>> scenes;
    const Scene boxes = boxes_scene(MediumModel::physical);
    const auto add = [&](const std::string& name, glm::vec3 position, glm::vec3 target) {
        Scene scene = boxes;
        scene.camera.position = position;
        scene.camera.target = target;
        scenes.emplace_back(name, std::move(scene));
    };
    add("light on screen", {6.0f, 1.0f, 6.0f}, {0.8f, 5.0f, -0.5f});
    add("light above (boxes)", boxes.camera.position, boxes.camera.target);
    add("light right", {-6.0f, 5.0f, 6.0f}, {-6.0f, 4.0f, -3.0f});
    add("light left, above", {6.0f, 2.0f, 6.0f}, {4.0f, 1.0f, -2.0f});
    add("light behind", {0.9f, 6.5f, -0.6f}, {-0.2f, 0.0f, 0.1f});
    add("light in the camera's plane", {-2.5f, 2.0f, -0.5f}, {-2.5f, 2.0f, -10.0f});
    return scenes;
}

double cross2(glm::dvec2 a, glm::dvec2 b) {
    return a.x * b.y - a.y * b.x;
}

// The slices, for every placement of the light: each exit point lies on the image border and
// each entry inside the image; the unwarp (slice_coordinate) of every point of slice s is s; and
// every pixel centre lies between the two slices its coordinate names (the pixel's direction
// from the light's screen position turns the same way from the first as to the second).
TEST(EpipolarGeometry, SlicesTileTheImageAndTheUnwarpFindsThem) {
    const int width = 160, height = 90, n = 64;
    for (const auto& [name, scene] : light_placements()) {
        const Views views = views_of(scene, width, height);
        const glm::dvec2 p = light_screen_position(views);
        const ExitArc arc = exit_arc(p, width, height);
        const std::vector<Slice> slices = make_slices(views, n, 1024);
        ASSERT_EQ(slices.size(), size_t(n));
        for (int s = 0; s < n; ++s) {
            const Slice& slice = slices[size_t(s)];
            const double to_border =
                std::min({slice.exit.x, slice.exit.y, width - slice.exit.x, height - slice.exit.y});
            EXPECT_NEAR(to_border, 0.0, 1e-9) << name << " slice " << s;
            EXPECT_TRUE(inside_image(slice.entry, width, height)) << name << " slice " << s;
            for (const double lambda : {0.1, 0.5, 0.99}) {
                const glm::dvec2 x = slice.entry + lambda * (slice.exit - slice.entry);
                if (glm::length(x - p) < 1e-3 || slice.entry == slice.exit) {
                    continue;
                }
                EXPECT_NEAR(slice_coordinate(p, arc, x, n, width, height), double(s), 1e-6)
                    << name << " slice " << s << " at " << lambda;
            }
        }
        int checked = 0;
        for (int y = 0; y < height; y += 3) {
            for (int x = 0; x < width; x += 3) {
                const glm::dvec2 pixel(x + 0.5, y + 0.5);
                const double c = slice_coordinate(p, arc, pixel, n, width, height);
                ASSERT_TRUE(std::isfinite(c)) << name;
                EXPECT_GE(c, -0.5 - 1e-9) << name;
                EXPECT_LE(c, n - 0.5 + 1e-9) << name;
                const int s0 = int(std::floor(c));
                if (!arc.periodic && (s0 < 0 || s0 + 1 >= n)) {
                    continue;  // beyond the first or last slice: the unwarp clamps
                }
                const glm::dvec2 a = slices[size_t((s0 + n) % n)].exit - p;
                const glm::dvec2 b = slices[size_t((s0 + 1) % n)].exit - p;
                const glm::dvec2 d = pixel - p;
                EXPECT_GE(cross2(a, d) * cross2(d, b),
                          -1e-9 * glm::length(a) * glm::length(b) * glm::dot(d, d))
                    << name << " pixel " << x << "," << y << " c " << c;
                ++checked;
            }
        }
        EXPECT_GT(checked, 1000) << name;
    }
}

// Chen et al.'s rectification: every point of every eye ray of slice s (through a point of its
// segment) that the light sees projects onto the slice's line in the shadow map, to 1e-5 of the
// map (a 2048² map's texel is 5e-4; the camera's matrices are float, and the eye they imply is
// the camera's position to 1e-7, which the light's projection magnifies where the eye is half a
// metre from it); and the line's part inside the map is what the slice records. A light in the
// camera's plane projects to infinity and its screen position is moved to 1e3 image diagonals,
// which turns the slices by up to 1e-3 rad: there the points lie within 1e-4 of the map (a fifth of
// a texel; the march projects each point onto the line, so this is harmless).
TEST(EpipolarGeometry, EveryEyeRayOfASliceProjectsOntoItsShadowMapLine) {
    const int width = 160, height = 90, n = 48;
    for (const auto& [name, scene] : light_placements()) {
        const Views views = views_of(scene, width, height);
        const glm::dmat4 inverse = glm::inverse(views.view_projection);
        const std::vector<Slice> slices = make_slices(views, n, 1024);
        const double tolerance = name == "light in the camera's plane" ? 1e-4 : 1e-5;
        int projected = 0;
        for (const Slice& slice : slices) {
            if (slice.map_step == glm::dvec2(0.0) || slice.entry == slice.exit) {
                continue;
            }
            const glm::dvec2 along = glm::normalize(slice.map_step);
            const glm::dvec2 end = slice.map_origin + 1024.0 * slice.map_step;
            for (const auto lo : {slice.map_origin, end}) {
                EXPECT_GE(std::min(lo.x, lo.y), -1e-9) << name;
                EXPECT_LE(std::max(lo.x, lo.y), 1.0 + 1e-9) << name;
            }
            for (const double lambda : {0.0, 0.3, 0.7, 1.0}) {
                const glm::dvec2 x = slice.entry + lambda * (slice.exit - slice.entry);
                const glm::dvec2 ndc = 2.0 * x / glm::dvec2(width, height) - 1.0;
                const glm::dvec4 far = inverse * glm::dvec4(ndc, 1.0, 1.0);
                const glm::dvec3 direction = glm::normalize(glm::dvec3(far) / far.w - views.camera);
                for (double t = 0.05; t < 40.0; t *= 1.3) {
                    const glm::dvec4 clip =
                        views.light_view_projection * glm::dvec4(views.camera + t * direction, 1.0);
                    if (clip.w <= 0.0) {
                        continue;
                    }
                    const glm::dvec2 uv = 0.5 * glm::dvec2(clip) / clip.w + 0.5;
                    if (std::min(uv.x, uv.y) < 0.0 || std::max(uv.x, uv.y) > 1.0) {
                        continue;
                    }
                    EXPECT_NEAR(cross2(along, uv - slice.map_origin), 0.0, tolerance)
                        << name << " t " << t;
                    ++projected;
                }
            }
        }
        EXPECT_GT(projected, 20) << name;
    }
}

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
// edge), the method stays within 2% (relative RMSE) of the closed form wherever the light's
// screen position is, inside the image, beyond a side or a corner, behind the camera: the
// unwarp finds each pixel's samples (a wrong slice or position is off by far more).
TEST_F(Epipolar, InterpolatesAnUnoccludedBeamWhereverTheLightIs) {
    for (auto [name, scene] : light_placements()) {
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
                  name == "light on screen" || name == "light behind")
            << name;
    }
}

// It converges to the exact reference as its slices, samples, refinement and steps grow: the
// error falls at every step and ends below 0.5%, with the light off the screen and on it (where
// I_s peaks as 1/h about the light's own pixel, the hardest case for interpolation).
TEST_F(Epipolar, ConvergesToTheReference) {
    for (const char* name : {"boxes", "light on screen"}) {
        Scene scene = boxes_scene(MediumModel::physical);
        for (auto& [placement, placed] : light_placements()) {
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

// Slices times samples beyond what it keeps: one error naming both parameters, no crash.
TEST_F(Epipolar, RefusesMoreSamplesThanItKeeps) {
    try {
        render_method(boxes_scene(MediumModel::physical), "epipolar", 64, 36,
                      {{"slices", "8192"}, {"samples_per_slice", "8192"}});
        ADD_FAILURE() << "epipolar accepted 8192 x 8192 samples";
    } catch (const sl::Error& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("slices x samples_per_slice"), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace sl::test
