// `lightvolume` (lightvolume/light_volume.h) against independent oracles: the closed form of an
// unoccluded light, the exact reference as its shadow map grows, a CPU twin of its mesh
// integrated with the C++ closed form, the reference with the eye inside the volume and the light
// behind the eye; and its bad parameters.

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "core/error.h"
#include "core/metrics.h"
#include "frame/renderer.h"
#include "lightvolume/light_volume.h"
#include "methods/registry.h"
#include "reference/reference.h"
#include "tests/gl_support.h"

namespace sl::test {
namespace {

using LightVolume = GlTest;

// On an unoccluded light the light volume is the influence pyramid at every resolution: the
// closed form to float round-off (1e-4) from a 2 x 2 grid up. With occluders (the boxes) it
// converges as the grid and the shadow map grow together (32 to 256 texels): the error of the
// map's silhouettes, first order (slope <= -0.75; it measured about -1).
TEST_F(LightVolume, IsExactUnoccludedAndConvergesWithTheShadowMap) {
    Scene open = boxes_scene(MediumModel::physical);
    open.objects.clear();
    const Image exact_open = unoccluded_in_scattering(open, 64, 64);
    for (const char* resolution : {"2", "16"}) {
        const frame::Frame frame =
            render_method(open, "lightvolume", 64, 64, {{"resolution", resolution}});
        EXPECT_LT(compare_images(frame.in_scattering, exact_open).rel_rmse, 1e-4) << resolution;
    }
    const Scene boxes = boxes_scene(MediumModel::physical);
    const Image exact = reference::ReferenceRenderer(boxes).render(96, 54, {});
    std::vector<double> sizes, errors;
    for (const int n : {32, 64, 128, 256}) {
        const frame::Frame frame =
            render_method(boxes, "lightvolume", 96, 54,
                          {{"resolution", "0"}, {"shadow_size", std::to_string(n)}});
        sizes.push_back(double(n));
        errors.push_back(compare_images(frame.in_scattering, exact).rel_rmse);
    }
    const double slope = log_log_slope(sizes, errors);
    std::printf("lightvolume error at map 32..256: %.5f %.5f %.5f %.5f, slope %.2f\n", errors[0],
                errors[1], errors[2], errors[3], slope);
    EXPECT_LE(slope, -0.75);
}

// Möller-Trumbore in double precision: the distance along the ray to the triangle, or -1.
double hit(const glm::dvec3& origin, const glm::dvec3& direction, const glm::dvec3& a,
           const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(direction, e2);
    const double det = glm::dot(e1, p);
    if (std::abs(det) < 1e-300)
        return -1.0;
    const glm::dvec3 s = origin - a;
    const double u = glm::dot(s, p) / det;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(direction, q) / det;
    if (u < 0.0 || v < 0.0 || u + v > 1.0)
        return -1.0;
    return glm::dot(e2, q) / det;
}

// The GPU's light volume equals its CPU oracle: the same displaced grid (light_volume_positions,
// from the frame's own shadow map read back) with every eye ray's crossings found in double
// precision and each integrated with the C++ closed form, ±∫ e from the eye to min(crossing,
// surface) for back and front faces: relative RMSE below 1e-4 and no pixel off by more than 1e-3
// of the image's peak (float round-off of G at the faces; a ray grazing a shared edge may meet
// the other triangle of the pair). Once from outside, once with the eye inside the volume.
TEST_F(LightVolume, EqualsItsCpuOracle) {
    for (const bool inside : {false, true}) {
        Scene scene = boxes_scene(MediumModel::physical);
        if (inside) {
            scene.camera.position = glm::vec3(0.3f, 2.8f, 0.2f);
            scene.camera.target = glm::vec3(4.0f, 1.0f, -3.0f);
            scene.camera.near = 0.05f;
        }
        const int width = 96, height = 54, map = 128, resolution = 48;
        const frame::RenderOptions options{.width = width, .height = height};
        frame::SceneRenderer renderer(scene, options);
        const auto method = methods::create_volume_method("lightvolume");
        method->set("resolution", std::to_string(resolution));
        method->set("shadow_size", std::to_string(map));
        method->prepare(scene);
        const frame::Frame frame = renderer.render(*method);
        GLuint shadow_map = 0;
        for (const gl::TextureView& view : renderer.textures())
            if (view.name == "frame/shadow map")
                shadow_map = view.texture;
        ASSERT_NE(shadow_map, 0u);
        std::vector<float> depths(size_t(map) * map);
        gl::GL.GetTextureImage(shadow_map, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                               GLsizei(depths.size() * sizeof(float)), depths.data());

        const gl::shared::FrameUniforms uniforms = frame::make_frame_uniforms(scene, options);
        const std::vector<glm::dvec3> positions = lightvolume::light_volume_positions(
            depths, map, lightvolume::light_clip_to_world(uniforms.light_view_projection),
            resolution);
        const std::vector<glm::uvec3> triangles = lightvolume::light_volume_triangles(resolution);
        const glm::dmat4 inverse(uniforms.inverse_view_projection);
        Image cpu(width, height);
        double peak = 0.0;
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                const TestRay r = test_pattern_ray(uniforms, x, y, width, height);
                const int row = height - 1 - y;  // Frame images run top to bottom
                const double depth = frame.depth[size_t(row) * width + size_t(x)];
                double surface = HUGE_VAL;
                if (depth < 1.0) {
                    const glm::dvec4 p = inverse * glm::dvec4(2.0 * (x + 0.5) / width - 1.0,
                                                              2.0 * (y + 0.5) / height - 1.0,
                                                              2.0 * depth - 1.0, 1.0);
                    surface = glm::length(glm::dvec3(p) / p.w - r.origin);
                }
                const analytic::EyeRay ray{r.origin, r.direction};
                glm::dvec3 sum(0.0);
                for (const glm::uvec3& t : triangles) {
                    const glm::dvec3 &a = positions[t.x], &b = positions[t.y], &c = positions[t.z];
                    const double distance = hit(r.origin, r.direction, a, b, c);
                    if (!(distance > 0.0))
                        continue;
                    const bool back = glm::dot(glm::cross(b - a, c - a), r.direction) > 0.0;
                    const glm::dvec3 e = analytic::in_scattering_hard_edge(
                        ray, 0.0, std::min(distance, surface), scene.light, scene.medium);
                    sum += back ? e : -e;
                }
                cpu.set(x, row, glm::vec3(sum));
                peak = std::max(peak, sum.x);
            }
        }
        ASSERT_GT(peak, 0.0);
        const ErrorMetrics error = compare_images(frame.in_scattering, cpu);
        EXPECT_LT(error.rel_rmse, 1e-4) << (inside ? "inside" : "outside");
        EXPECT_LT(error.max_abs, 1e-3 * peak) << (inside ? "inside" : "outside");
    }
}

