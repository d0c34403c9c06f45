#include "tests/support.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <array>

#include <cmath>
#include <fstream>
#include <limits>
#include <random>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "analytic/in_scattering.h"
#include "core/error.h"
#include "scenes/mesh.h"
#include "scenes/scene_file.h"
#include "scenes/scene_sections.h"

namespace sl::test {

namespace fs = std::filesystem;

TempDir::TempDir() {
    std::random_device random;
    path_ = fs::temp_directory_path() / ("shaftlab-test-" + std::to_string(random()));
    fs::create_directories(path_);
}

TempDir::~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
}

size_t TempDir::file_count() const {
    size_t count = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(path_)) {
        ++count;
    }
    return count;
}

void write_text(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

namespace {

bool segment_hits_box(glm::vec3 from, glm::vec3 to, const Bounds& box) {
    constexpr float kMargin = 1e-4f;
    const glm::vec3 d = to - from;
    float t0 = 0.0f, t1 = 1.0f;
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(d[axis]) < 1e-12f) {
            if (from[axis] < box.min[axis] - kMargin || from[axis] > box.max[axis] + kMargin) {
                return false;
            }
            continue;
        }
        float a = (box.min[axis] - kMargin - from[axis]) / d[axis];
        float b = (box.max[axis] + kMargin - from[axis]) / d[axis];
        if (a > b) {
            std::swap(a, b);
        }
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
        if (t0 > t1) {
            return false;
        }
    }
    return true;
}

}  // namespace

CpuRayCaster::CpuRayCaster(const Scene& scene) {
    for (const Object& object : scene.objects) {
        WorldObject world;
        world.vertices.reserve(object.mesh->positions.size());
        for (const glm::vec3& p : object.mesh->positions) {
            world.vertices.emplace_back(object.transform * glm::vec4(p, 1.0f));
            world.bounds.extend(glm::vec3(world.vertices.back()));
        }
        world.triangles = object.mesh->triangles;
        objects_.push_back(std::move(world));
    }
}

bool CpuRayCaster::blocked(glm::vec3 from, glm::vec3 to) const {
    const glm::dvec3 origin(from), direction = glm::dvec3(to) - glm::dvec3(from);
    constexpr double kEpsilon = 1e-6;  // relative to the segment: excludes its end points
    for (const WorldObject& object : objects_) {
        if (!segment_hits_box(from, to, object.bounds)) {
            continue;
        }
        for (const glm::uvec3& t : object.triangles) {
            const glm::dvec3 a = object.vertices[t.x];
            const glm::dvec3 e1 = object.vertices[t.y] - a, e2 = object.vertices[t.z] - a;
            const glm::dvec3 p = glm::cross(direction, e2);
            const double det = glm::dot(e1, p);
            if (std::abs(det) < 1e-18) {
                continue;
            }
            const glm::dvec3 s = origin - a;
            const double u = glm::dot(s, p) / det;
            if (u < 0.0 || u > 1.0) {
                continue;
            }
            const glm::dvec3 q = glm::cross(s, e1);
            const double v = glm::dot(direction, q) / det;
            if (v < 0.0 || u + v > 1.0) {
                continue;
            }
            const double t_hit = glm::dot(e2, q) / det;
            if (t_hit > kEpsilon && t_hit < 1.0 - kEpsilon) {
                return true;
            }
        }
    }
    return false;
}

Scene load_canonical(const std::string& name) {
    return load_scene(name, SceneSearchPaths::defaults());
}

// Floor and rotated boxes under a spot light: every object is its own outer volume.
Scene boxes_scene(MediumModel model) {
    Scene scene;
    scene.name = "boxes";
    scene.camera.position = glm::vec3(0.5f, 3.0f, 9.0f);
    scene.camera.target = glm::vec3(0.0f, 1.0f, 0.0f);
    scene.light.position = glm::vec3(0.8f, 6.0f, -0.5f);
    scene.light.target = glm::vec3(0.0f);
    scene.light.cone_half_angle_degrees = 32.0f;
    scene.light.near = 0.3f;
    scene.light.far = 8.0f;
    scene.light.intensity = glm::vec3(60.0f, 50.0f, 40.0f);
    scene.medium.sigma_s = glm::vec3(0.08f, 0.1f, 0.12f);
    scene.medium.sigma_a = glm::vec3(0.02f);
    scene.medium.model = model;
    scene.materials.push_back(Material{.name = "default"});
    auto add = [&](std::shared_ptr<const Mesh> mesh, glm::mat4 transform) {
        Object object;
        object.name = "object" + std::to_string(scene.objects.size());
        object.mesh = std::move(mesh);
        object.transform = transform;
        scene.objects.push_back(std::move(object));
    };
    add(std::make_shared<const Mesh>(make_plane({16.0f, 16.0f})), glm::mat4(1.0f));
    const auto box = std::make_shared<const Mesh>(make_box(glm::vec3(1.0f)));
    add(box, glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(-1.2f, 0.6f, 0.4f)), 0.5f,
                         glm::vec3(0, 1, 0)));
    add(box, glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 1.5f, -0.8f)),
                        glm::vec3(0.6f, 3.0f, 0.6f)));
    add(box, glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, 2.5f, 1.2f)), 0.8f,
                         glm::vec3(1, 0, 1)));
    return scene;
}

