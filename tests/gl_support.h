#pragma once
// Test support with GL (tests/CMakeLists.txt: shaftlab_gl_tests): one headless GL context per
// test process, a GL-error check for fixtures, full-screen test patterns of the shaders, eye rays
// of a frame's pixels, and one frame of a scene with a method.

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "analytic/in_scattering.h"
#include "frame/renderer.h"
#include "gl/platform.h"
#include "gl/shaders/frame_uniforms.h"
#include "scenes/scene.h"
#include "tests/support.h"

namespace sl::test {

// The process's OSMesa context, created on first use and current from then on.
gl::Platform& headless_gl();

// A fixture for tests that use GL: the context exists, and no GL error may be left at the end.
class GlTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;
};

// Draws a full-screen test pattern with `fragment_shader` (an embedded path) and the given frame
// uniforms into an RGBA32F target; returns its pixels, rows bottom to top. Textures the shader
// reads are the caller's to bind.
std::vector<float> render_test_pattern(const gl::shared::FrameUniforms& uniforms,
                                       const char* fragment_shader, int width, int height,
                                       const std::vector<std::string>& defines = {});

// The eye ray of test-pattern pixel (x, y) (GL rows, bottom to top) made from the very float
// matrix the shader reads, not PixelUnprojector's double inverse: comparisons must be on identical
// rays, or pixels at the cone's edge differ.
struct TestRay {
    glm::dvec3 origin;
    glm::dvec3 direction;
};
TestRay test_pattern_ray(const gl::shared::FrameUniforms& uniforms, int x, int y, int width,
                         int height);
// Calls f(x, y, ray, t, index) for every test-pattern pixel: its eye ray (test_pattern_ray), the
// distance t = 1 + 24 (x + ½) / width the tests/shaders patterns evaluate at, and the offset of
// its RGBA value in the pattern's pixels.
template <typename F>
void for_each_pattern_pixel(const gl::shared::FrameUniforms& uniforms, int width, int height,
                            const F& f) {
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const TestRay r = test_pattern_ray(uniforms, x, y, width, height);
            f(x, y, analytic::EyeRay{r.origin, r.direction}, 1.0 + 24.0 * (x + 0.5) / width,
              (size_t(y) * width + x) * 4);
        }
    }
}
// The largest red value of an RGBA image.
double red_peak(const std::vector<float>& rgba);

// The eye ray through pixel (x, y) of a frame of `scene` (PixelUnprojector's pixels) and the
// distance along it to the frame's surface, from its depth buffer; `surface` is false where the
// pixel sees none (distance: to the far plane).
struct PixelRay {
    analytic::EyeRay ray;
    double distance;
    bool surface;
};
PixelRay pixel_ray(const Scene& scene, const PixelUnprojector& unproject, const frame::Frame& frame,
                   int x, int y);

// One frame of `scene` with the named method and its parameter settings (NAME, VALUE).
frame::Frame render_method(const Scene& scene, const std::string& method, int width, int height,
                           const std::vector<std::pair<std::string, std::string>>& settings = {});

// I_s of every pixel's eye ray with nothing in the way, in closed form (analytic/): the oracle
// of the convergence tests.
Image unoccluded_in_scattering(const Scene& scene, int width, int height);

// Setting `name` to `value` on `method` and rendering a frame of the boxes scene at 1280x720
// throws sl::Error with `words` in its message (a failure of the calling test otherwise).
void expect_refused(const std::string& method, const std::string& name, const std::string& value,
                    const std::string& words);

}  // namespace sl::test