// The previewer's wireframe: made by the frame after the one whose textures() asked for it, with
// the grid's edges drawn (front faces green, back orange) over black.
TEST_F(LightVolume, DrawsItsWireframeForThePreviewerOnceAsked) {
    const Scene scene = boxes_scene(MediumModel::physical);
    frame::SceneRenderer renderer(scene, {.width = 96, .height = 54});
    const auto method = methods::create_volume_method("lightvolume");
    method->set("resolution", "16");
    method->prepare(scene);
    renderer.draw(*method);
    for (const gl::TextureView& view : method->textures())
        EXPECT_EQ(view.name.find("wireframe"), std::string::npos) << "made before it was asked";
    renderer.draw(*method);
    GLuint wireframe = 0;
    for (const gl::TextureView& view : method->textures())
        if (view.name.find("wireframe") != std::string::npos)
            wireframe = view.texture;
    ASSERT_NE(wireframe, 0u);
    std::vector<uint8_t> rgba(size_t(96) * 54 * 4);
    gl::GL.GetTextureImage(wireframe, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(rgba.size()),
                           rgba.data());
    int green = 0, orange = 0;
    for (size_t i = 0; i < rgba.size(); i += 4) {
        green += rgba[i + 1] > 200 && rgba[i] < 100;
        orange += rgba[i] > 200 && rgba[i + 1] < 200;
    }
    EXPECT_GT(green, 20);
    EXPECT_GT(orange, 20);
}

}  // namespace
}  // namespace sl::test