std::vector<std::pair<std::string, Scene>> eye_and_light_views() {
    struct View {
        const char* name;
        glm::vec3 position, target;
    };
    std::vector<std::pair<std::string, Scene>> scenes;
    for (const View& view : {View{"inside, across", {0.3f, 2.8f, 0.2f}, {4.0f, 1.0f, -3.0f}},
                             View{"inside, down", {0.3f, 2.8f, 0.2f}, {0.0f, 0.0f, 0.0f}},
                             View{"light behind", {0.9f, 6.5f, -0.6f}, {-0.2f, 0.0f, 0.1f}}}) {
        Scene scene = boxes_scene(MediumModel::physical);
        scene.camera.position = view.position;
        scene.camera.target = view.target;
        scene.camera.near = 0.05f;
        scenes.emplace_back(view.name, std::move(scene));
    }
    return scenes;
}

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

std::vector<std::pair<std::string, Scene>> sun_placements() {
    std::vector<std::pair<std::string, Scene>> scenes;
    for (auto [name, scene] : light_placements()) {
        // Towards the sun: the spot as the camera sees it; behind the camera (where the spot lies
        // below it), the way back past the camera's shoulder, so that the sun stays above the
        // floor.
        glm::vec3 toward = scene.light.position - scene.camera.position;
        if (name == "light behind") {
            toward = scene.camera.position - scene.camera.target + glm::vec3(0.6f, 0.0f, 0.4f);
        }
        DirectionalLight sun;
        sun.direction = -glm::normalize(toward);
        sun.irradiance = glm::vec3(1.5f, 1.4f, 1.2f);
        sun.entry = glm::vec3(std::numeric_limits<float>::quiet_NaN());
        resolve_directional_light(sun, scene, "sun_placements");
        scene.set_lights({sun});
        scenes.emplace_back("sun" + name.substr(name.find(' ')), std::move(scene));
    }
    return scenes;
}

SpotLight near_light_test_light() {
    SpotLight light;
    light.position = glm::vec3(-2.15f, 6.17f, 1.22f);
    light.target = glm::vec3(0.22f, 0.0f, 0.29f);
    light.cone_half_angle_degrees = 26.0f;
    light.near = 0.54f;
    light.far = 7.7f;
    light.intensity = glm::vec3(178.0f, 120.0f, 60.0f);
    return light;
}

const char* to_string(NearLightKind kind) {
    switch (kind) {
        case NearLightKind::away:
            return "away from the light";
        case NearLightKind::toward:
            return "toward the light";
        case NearLightKind::through:
            return "through the light";
    }
    return "?";
}

