#pragma once
// Shared test support without GL (the CPU tests link no GL; tests/gl_support.h holds the rest):
// temporary directories and files, a brute-force CPU ray caster used as an independent
// visibility oracle, the scenes and rays the tests share, image comparisons, and the shaftlab
// executable run as a user would.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "analytic/in_scattering.h"
#include "core/image.h"
#include "scenes/scene.h"

namespace sl::test {

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

// The boxes scene seen so that the light's screen position lies inside the image, beyond each
// side and corner, behind the camera, and (nearly) in the camera's plane. Named.
std::vector<std::pair<std::string, Scene>> light_placements();

// light_placements() under a sun instead of the spot: a directional light shining from where the
// spot is seen from the camera, so that the sun's point at infinity lies where the spot's position
// did (on screen, beyond each side and corner, in the camera's plane: a direction across the
// view, whose epipolar lines are parallel); "sun behind" shines from behind the camera's shoulder,
// its anti-solar point in view. Its region is the default one (the objects and the camera).
// Named "sun ..." after the placement.
std::vector<std::pair<std::string, Scene>> sun_placements();

// Eye rays at a small angle from the two directions where the light model's integral is worst
// conditioned (analytic/in_scattering.h): `away` leaves an eye inside the cone at that angle from
// the direction straight away from the light (the antilight direction, light behind the eye);
// `toward` leaves an eye inside the cone at that angle from the direction to the light; `through`
// starts behind the light, outside its cone, and passes it at that angle on its way into the cone.
// Each with the interval it is integrated over: the whole ray, or a short piece of it (a lit gap
// between two shadows).
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
