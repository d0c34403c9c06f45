// `froxel` (froxel/froxel.h) against independent oracles: the closed form of an unoccluded
// light, the closed form of a constant slab for its integration, the exact reference with the eye
// inside the light and the light behind the eye, the average its temporal filter converges to;
// and its bad parameters.

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "core/error.h"
#include "core/metrics.h"
#include "frame/renderer.h"
#include "froxel/froxel.h"
#include "methods/registry.h"
#include "reference/reference.h"
#include "tests/gl_support.h"

namespace sl::test {
namespace {

using Froxel = GlTest;

// On an unoccluded light the froxel grid converges to the closed form as it grows on every axis
// (grid_scale 1, 2, 4, 8: 8 to 64 columns and 64 to 512 slices at 64²): the error falls at least
// as fast as the froxels' size to the power 0.75 (the shaft's edge is blurred over a column; it
// measured a slope of about -1).
TEST_F(Froxel, ConvergesToTheClosedFormOfAnUnoccludedLight) {
    Scene scene = boxes_scene(MediumModel::physical);
    scene.objects.clear();
    const int size = 64;
    const Image exact = unoccluded_in_scattering(scene, size, size);
    std::vector<double> scales, errors;
    for (const double scale : {1.0, 2.0, 4.0, 8.0}) {
        const frame::Frame frame =
            render_method(scene, "froxel", size, size, {{"grid_scale", std::to_string(scale)}});
        scales.push_back(scale);
        errors.push_back(compare_images(frame.in_scattering, exact).rel_rmse);
    }
    const double slope = log_log_slope(scales, errors);
    std::printf("froxel error at grid_scale 1..8: %.5f %.5f %.5f %.5f, slope %.2f\n", errors[0],
                errors[1], errors[2], errors[3], slope);
    EXPECT_LE(slope, -0.75);
    EXPECT_LT(errors.back(), 0.02);
}

// The froxel integration conserves energy: a slab of constant density S and extinction σt
// integrates, at the far side of every slice k, to the closed form S (1 - e^(-σt L)) / σt with L
// the ray's length to that side (S L without extinction), whatever the slicing — to 2e-5
// relative in float. A Riemann step T S Δt would be off by σt Δt / 2 (here up to 40%).
TEST_F(Froxel, IntegrationOfAConstantSlabIsItsClosedForm) {
    for (const MediumModel model : {MediumModel::physical, MediumModel::simplified}) {
        Scene scene = boxes_scene(model);
        scene.medium.sigma_s = glm::vec3(0.2f, 0.4f, 0.8f);
        scene.medium.sigma_a = glm::vec3(0.05f);
        const frame::RenderOptions options{.width = 64, .height = 48};
        const gl::shared::FrameUniforms uniforms = frame::make_frame_uniforms(scene, options);
        const gl::Buffer ubo = gl::create_buffer(&uniforms, sizeof(uniforms));
        gl::GL.BindBufferBase(GL_UNIFORM_BUFFER, SL_FRAME_UNIFORMS_BINDING, ubo.id());
        const froxel::FroxelGrid grid{
            .size = {5, 4, 12}, .depth_extent = 20.0f, .linear_depth = 2.5f};
        const glm::vec4 density(0.3f, 0.7f, 1.1f, 0.0f);
        const gl::Texture densities = gl::create_texture_3d(GL_RGBA32F, 5, 4, 12, GL_LINEAR);
        gl::GL.ClearTexImage(densities.id(), 0, GL_RGBA, GL_FLOAT, &density[0]);
        const gl::Texture integrated = gl::create_texture_3d(GL_RGBA32F, 5, 4, 12, GL_LINEAR);
        froxel::FroxelIntegrator().integrate(grid, densities.id(), integrated.id());
        std::vector<float> texels(size_t(5 * 4 * 12) * 4);
        gl::GL.GetTextureImage(integrated.id(), 0, GL_RGBA, GL_FLOAT,
                               GLsizei(texels.size() * sizeof(float)), texels.data());
        const glm::dvec3 sigma_t = model == MediumModel::physical
                                       ? glm::dvec3(scene.medium.sigma_s + scene.medium.sigma_a)
                                       : glm::dvec3(0.0);
        const glm::dmat4 inverse(uniforms.inverse_view_projection);
        const glm::dvec3 eye(uniforms.camera_position), forward(uniforms.camera_forward);
        double worst = 0.0;
        for (int k = 0; k < 12; ++k) {
            for (int y = 0; y < 4; ++y) {
                for (int x = 0; x < 5; ++x) {
                    const glm::dvec4 far =
                        inverse *
                        glm::dvec4(2.0 * (x + 0.5) / 5 - 1.0, 2.0 * (y + 0.5) / 4 - 1.0, 1.0, 1.0);
                    const glm::dvec3 direction = glm::normalize(glm::dvec3(far) / far.w - eye);
                    const double length =
                        froxel::slice_depth(grid, k + 1) / glm::dot(direction, forward);
                    for (int c = 0; c < 3; ++c) {
                        const double s = density[c], st = sigma_t[c];
                        const double expected =
                            st > 0.0 ? s * -std::expm1(-st * length) / st : s * length;
                        const double got = texels[((size_t(k) * 4 + y) * 5 + x) * 4 + size_t(c)];
                        worst = std::max(worst, std::abs(got - expected) / expected);
                    }
                }
            }
        }
        EXPECT_LT(worst, 2e-5) << to_string(model);
    }
}

// Temporal reprojection averages the jitter: on a still view, against the same grid without
// jitter at 64 samples per froxel (what the jittered points average to), 24 frames with the
// history are at least 2x closer than one jittered frame without it.
TEST_F(Froxel, HistoryAveragesTheJitterOfAStillView) {
    const Scene scene = boxes_scene(MediumModel::physical);
    const Image mean = render_method(scene, "froxel", 96, 54, {{"samples", "64"}}).in_scattering;
    const auto error_after = [&](int frames, bool temporal) {
        frame::SceneRenderer renderer(scene, {.width = 96, .height = 54});
        const auto method = methods::create_volume_method("froxel");
        method->set("jitter", "1");
        method->set("temporal", temporal ? "1" : "0");
        method->prepare(scene);
        for (int i = 0; i + 1 < frames; ++i)
            renderer.draw(*method);
        return compare_images(renderer.render(*method).in_scattering, mean).rel_rmse;
    };
    const double single = error_after(1, false), accumulated = error_after(24, true);
    std::printf("froxel jitter noise: one frame %.5f, 24 with history %.5f\n", single, accumulated);
    EXPECT_LT(accumulated, 0.5 * single);
}

// The previewer's slices: made by the frame after the one whose textures() asked for them, each
// volume's slices side by side, the integral growing from slice to slice along a lit column.
TEST_F(Froxel, ShowsItsSlicesToThePreviewerOnceAsked) {
    const Scene scene = boxes_scene(MediumModel::physical);
    frame::SceneRenderer renderer(scene, {.width = 96, .height = 54});
    const auto method = methods::create_volume_method("froxel");
    method->prepare(scene);
    renderer.draw(*method);
    EXPECT_TRUE(method->textures().empty());
    renderer.draw(*method);
    const gl::TextureViews views = method->textures();
    ASSERT_EQ(views.size(), 2u);
    // 12 x 7 columns, 64 slices: 8 x 8 tiles of 12 x 7.
    std::vector<float> rgba(size_t(96) * 56 * 4);
    gl::GL.GetTextureImage(views[1].texture, 0, GL_RGBA, GL_FLOAT,
                           GLsizei(rgba.size() * sizeof(float)), rgba.data());
    double first = 0.0, last = 0.0;
    for (int y = 0; y < 7; ++y) {
        for (int x = 0; x < 12; ++x) {
            first += rgba[(size_t(y) * 96 + x) * 4];
            last += rgba[(size_t(7 * 7 + y) * 96 + 7 * 12 + x) * 4];
        }
    }
    EXPECT_GT(last, first);
    EXPECT_GT(last, 0.0);
}

}  // namespace
}  // namespace sl::test
