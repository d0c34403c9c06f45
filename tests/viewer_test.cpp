// The viewer's parts that need no display: the camera controller, scripted paths, the error heat
// map, "save as experiment" read back by the harness, and the region overlay's accumulated
// lengths against the beam tree's own classification along CPU eye rays.

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "beamtree/beam_tree.h"
#include "beamtree/regions.h"
#include "core/error.h"
#include "core/metrics.h"
#include "experiments/experiment.h"
#include "gl/functions.h"
#include "methods/registry.h"
#include "reference/reference.h"
#include "scenes/scene_file.h"
#include "tests/gl_support.h"
#include "viewer/camera_controller.h"
#include "viewer/region_overlay.h"
#include "viewer/saved_view.h"

namespace sl::test {
namespace {

using viewer::CameraController;

void expect_near(glm::vec3 a, glm::vec3 b, float tolerance, const char* what) {
    EXPECT_LE(glm::length(a - b), tolerance)
        << what << ": (" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y
        << ", " << b.z << ")";
}

// The controller reproduces the camera it was made from, orbits keep the target and the
// distance, a full turn comes back, flying keeps the position, and the pitch never flips.
TEST(CameraController, OrbitAndFlyKeepTheirInvariants) {
    const Scene scene = load_canonical("toplight");
    Camera camera = scene.camera;
    CameraController controller(camera);
    controller.apply(camera);
    expect_near(camera.position, scene.camera.position, 1e-5f, "round trip position");
    expect_near(camera.target, scene.camera.target, 1e-6f, "round trip target");

    const float distance = glm::length(scene.camera.target - scene.camera.position);
    controller.orbit(0.7f, 0.3f);
    controller.apply(camera);
    expect_near(camera.target, scene.camera.target, 1e-6f, "orbit keeps the target");
    EXPECT_NEAR(glm::length(camera.target - camera.position), distance, 1e-4f);
    EXPECT_GT(glm::length(camera.position - scene.camera.position), 1.0f) << "it moved";
    controller.orbit(-0.7f + 2.0f * std::numbers::pi_v<float>, -0.3f);
    controller.apply(camera);
    expect_near(camera.position, scene.camera.position, 1e-4f, "a full turn comes back");

    const glm::vec3 eye = camera.position;
    controller.look(0.4f, -0.2f);
    controller.apply(camera);
    expect_near(camera.position, eye, 1e-4f, "looking keeps the position");
    const glm::vec3 forward = controller.forward();
    controller.move({0.0f, 0.0f, 2.0f});
    controller.apply(camera);
    expect_near(camera.position, eye + 2.0f * forward, 1e-4f, "moving forward");

    controller.orbit(0.0f, 10.0f);  // far past the pole
    EXPECT_LT(glm::dot(controller.forward(), glm::vec3(0, 1, 0)), std::sin(glm::radians(89.01f)));
    EXPECT_GT(glm::length(glm::cross(controller.forward(), glm::vec3(0, 1, 0))), 0.0f);
    controller.zoom(0.5f);
    EXPECT_NEAR(controller.distance(), distance * 0.5f, 1e-3f);
}

// The heat map is black where the images agree, at the top of the ramp at full scale, and never
// hides a NaN.
TEST(ErrorHeatMap, ScalesWithTheReferenceRms) {
    Image reference(4, 1), image(4, 1);
    for (int x = 0; x < 4; ++x) {
        reference.set(x, 0, glm::vec3(2.0f, 0.0f, 0.0f));  // RMS pixel 2
        image.set(x, 0, glm::vec3(2.0f, 0.0f, 0.0f));
    }
    image.set(1, 0, {3.0f, 0.0f, 0.0f});  // error 1 = 0.5 RMS
    image.set(2, 0, {2.0f, 0.0f, 0.5f});  // error 0.5 = 0.25 RMS
    image.set(3, 0, {std::nanf(""), 0.0f, 0.0f});
    const std::vector<unsigned char> rgb = error_heat_map(image, reference, 0.5);
    auto pixel = [&](int x) {
        return glm::vec3(rgb[size_t(x) * 3], rgb[size_t(x) * 3 + 1], rgb[size_t(x) * 3 + 2]);
    };
    expect_near(pixel(0), 255.0f * heat_color(0.0), 0.6f, "agreement");
    expect_near(pixel(1), 255.0f * heat_color(1.0), 0.6f, "full scale");
    expect_near(pixel(2), 255.0f * heat_color(0.5), 0.6f, "half scale");
    expect_near(pixel(3), 255.0f * heat_color(1.0), 0.6f, "NaN");
    EXPECT_LT(heat_color(0.0).r + heat_color(0.0).g, 0.05f);
    EXPECT_GT(heat_color(1.0).r + heat_color(1.0).g, 1.9f);
    EXPECT_THROW(error_heat_map(image, Image(3, 1), 1.0), Error);
    EXPECT_THROW(error_heat_map(image, reference, 0.0), Error);
}

// "Save as experiment" writes a file the harness reads back to exactly one cell: the saved
// scene's view, the method and every parameter as set, the size and the shadow map.
TEST(SavedView, HarnessReadsTheViewBack) {
    Scene scene = load_canonical("parallel");
    scene.camera.position += glm::vec3(0.25f, -0.1f, 0.5f);
    scene.light.target += glm::vec3(0.3f, 0.0f, 0.0f);
    scene.medium.sigma_s *= 2.0f;
    const auto method = methods::create_volume_method("march");
    method->set("samples", "37");
    method->set("clip", "pyramid");
    TempDir dir;
    const frame::ShadowSettings shadow{
        .filter = frame::ShadowFilter::vsm, .map_size = 512, .radius = 2};
    const viewer::SavedView saved = viewer::save_view_as_experiment(
        dir / "views" / "mine.toml", scene, "parallel", *method, 320, 200, shadow);
    EXPECT_EQ(saved.scene.filename(), "mine.scene.toml");
    EXPECT_EQ(dir.file_count(), 1u) << "only the views folder: no temporaries";

    const experiments::Experiment x = experiments::load_experiment(saved.experiment);
    const std::vector<experiments::Cell> cells = x.cells();
    ASSERT_EQ(cells.size(), 1u);
    const experiments::Cell& cell = cells[0];
    EXPECT_EQ(cell.method, "march");
    EXPECT_EQ(cell.width, 320);
    EXPECT_EQ(cell.height, 200);
    ASSERT_NE(cell.setting("samples"), nullptr);
    EXPECT_EQ(*cell.setting("samples"), "37");
    ASSERT_NE(cell.setting("clip"), nullptr);
    EXPECT_EQ(*cell.setting("clip"), "pyramid");
    EXPECT_EQ(cell.settings.size(), method->parameters().size()) << "every parameter is saved";
    EXPECT_EQ(x.render.shadow, "vsm");
    EXPECT_EQ(x.render.shadow_map_size, 512);
    EXPECT_EQ(x.render.pcf_radius, 2);

    const Scene back = load_scene(cell.scene, SceneSearchPaths::defaults());
    EXPECT_EQ(back.camera.position, scene.camera.position);
    EXPECT_EQ(back.light.target, scene.light.target);
    EXPECT_EQ(back.medium.sigma_s, scene.medium.sigma_s);
    EXPECT_EQ(back.triangle_count(), scene.triangle_count());
    EXPECT_THROW(
        viewer::save_view_as_experiment(dir / "x.txt", scene, "parallel", *method, 8, 8, shadow),
        Error);
}

class RegionOverlayTest : public GlTest {};

// The overlay's accumulated lengths (signed back/front faces clamped at the surface) equal, per
// region type, the length of each eye ray the beam tree classifies as that type up to the first
// surface — sampled on the CPU with classify() and Embree's first hit.
TEST_F(RegionOverlayTest, AccumulatedLengthsMatchCpuClassification) {
    const Scene scene = load_canonical("toplight");
    constexpr int kWidth = 64, kHeight = 40;
    const bt::BeamTree tree = bt::build_scene_beam_tree(scene);
    const bt::Regions regions = bt::extract_regions(tree);
    frame::SceneRenderer renderer(scene, {.width = kWidth, .height = kHeight});
    const auto none = methods::create_volume_method("none");
    renderer.draw(*none);
    GLuint depth = 0;
    for (const gl::TextureView& view : renderer.textures()) {
        if (view.name == "frame/surface depth")
            depth = view.texture;
    }
    ASSERT_NE(depth, 0u);
    viewer::RegionOverlay overlay;
    overlay.upload(regions, scene.light.far);
    const gl::Framebuffer target = gl::create_framebuffer();
    const gl::Texture color = gl::create_texture_2d(GL_RGBA8, kWidth, kHeight, GL_NEAREST);
    gl::GL.NamedFramebufferTexture(target.id(), GL_COLOR_ATTACHMENT0, color.id(), 0);
    overlay.draw(target.id(), depth, kWidth, kHeight, renderer.uniforms().view_projection,
                 viewer::OverlaySettings{});
    std::vector<float> lengths(size_t(kWidth) * kHeight * 4);
    gl::GL.GetTextureImage(overlay.thickness(), 0, GL_RGBA, GL_FLOAT,
                           GLsizei(lengths.size() * sizeof(float)), lengths.data());

    const reference::ReferenceRenderer embree(scene);
    double total = 0.0, error = 0.0;
    std::array<double, 3> seen{};
    int checked = 0;
    for (int y = 1; y < kHeight; y += 3) {
        for (int x = 1; x < kWidth; x += 3) {
            const TestRay ray = test_pattern_ray(renderer.uniforms(), x, y, kWidth, kHeight);
            const double far = 60.0;
            const double hit = embree.first_hit({ray.origin, ray.direction}, far);
            // 2000 midpoint samples along [0, hit]; the classification is the oracle.
            constexpr int kSamples = 2000;
            std::array<double, 3> cpu{};
            for (int s = 0; s < kSamples; ++s) {
                const double t = hit * (s + 0.5) / kSamples;
                const glm::dvec3 p = ray.origin + t * ray.direction;
                if (!scene.light.in_influence_volume(glm::vec3(p)))
                    continue;
                cpu[size_t(tree.classify(p))] += hit / kSamples;
            }
            const size_t i = (size_t(y) * kWidth + x) * 4;
            for (int r = 0; r < 3; ++r) {
                const double gpu = lengths[i + size_t(r)];
                error += std::abs(gpu - cpu[size_t(r)]);
                total += cpu[size_t(r)];
                seen[size_t(r)] += cpu[size_t(r)];
            }
            ++checked;
        }
    }
    ASSERT_GT(checked, 200);
    for (int r = 0; r < 3; ++r) {
        EXPECT_GT(seen[size_t(r)], 1.0) << "the view crosses every region type: " << r;
    }
    // Sampling resolves a boundary to hit/2000; pixels whose centre ray grazes an edge differ.
    EXPECT_LT(error / total, 0.02) << "relative L1 difference of the lengths";
    std::printf("overlay lengths vs CPU classification: relative L1 %.5f over %d rays\n",
                error / total, checked);
    EXPECT_GT(overlay.triangle_count(), 1000u);
    EXPECT_GT(overlay.edge_count(), 1000u);
}

}  // namespace
}  // namespace sl::test
