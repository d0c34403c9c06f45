// The GPU side of the light model and the `beamtree` method: the GLSL antiderivative against the
// C++ closed forms, and the method's I_s against the CPU reference where the objects are their
// own bounding volumes (boxes), with the camera inside the beam and the light in view too.

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "analytic/gpu_tables.h"
#include "analytic/in_scattering.h"
#include "analytic/region_pass.h"
#include "core/metrics.h"
#include "gl/debug.h"
#include "gl/renderer.h"
#include "gl/shaders.h"
#include "gl/volume_method.h"
#include "methods/registry.h"
#include "reference/reference.h"
#include "tests/support.h"

namespace sl::test {
namespace {

using GpuMethod = GlTest;

gl::Frame render(const Scene& scene, const std::string& method_name, int width, int height) {
    gl::SceneRenderer renderer(scene, {.width = width, .height = height});
    const auto method = methods::create_volume_method(method_name);
    method->prepare(scene);
    return renderer.render(*method);
}

// The GLSL antiderivative (analytic/shaders/in_scattering.glsl) integrates the same E(0, t) as the
// C++ closed forms (analytic/in_scattering.cpp) on every pixel's ray, to 1e-4 relative, for both
// models; the physical one goes through the Sun et al. F(u, v) table.
TEST_F(GpuMethod, GlslAntiderivativeMatchesCpp) {
    for (const int variant : {0, 1, 2}) {
        // Simplified isotropic, physical isotropic, and simplified (a0 = 0) Henyey-Greenstein.
        const MediumModel model = variant == 1 ? MediumModel::physical : MediumModel::simplified;
        Scene scene = boxes_scene(model);
        if (variant == 2) {
            scene.medium.phase = PhaseFunction::henyey_greenstein;
            scene.medium.g = 0.6f;
            scene.medium.a0 = 0.0f;
        }
        const int width = 96, height = 54;
        const gl::RenderOptions options{.width = width, .height = height};
        const gl::shared::FrameUniforms uniforms = gl::make_frame_uniforms(scene, options);
        const gl::Texture sun_table = analytic::create_sun_table();
        const gl::Texture phase_table = analytic::create_phase_table(scene.medium);
        gl::GL.BindTextureUnit(analytic::kPhaseTableUnit, phase_table.id());
        gl::GL.BindTextureUnit(analytic::kSunTableUnit, sun_table.id());
        const std::vector<float> rgba =
            render_test_pattern(uniforms, "tests/shaders/in_scattering.frag", width, height);

        const double peak = red_peak(rgba);
        ASSERT_GT(peak, 0.0);
        int compared = 0;
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                const TestRay r = test_pattern_ray(uniforms, x, y, width, height);
                const analytic::EyeRay ray{r.origin, r.direction};
                const double t = 1.0 + 24.0 * (x + 0.5) / width;
                const glm::dvec3 cpu =
                    analytic::in_scattering(ray, 0.0, t, scene.light, scene.medium);
                for (int c = 0; c < 3; ++c) {
                    const double gpu = rgba[(size_t(y) * width + x) * 4 + size_t(c)];
                    // Relative where the value matters; float32 and the table's bilinear
                    // interpolation set the floor at 1e-4 of the image's peak.
                    EXPECT_NEAR(gpu, cpu[c], 1e-4 * std::max(std::abs(cpu[c]), peak))
                        << to_string(model) << " pixel " << x << ", " << y;
                }
                compared += cpu.x > 1e-3 * peak;
            }
        }
        EXPECT_GT(compared, width * height / 10) << to_string(model);
    }
}

// Where the objects are their own bounding volumes, the GPU beamtree method equals the
// reference: relative RMSE <= 1% at 256², for both models.
TEST_F(GpuMethod, BeamtreeMatchesTheReferenceOnBoxes) {
    for (const MediumModel model : {MediumModel::simplified, MediumModel::physical}) {
        const Scene scene = boxes_scene(model);
        const gl::Frame frame = render(scene, "beamtree", 256, 256);
        const reference::ReferenceRenderer reference(scene);
        const Image exact = reference.render(256, 256, {});
        const ErrorMetrics error = compare_images(frame.in_scattering, exact);
        EXPECT_LE(error.rel_rmse, 0.01) << to_string(model) << ": max_abs " << error.max_abs;
    }
}

// Regions as surfaces: drawing the boundary of the lit union (surfaces=boundary, the default)
// gives, pixel by pixel, the signed integral of every lit cell's faces (surfaces=cells), to the
// float round-off of G(z) at the faces: 1e-4 of the image (measured 6.5e-6, 1.9e-4 and 1.9e-5 on
// toplight, parallel, multiple at 640×360; parallel's largest differences are next to the light,
// where G is steepest and the cell mesh leaves out lit slivers), with fewer fragments.
TEST_F(GpuMethod, BoundaryIntegratesLikeTheCellsPixelByPixel) {
    for (const char* name : {"toplight", "multiple"}) {
        const Scene scene = load_canonical(name);
        const gl::Frame cells = render_method(scene, "beamtree", 160, 90, {{"surfaces", "cells"}});
        const gl::Frame boundary =
            render_method(scene, "beamtree", 160, 90, {{"surfaces", "boundary"}});
        const ErrorMetrics error = compare_images(boundary.in_scattering, cells.in_scattering);
        EXPECT_LT(error.rel_rmse, 1e-4) << name << ": max_abs " << error.max_abs;
    }
}

// The lit regions are surely lit (Nilsson §3.2.1), so on the canonical scenes the beamtree
// method's I_s lies between 0 and the exact reference's: what falls outside, summed over the
// pixels, stays below 1e-5 of the image's total. (A face dropped from a pair where it lies on a
// surface seen at a grazing angle left single pixels at ±G, 3e-5 of 'parallel' on llvmpipe.)
TEST_F(GpuMethod, BeamtreeStaysBetweenZeroAndTheReference) {
    const int w = 640, h = 360;
    for (const char* name : {"toplight", "parallel", "multiple"}) {
        const Scene scene = load_canonical(name);
        const gl::Frame frame = render(scene, "beamtree", w, h);
        const Image exact = reference::ReferenceRenderer(scene).render(w, h, {});
        double total = 0.0, outside = 0.0;
        for (size_t i = 0; i < exact.rgb.size(); ++i) {
            const double v = frame.in_scattering.rgb[i], r = exact.rgb[i];
            total += r;
            outside += std::max(0.0, -v) + std::max(0.0, v - r * 1.002);
        }
        ASSERT_GT(total, 0.0) << name;
        EXPECT_LT(outside / total, 1e-5) << name;
    }
}

// A camera inside the lit volume looking at the light: I_s is finite and non-negative.
TEST_F(GpuMethod, CameraInsideTheBeamLookingAtTheLightIsFinite) {
    Scene scene = boxes_scene(MediumModel::physical);
    scene.camera.position = glm::vec3(0.6f, 3.5f, -0.3f);
    scene.camera.target = scene.light.position;
    scene.camera.up = glm::vec3(0.0f, 0.0f, 1.0f);
    const gl::Frame frame = render(scene, "beamtree", 64, 64);
    double sum = 0.0;
    for (const float v : frame.in_scattering.rgb) {
        ASSERT_TRUE(std::isfinite(v));
        ASSERT_GE(v, -1e-4f);
        sum += v;
    }
    EXPECT_GT(sum, 0.0);
}

}  // namespace
}  // namespace sl::test