std::vector<NearLightRay> near_light_rays(const SpotLight& light) {
    using glm::dvec3;
    const dvec3 L(light.position), axis = glm::normalize(dvec3(light.direction()));
    const dvec3 side = glm::normalize(glm::cross(axis, dvec3(0.3, 0.1, 1.0)));
    const dvec3 other = glm::cross(axis, side);
    auto tilt = [](dvec3 d, dvec3 p, double degrees) {
        const double a = glm::radians(degrees);
        return glm::normalize(std::cos(a) * d + std::sin(a) * p);
    };
    // Origins exact in float: the GLSL twin reads the rays as floats.
    auto exact = [](dvec3 v) { return dvec3(glm::vec3(v)); };
    std::vector<NearLightRay> rays;
    for (const NearLightKind kind :
         {NearLightKind::away, NearLightKind::toward, NearLightKind::through}) {
        for (const double degrees : {1e-4, 1e-3, 1e-2, 0.1, 1.0, 10.0}) {
            for (int eye = 0; eye < 2; ++eye) {
                const dvec3 offset = eye == 0 ? side : other;
                dvec3 origin, singular;
                if (kind == NearLightKind::through) {
                    origin = L - (1.5 + eye) * axis + 0.05 * offset;
                    singular = glm::normalize(L - origin);
                } else {
                    origin = L + (1.5 + 1.5 * eye) * tilt(axis, offset, 8.0 + 6.0 * eye);
                    singular =
                        glm::normalize(kind == NearLightKind::away ? origin - L : L - origin);
                }
                const dvec3 perpendicular =
                    glm::normalize(glm::cross(singular, offset + 0.3 * axis));
                const analytic::EyeRay ray{exact(origin), tilt(singular, perpendicular, degrees)};
                rays.push_back({ray, 0.0, 40.0, kind, degrees});
                // A short lit piece: the ray's middle stretch inside the cone.
                const analytic::Interval lit = analytic::light_interval(ray, light, 40.0);
                if (!lit.empty()) {
                    const double middle = 0.5 * (lit.begin + lit.end);
                    const double half = 0.05 * (lit.end - lit.begin);
                    rays.push_back({ray, middle - half, middle + half, kind, degrees});
                }
            }
        }
    }
    return rays;
}

std::vector<Medium> near_light_media() {
    std::vector<Medium> media;
    for (const MediumModel model : {MediumModel::simplified, MediumModel::physical}) {
        for (const float a0 : {1.0f, 0.0f}) {
            if (model == MediumModel::physical && a0 == 0.0f)
                continue;
            Medium medium;
            medium.model = model;
            medium.sigma_s = glm::vec3(0.17f, 0.05f, 0.6f);
            medium.sigma_a = glm::vec3(0.01f, 0.0f, 0.2f);
            medium.a0 = a0;
            medium.a1 = 1.0f;
            media.push_back(medium);
            for (const PhaseFunction phase :
                 {PhaseFunction::henyey_greenstein, PhaseFunction::schlick}) {
                for (const float g : {-0.9f, -0.5f, 0.0f, 0.6f, 0.82f, 0.9f}) {
                    medium.phase = phase;
                    medium.g = g;
                    media.push_back(medium);
                }
            }
        }
    }
    return media;
}

double max_abs_difference(const Image& a, const Image& b) {
    double worst = 0.0;
    for (size_t i = 0; i < a.rgb.size(); ++i) {
        worst = std::max(worst, std::abs(double(a.rgb[i]) - double(b.rgb[i])));
    }
    return worst;
}

double image_peak(const Image& image) {
    double p = 0.0;
    for (const float v : image.rgb) {
        p = std::max(p, double(v));
    }
    return p;
}

double log_log_slope(const std::vector<double>& x, const std::vector<double>& y) {
    const double n = double(x.size());
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t i = 0; i < x.size(); ++i) {
        const double lx = std::log(x[i]), ly = std::log(y[i]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

Image unoccluded_in_scattering(const Scene& scene, int width, int height) {
    const PixelUnprojector unproject(scene.camera, width, height);
    const glm::dvec3 origin(scene.camera.position);
    Image image(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const analytic::EyeRay ray{origin, glm::normalize(unproject.point(x, y, 1.0) - origin)};
            image.set(
                x, y,
                glm::vec3(analytic::in_scattering(ray, 0.0, 1e30, scene.light, scene.medium)));
        }
    }
    return image;
}

void write_unchecked_exr(const Image& image, const std::filesystem::path& path) {
    Imf::Header header(image.width, image.height);
    Imf::FrameBuffer frame;
    const char* names[] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
        header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
        char* base = reinterpret_cast<char*>(const_cast<float*>(image.rgb.data() + c));
        frame.insert(names[c], Imf::Slice(Imf::FLOAT, base, sizeof(float) * 3,
                                          sizeof(float) * 3 * size_t(image.width)));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(image.height);
}

CommandResult run_shaftlab_with(const std::string& environment, const std::string& arguments) {
    return run_command(environment + std::string(SHAFTLAB_BINARY) + " " + arguments);
}

CommandResult run_command(const std::string& line) {
    const std::string command = "{ " + line + "; } 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) {
        return {-1, "popen failed"};
    }
    std::string output;
    std::array<char, 4096> buffer{};
    while (size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) {
        output.append(buffer.data(), n);
    }
    const int status = pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

CommandResult run_shaftlab(const std::string& arguments) {
    return run_shaftlab_with("", arguments);
}

}  // namespace sl::test
