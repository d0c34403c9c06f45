// The beam tree's GLSL twin (beamtree/shaders/classify.glsl) against the C++ classify().

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "analytic/gpu_tree.h"
#include "beamtree/beam_tree.h"
#include "beamtree/bounding_volumes.h"
#include "frame/renderer.h"
#include "gl/objects.h"
#include "tests/gl_support.h"

namespace sl::test {
namespace {

using BeamTreeGpu = GlTest;
using glm::dvec3;

// The GPU's classify of 131072 random points in and around the influence volume of each
// canonical scene equals the C++ classify wherever the point is farther than 10ε from every
// plane the answer depends on (float positions, light-relative planes); every region occurs.
TEST_F(BeamTreeGpu, GlslClassifyMatchesCpp) {
    constexpr int kWidth = 512, kHeight = 256;
    for (const char* name : {"toplight", "parallel", "multiple"}) {
        const Scene scene = load_canonical(name);
        bt::VolumeLibrary library({.max_outer_planes = scene.bounds.max_outer_planes,
                                   .automatic_inner = scene.bounds.automatic_inner});
        const bt::BeamTree tree(scene.light, library.build(scene, nullptr));
        analytic::GpuTreeBuffers buffers;  // what the methods upload, at classify.glsl's bindings
        buffers.upload(tree.gpu_tree());
        buffers.bind();

        // Points in the light's cone and range, a little beyond it too.
        std::mt19937 rng(17);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        const dvec3 apex(scene.light.position), axis(scene.light.direction());
        const double half = glm::radians(double(scene.light.cone_half_angle_degrees)) * 1.2;
        dvec3 u = glm::normalize(
            glm::cross(axis, std::abs(axis.y) < 0.9 ? dvec3(0, 1, 0) : dvec3(1, 0, 0)));
        const dvec3 v = glm::cross(axis, u);
        std::vector<glm::vec4> points(size_t(kWidth) * kHeight);
        for (glm::vec4& p : points) {
            const double depth = double(scene.light.far) * (0.02 + 1.05 * unit(rng));
            const double r = depth * std::tan(half) * std::sqrt(unit(rng));
            const double phi = 6.283185307179586 * unit(rng);
            p = glm::vec4(
                glm::vec3(apex + depth * axis + r * (std::cos(phi) * u + std::sin(phi) * v)), 1.0f);
        }
        const gl::Texture texture = gl::create_texture_2d(GL_RGBA32F, kWidth, kHeight, GL_NEAREST);
        gl::GL.TextureSubImage2D(texture.id(), 0, 0, 0, kWidth, kHeight, GL_RGBA, GL_FLOAT,
                                 points.data());
        gl::GL.BindTextureUnit(0, texture.id());
        const gl::shared::FrameUniforms uniforms =
            frame::make_frame_uniforms(scene, {.width = kWidth, .height = kHeight});
        const std::vector<float> rgba =
            render_test_pattern(uniforms, "tests/shaders/classify.frag", kWidth, kHeight);
        size_t compared = 0, differ = 0;
        std::array<size_t, 3> seen{};
        for (size_t i = 0; i < points.size(); ++i) {
            double margin = 0.0;
            const bt::Region expected = tree.classify(dvec3(glm::vec3(points[i])), &margin);
            if (margin <= 10.0 * tree.epsilon()) {
                continue;
            }
            ++compared;
            ++seen[size_t(expected)];
            differ += int(rgba[i * 4]) != int(expected);
        }
        EXPECT_GE(compared, 100000u) << name;
        EXPECT_EQ(differ, 0u) << name;
        for (size_t r = 0; r < 3; ++r) {
            EXPECT_GT(seen[r], 100u) << name << " region " << r;
        }
    }
}

}  // namespace
}  // namespace sl::test
