#include "tests/gl_support.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "core/error.h"
#include "frame/volume_method.h"
#include "gl/debug.h"
#include "gl/functions.h"
#include "gl/objects.h"
#include "gl/shaders.h"
#include "methods/configured_method.h"
#include "methods/registry.h"

namespace sl::test {

gl::Platform& headless_gl() {
    static std::unique_ptr<gl::Platform> platform = gl::create_headless_platform();
    platform->make_current();
    return *platform;
}

void GlTest::SetUp() {
    headless_gl();
    gl::take_errors();
}

void GlTest::TearDown() {
    const std::vector<std::string> errors = gl::take_errors();
    for (const std::string& error : errors) {
        ADD_FAILURE() << error;
    }
}

std::vector<float> render_test_pattern(const gl::shared::FrameUniforms& uniforms,
                                       const char* fragment_shader, int width, int height,
                                       const std::vector<std::string>& defines) {
    const gl::Buffer ubo = gl::create_buffer(&uniforms, sizeof(uniforms));
    gl::GL.BindBufferBase(GL_UNIFORM_BUFFER, SL_FRAME_UNIFORMS_BINDING, ubo.id());
    const gl::Texture target = gl::create_texture_2d(GL_RGBA32F, width, height, GL_NEAREST);
    const gl::Framebuffer framebuffer = gl::create_framebuffer();
    gl::GL.NamedFramebufferTexture(framebuffer.id(), GL_COLOR_ATTACHMENT0, target.id(), 0);
    const gl::Program program = gl::create_program(
        {{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"}, {GL_FRAGMENT_SHADER, fragment_shader}},
        defines);
    gl::GL.BindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    gl::GL.Viewport(0, 0, width, height);
    gl::GL.UseProgram(program.id());
    const gl::VertexArray empty = gl::create_vertex_array();
    gl::GL.BindVertexArray(empty.id());
    gl::GL.DrawArrays(GL_TRIANGLES, 0, 3);
    std::vector<float> rgba(size_t(width) * height * 4);
    gl::GL.GetTextureImage(target.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(rgba.size() * sizeof(float)),
                           rgba.data());
    gl::check_errors(fragment_shader);
    return rgba;
}

TestRay test_pattern_ray(const gl::shared::FrameUniforms& uniforms, int x, int y, int width,
                         int height) {
    const glm::dmat4 inverse(uniforms.inverse_view_projection);
    const glm::dvec2 ndc(2.0 * (x + 0.5) / width - 1.0, 2.0 * (y + 0.5) / height - 1.0);
    const glm::dvec4 far = inverse * glm::dvec4(ndc, 1.0, 1.0);
    const glm::dvec3 origin(uniforms.camera_position);
    return {origin, glm::normalize(glm::dvec3(far) / far.w - origin)};
}

double red_peak(const std::vector<float>& rgba) {
    double peak = 0.0;
    for (size_t i = 0; i < rgba.size(); i += 4)
        peak = std::max(peak, double(rgba[i]));
    return peak;
}

PixelRay pixel_ray(const Scene& scene, const PixelUnprojector& unproject, const frame::Frame& frame,
                   int x, int y) {
    const glm::dvec3 eye(scene.camera.position);
    const glm::dvec3 far = unproject.point(x, y, 1.0);
    const double depth = frame.depth[size_t(y) * size_t(frame.in_scattering.width) + size_t(x)];
    const bool surface = depth < 1.0;
    return {{eye, glm::normalize(far - eye)},
            glm::length((surface ? unproject.point(x, y, 2.0 * depth - 1.0) : far) - eye),
            surface};
}

frame::Frame render_method(const Scene& scene, const std::string& method, int width, int height,
                           const std::vector<std::pair<std::string, std::string>>& settings) {
    frame::SceneRenderer renderer(scene, {.width = width, .height = height});
    const auto volume_method = methods::create_volume_method(method);
    for (const auto& [name, value] : settings)
        volume_method->set(name, value);
    volume_method->prepare(scene);
    return renderer.render(*volume_method);
}

void expect_refused(const std::string& method, const std::string& name, const std::string& value,
                    const std::string& words) {
    try {
        render_method(boxes_scene(MediumModel::physical), method, 1280, 720, {{name, value}});
        ADD_FAILURE() << method << " accepted " << name << " = " << value;
    } catch (const sl::Error& error) {
        EXPECT_NE(std::string(error.what()).find(words), std::string::npos) << error.what();
    }
}

}  // namespace sl::test
