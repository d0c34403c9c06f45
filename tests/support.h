#pragma once
// Shared test support: one headless GL context per test process, a GL-error check for fixtures,
// temporary directories, and a brute-force CPU ray caster used as an independent visibility
// oracle for the shadow map.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "analytic/in_scattering.h"
#include "core/image.h"
#include "frame/renderer.h"
#include "gl/platform.h"
#include "gl/shaders/frame_uniforms.h"
#include "scenes/scene.h"

namespace sl::test {

// The process's OSMesa context, created on first use and current from then on.
gl::Platform& headless_gl();

// A fixture for tests that use GL: the context exists, and no GL error may be left at the end.
class GlTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;
};

// A fresh empty directory under the system temp dir, removed by the destructor.
class TempDir {
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
    size_t file_count() const;

private:
    std::filesystem::path path_;
};

void write_text(const std::filesystem::path& path, const std::string& text);
// An EXR as any program might write it: no check of its values (write_exr refuses NaN), for
// testing what readers make of non-finite or huge pixels.
void write_unchecked_exr(const Image& image, const std::filesystem::path& path);

// Brute-force CPU visibility (Möller–Trumbore in double precision over world-space triangles,
// culled by each object's bounding box): an oracle independent of the GPU path.
class CpuRayCaster {
public:
    explicit CpuRayCaster(const Scene& scene);
    // True when the open segment (from, to) hits a triangle of any object.
    bool blocked(glm::vec3 from, glm::vec3 to) const;

private:
    struct WorldObject {
        Bounds bounds;
        std::vector<glm::dvec3> vertices;
        std::vector<glm::uvec3> triangles;
    };
    std::vector<WorldObject> objects_;
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

// The largest difference of two images of one size, channel by channel, and an image's largest
// channel value: the two halves of "equal to float rounding" between two renders.
double max_abs_difference(const Image& a, const Image& b);
double image_peak(const Image& image);

// Least-squares slope of log(y) over log(x): the order of convergence of an error.
double log_log_slope(const std::vector<double>& x, const std::vector<double>& y);

// Floor and rotated boxes under a spot light: every object is its own outer volume.
Scene boxes_scene(MediumModel model);

// The boxes scene (physical medium) seen from three places that test how a method starts its eye
// rays: inside the light looking across the beam, inside looking down at the objects, and above
// the light with the apex behind the camera. Named.
std::vector<std::pair<std::string, Scene>> eye_and_light_views();

// Eye rays at a small angle from the two directions where the light model's integral is worst
// conditioned (issue 33): `away` leaves an eye inside the cone at that angle from the direction
// straight away from the light (the antilight direction, light behind the eye); `toward` leaves an
// eye inside the cone at that angle from the direction to the light; `through` starts behind the
// light, outside its cone, and passes it at that angle on its way into the cone. Each with the
// interval it is integrated over: the whole ray, or a short piece of it (a lit gap between two
// shadows).
enum class NearLightKind { away, toward, through };
struct NearLightRay {
    analytic::EyeRay ray;
    double z0, z1;
    NearLightKind kind;
    double degrees;  // the angle from the singular direction
};
// The light the rays are made for: the antilight reproducer's (cone 26°, near 0.54).
SpotLight near_light_test_light();
// For every kind, every angle of 1e-4, 1e-3, 1e-2, 0.1, 1 and 10 degrees, two eyes and both
// intervals. The origins are exact in float; a GLSL twin reads the directions rounded to float
// (1e-7 off), which the integral, well conditioned, does not notice.
std::vector<NearLightRay> near_light_rays(const SpotLight& light);
const char* to_string(NearLightKind kind);
// The media they are integrated in: both models (the simplified one with and without its constant
// term a0, which alone keeps H away from 0), isotropic, and Henyey-Greenstein and Schlick at
// g = -0.9, -0.5, 0, 0.6, 0.82 and 0.9; the channels differ in density.
std::vector<Medium> near_light_media();

// The canonical scenes from the source tree.
Scene load_canonical(const std::string& name);

// The shaftlab executable run through the shell, stdout and stderr together.
struct CommandResult {
    int exit_code;
    std::string output;
};
// Runs a shell command line, stdout and stderr together.
CommandResult run_command(const std::string& command);
// Runs the binary with `environment` ("NAME=value " pairs) in front of it.
CommandResult run_shaftlab_with(const std::string& environment, const std::string& arguments);
CommandResult run_shaftlab(const std::string& arguments);

}  // namespace sl::test
