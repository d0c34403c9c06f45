#include "scenes/animation.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "core/text.h"
#include "scenes/animation_toml.h"
#include "scenes/toml_reader.h"

namespace sl {

template <typename T>
T Track<T>::at(double time, Interpolation interpolation) const {
    const size_t n = times.size();
    if (time <= times.front()) {
        return values.front();
    }
    if (time >= times.back()) {
        return values.back();
    }
    const size_t i = size_t(std::upper_bound(times.begin(), times.end(), time) - times.begin());
    const double t0 = times[i - 1], t1 = times[i];
    const double h = t1 - t0;
    const double s = (time - t0) / h;
    const T& p0 = values[i - 1];
    const T& p1 = values[i];
    if (interpolation == Interpolation::linear || n == 2) {
        return p0 + float(s) * (p1 - p0);
    }
    // Non-uniform cardinal (Catmull-Rom) tangents, one-sided at the ends, in units of value per
    // second; the cubic Hermite basis on [t0, t1].
    auto tangent = [&](size_t k) -> T {
        const size_t a = k == 0 ? 0 : k - 1;
        const size_t b = std::min(k + 1, n - 1);
        return (values[b] - values[a]) / float(times[b] - times[a]);
    };
    const T m0 = tangent(i - 1) * float(h);
    const T m1 = tangent(i) * float(h);
    const double s2 = s * s, s3 = s2 * s;
    return float(2 * s3 - 3 * s2 + 1) * p0 + float(s3 - 2 * s2 + s) * m0 +
           float(-2 * s3 + 3 * s2) * p1 + float(s3 - s2) * m1;
}

template struct Track<glm::vec3>;
template struct Track<float>;

int Animation::frame_count() const {
    // A tiny slack so that (end - start)·fps computed in double still counts its last frame;
    // saturated, so that no range converts out of int (read_animation allows 10^6 frames).
    const double steps = std::floor((end - start) * fps * (1.0 + 1e-12) + 1e-9);
    return steps < double(kMaxFrames) ? int(steps) + 1 : kMaxFrames;
}

bool Animation::moves_light() const {
    return !light_position.empty() || !light_target.empty() || !cone_angle.empty() ||
           !light_intensity.empty() || !lights.empty();
}

namespace {

// Keys of one track group ([[animation.light]], ...): each key's time strictly after the
// previous one's and at least `start`.
class KeyReader {
public:
    explicit KeyReader(double start) : start_(start) {}

    double time(TomlTableReader& r, double& previous, bool first) const {
        if (!r.has("time")) {
            r.error("time", "missing: every key needs its time");
        }
        const double t = r.number("time");
        if (t < start_) {
            r.error("time", fmt::format("{} is before the animation's start {}", t, start_));
        }
        if (!first && t <= previous) {
            r.error("time", fmt::format("{} is not after the previous key's {}", t, previous));
        }
        previous = t;
        return t;
    }

private:
    double start_;
};

template <typename T>
void add_key(Track<T>& track, double time, T value) {
    track.times.push_back(time);
    track.values.push_back(value);
}

// A key table of `[[animation.NAME]]` at index i, or a clear error.
const toml::table& key_table(const toml::array& keys, size_t i, const std::string& origin,
                             const char* name) {
    const toml::table* table = keys[i].as_table();
    if (!table) {
        fail("{}:{}: [animation] {}: expected an array of tables ([[animation.{}]])", origin,
             keys[i].source().begin.line, name, name);
    }
    return *table;
}

void read_light_key(TomlTableReader& k, double t, Animation& a) {
    if (k.has("position"))
        add_key(a.light_position, t, k.vec3("position"));
    if (k.has("target"))
        add_key(a.light_target, t, k.vec3("target"));
    if (k.has("cone_angle"))
        add_key(a.cone_angle, t, float(k.number_in("cone_angle", 0, 0, 89, true)));
    if (k.has("intensity"))
        add_key(a.light_intensity, t, k.non_negative_vec3("intensity", glm::vec3(0)));
}

void read_camera_key(TomlTableReader& k, double t, Animation& a) {
    if (k.has("position"))
        add_key(a.camera_position, t, k.vec3("position"));
    if (k.has("target"))
        add_key(a.camera_target, t, k.vec3("target"));
    if (k.has("fov"))
        add_key(a.fov, t, float(k.number_in("fov", 0, 0, 180, true, true)));
}

// The keys of [[animation.light]] in a scene of [[lights]]: each names its entry (`light = N`,
// from 1) and sets that light type's keys; each entry's key times rise on their own.
class LightKeys {
public:
    LightKeys(const Scene& scene, const KeyReader& keys)
        : scene_(scene),
          keys_(keys),
          previous_(scene.lights.size(), 0.0),
          tracks_of_(scene.lights.size(), -1) {}

    double read(TomlTableReader& k, Animation& a) {
        const int count = int(scene_.lights.size());
        if (!k.has("light")) {
            k.error("light",
                    fmt::format("missing: which [[lights]] entry the key moves, 1 to {}", count));
        }
        const size_t light = size_t(k.integer_in("light", 1, 1, count) - 1);
        int& index = tracks_of_[light];
        const double t = keys_.time(k, previous_[light], index < 0);
        if (index < 0) {
            index = int(a.lights.size());
            Animation::LightTracks tracks;
            tracks.light = int(light);
            a.lights.push_back(std::move(tracks));
        }
        Animation::LightTracks& tracks = a.lights[size_t(index)];
        const LightSource& source = scene_.lights[light];
        auto refuse = [&](std::initializer_list<const char*> keys, const char* takes) {
            for (const char* key : keys) {
                if (k.has(key)) {
                    k.error(key, fmt::format("light {} is a {} light, which takes {}", light + 1,
                                             light_type(source), takes));
                }
            }
        };
        if (std::holds_alternative<DirectionalLight>(source)) {
            refuse({"position", "target", "cone_angle", "intensity"}, "direction and irradiance");
            if (k.has("direction")) {
                const glm::vec3 d = k.vec3("direction");
                if (d == glm::vec3(0.0f)) {
                    k.error("direction", "must not be [0, 0, 0]");
                }
                add_key(tracks.direction, t, d);
            }
            if (k.has("irradiance"))
                add_key(tracks.intensity, t, k.non_negative_vec3("irradiance", glm::vec3(0)));
            return t;
        }
        refuse({"direction", "irradiance"}, std::holds_alternative<SpotLight>(source)
                                                ? "position, target, cone_angle and intensity"
                                                : "position and intensity");
        if (std::holds_alternative<PointLight>(source)) {
            refuse({"target", "cone_angle"}, "position and intensity");
        }
        if (k.has("position"))
            add_key(tracks.position, t, k.vec3("position"));
        if (k.has("target"))
            add_key(tracks.target, t, k.vec3("target"));
        if (k.has("cone_angle"))
            add_key(tracks.cone_angle, t, float(k.number_in("cone_angle", 0, 0, 89, true)));
        if (k.has("intensity"))
            add_key(tracks.intensity, t, k.non_negative_vec3("intensity", glm::vec3(0)));
        return t;
    }

private:
    const Scene& scene_;
    const KeyReader& keys_;
    std::vector<double> previous_;
    std::vector<int> tracks_of_;
};

// The keys of [[animation.objects]]: each names an object of the scene, whose tracks are made at
// its first key; each object's key times rise on their own.
class ObjectKeys {
public:
    ObjectKeys(const Scene& scene, const KeyReader& keys)
        : scene_(scene),
          keys_(keys),
          previous_(scene.objects.size(), 0.0),
          tracks_of_(scene.objects.size(), -1) {}

    double read(TomlTableReader& k, Animation& a) {
        const std::string name = k.string("name");
        const auto it = std::find_if(scene_.objects.begin(), scene_.objects.end(),
                                     [&](const Object& o) { return o.name == name; });
        if (it == scene_.objects.end()) {
            k.error("name", fmt::format("the scene has no object {}", quote(name)));
        }
        const size_t object = size_t(it - scene_.objects.begin());
        int& index = tracks_of_[object];
        const double t = keys_.time(k, previous_[object], index < 0);
        if (index < 0) {
            index = int(a.objects.size());
            a.objects.push_back(
                {.object = int(object), .translate = {}, .rotate = {}, .scale = {}});
        }
        Animation::ObjectTracks& tracks = a.objects[size_t(index)];
        const Placement placement = read_placement(k, it->placement);
        if (k.has("translate"))
            add_key(tracks.translate, t, placement.translate);
        if (k.has("rotate"))
            add_key(tracks.rotate, t, placement.rotate_degrees);
        if (k.has("scale"))
            add_key(tracks.scale, t, placement.scale);
        return t;
    }

private:
    const Scene& scene_;
    const KeyReader& keys_;
    std::vector<double> previous_;
    std::vector<int> tracks_of_;
};

}  // namespace

Animation read_animation(const toml::table& table, const std::string& origin, const Scene& scene) {
    TomlTableReader r(table, origin, "[animation]");
    Animation a;
    a.start = r.number("start", 0.0);
    a.fps = r.number_in("fps", 30.0, 0.0, 1e4, true);
    const std::string interpolation = r.string("interpolation", "linear");
    if (interpolation == "catmull-rom") {
        a.interpolation = Interpolation::catmull_rom;
    } else if (interpolation != "linear") {
        r.error("interpolation", fmt::format("unknown value {} (expected one of: linear, "
                                             "catmull-rom)",
                                             quote(interpolation)));
    }
    const KeyReader keys(a.start);
    double last = a.start;
    bool any = false;

    // Reads every key table of [[animation.NAME]] with read(key, index), which returns its time.
    auto each_key = [&](const char* name, const auto& read) {
        const toml::array* list = r.array(name);
        for (size_t i = 0; list && i < list->size(); ++i) {
            TomlTableReader k(key_table(*list, i, origin, name), origin,
                              fmt::format("[[animation.{}]] #{}", name, i + 1));
            last = std::max(last, read(k, i));
            k.finish();
            any = true;
        }
    };
    double light_previous = 0.0, camera_previous = 0.0;
    LightKeys light_keys(scene, keys);
    each_key("light", [&](TomlTableReader& k, size_t i) {
        if (!scene.lights.empty()) {
            return light_keys.read(k, a);
        }
        if (k.has("light")) {
            k.error("light", "the scene has one light ([light]): its keys need no `light`");
        }
        const double t = keys.time(k, light_previous, i == 0);
        read_light_key(k, t, a);
        return t;
    });
    each_key("camera", [&](TomlTableReader& k, size_t i) {
        const double t = keys.time(k, camera_previous, i == 0);
        read_camera_key(k, t, a);
        return t;
    });
    ObjectKeys objects(scene, keys);
    each_key("objects", [&](TomlTableReader& k, size_t) { return objects.read(k, a); });
    if (!any) {
        fail(
            "{}: [animation] needs at least one key ([[animation.light]], [[animation.camera]] "
            "or [[animation.objects]])",
            origin);
    }
    a.end = r.number("end", last);
    if (a.end <= a.start) {
        r.error("end", fmt::format("{} is not after the start {}", a.end, a.start));
    }
    if (last > a.end) {
        r.error("end", fmt::format("{} is before the last key's time {}", a.end, last));
    }
    if ((a.end - a.start) * a.fps >= double(Animation::kMaxFrames)) {
        r.error("fps", fmt::format("{} fps from {} s to {} s is more than {} frames", a.fps,
                                   a.start, a.end, Animation::kMaxFrames));
    }
    r.finish();
    return a;
}

Animation parse_animation(const std::string& text, const std::string& origin, const Scene& scene) {
    toml::table root;
    try {
        root = toml::parse(text, origin);
    } catch (const toml::parse_error& e) {
        fail("{}:{}: malformed TOML: {}", origin, e.source().begin.line, e.description());
    }
    const toml::table* animation = root["animation"].as_table();
    if (!animation) {
        fail("{}: no [animation] table (a path file holds the scene file's [animation] keys)",
             origin);
    }
    return read_animation(*animation, origin, scene);
}

Animation load_animation_file(const std::filesystem::path& path, const Scene& scene) {
    return parse_animation(read_text_file(path, "the animation file"), path.string(), scene);
}

Scene scene_at(const Scene& scene, const Animation& a, double time) {
    if (!std::isfinite(time) || time < a.start || time > a.end) {
        fail("{}: time {} is outside the animation's range [{}, {}]", scene.name, time, a.start,
             a.end);
    }
    Scene s = scene;
    const Interpolation in = a.interpolation;
    if (!a.light_position.empty())
        s.light.position = a.light_position.at(time, in);
    if (!a.light_target.empty())
        s.light.target = a.light_target.at(time, in);
    if (!a.cone_angle.empty())
        s.light.cone_half_angle_degrees = a.cone_angle.at(time, in);
    if (!a.light_intensity.empty())
        // Catmull-Rom may overshoot below zero near a dark key: no light is the floor.
        s.light.intensity = glm::max(a.light_intensity.at(time, in), glm::vec3(0.0f));
    if (!a.camera_position.empty())
        s.camera.position = a.camera_position.at(time, in);
    if (!a.camera_target.empty())
        s.camera.target = a.camera_target.at(time, in);
    if (!a.fov.empty())
        s.camera.fov_y_degrees = a.fov.at(time, in);
    const char* bad = nullptr;
    if (!a.lights.empty()) {
        std::vector<LightSource> lights = s.lights;
        for (const Animation::LightTracks& tracks : a.lights) {
            LightSource& source = lights[size_t(tracks.light)];
            const glm::vec3 intensity =
                tracks.intensity.empty() ? glm::vec3(0.0f)
                                         : glm::max(tracks.intensity.at(time, in), glm::vec3(0.0f));
            if (auto* sun = std::get_if<DirectionalLight>(&source)) {
                if (!tracks.direction.empty()) {
                    const glm::vec3 d = tracks.direction.at(time, in);
                    if (!(glm::length(d) > 1e-6f)) {
                        bad = "a directional light's direction passed through zero";
                        continue;
                    }
                    sun->direction = glm::normalize(d);
                    if (sun->default_entry) {
                        sun->enter_region();
                    }
                }
                if (!tracks.intensity.empty())
                    sun->irradiance = intensity;
                continue;
            }
            std::visit(
                [&](auto& light) {
                    using Light = std::decay_t<decltype(light)>;
                    if constexpr (!std::is_same_v<Light, DirectionalLight>) {
                        if (!tracks.position.empty())
                            light.position = tracks.position.at(time, in);
                        if (!tracks.intensity.empty())
                            light.intensity = intensity;
                    }
                    if constexpr (std::is_same_v<Light, SpotLight>) {
                        if (!tracks.target.empty())
                            light.target = tracks.target.at(time, in);
                        if (!tracks.cone_angle.empty())
                            light.cone_half_angle_degrees = tracks.cone_angle.at(time, in);
                    }
                },
                source);
        }
        for (const LightSource& source : lights) {
            const auto* spot = std::get_if<SpotLight>(&source);
            if (spot && !distinct_in_float(spot->position, spot->target)) {
                bad = "a spot light's target is on its position";
            } else if (spot && !(spot->cone_half_angle_degrees > 0.0f &&
                                 spot->cone_half_angle_degrees < 89.0f)) {
                bad = "a spot light's cone angle left (0, 89) degrees";
            } else if (spot && spot->falloff_degrees > spot->cone_half_angle_degrees) {
                bad = "a spot light's cone angle fell below its falloff";
            }
        }
        if (!bad) {
            s.set_lights(std::move(lights));
        }
    }
    for (const Animation::ObjectTracks& tracks : a.objects) {
        Object& object = s.objects[size_t(tracks.object)];
        if (!tracks.translate.empty())
            object.placement.translate = tracks.translate.at(time, in);
        if (!tracks.rotate.empty())
            object.placement.rotate_degrees = tracks.rotate.at(time, in);
        if (!tracks.scale.empty())
            object.placement.scale = tracks.scale.at(time, in);
        const glm::vec3 scale = object.placement.scale;
        if (scale.x == 0 || scale.y == 0 || scale.z == 0) {
            fail("{} at time {}: object {} has a zero scale", scene.name, time, quote(object.name));
        }
        object.transform = object.placed();
    }
    auto finite = [](const glm::vec3& v) {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    };
    bool all_finite = finite(s.camera.position) && finite(s.camera.target) &&
                      std::isfinite(s.camera.fov_y_degrees) && finite(s.light.position) &&
                      finite(s.light.target) && finite(s.light.intensity) &&
                      std::isfinite(s.light.cone_half_angle_degrees);
    for (const Object& o : s.objects) {
        all_finite = all_finite && finite(o.placement.translate) &&
                     finite(o.placement.rotate_degrees) && finite(o.placement.scale);
    }
    for (const SpotLight& light : s.spot_lights()) {
        all_finite = all_finite && finite(light.position) && finite(light.target) &&
                     finite(light.intensity) && std::isfinite(light.cone_half_angle_degrees);
    }
    if (bad) {
        // a light's, found above
    } else if (!all_finite) {
        bad = "an interpolated value is not finite (keys too far apart for float)";
    } else if (!distinct_in_float(s.camera.position, s.camera.target)) {
        bad = "the camera's target is on its position";
    } else if (glm::length(glm::cross(s.camera.target - s.camera.position, s.camera.up)) <=
               1e-6f * glm::length(s.camera.up)) {
        bad = "the camera looks along its up vector";
    } else if (!distinct_in_float(s.light.position, s.light.target)) {
        bad = "the light's target is on its position";
    } else if (!s.light.parallel() && !(s.light.cone_half_angle_degrees > 0.0f &&
                                        s.light.cone_half_angle_degrees < 89.0f)) {
        bad = "the cone angle left (0, 89) degrees";
    } else if (s.light.falloff_degrees > s.light.cone_half_angle_degrees) {
        bad = "the cone angle fell below the light's falloff";
    } else if (!(s.camera.fov_y_degrees > 0.0f && s.camera.fov_y_degrees < 180.0f)) {
        bad = "the field of view left (0, 180) degrees";
    }
    if (bad) {
        fail("{} at time {}: {}", scene.name, time, bad);
    }
    return s;
}

Scene scene_at(const Scene& scene, double time) {
    if (!scene.animation) {
        fail("{}: the scene has no [animation]", scene.name);
    }
    return scene_at(scene, *scene.animation, time);
}

SceneChange SceneChange::everything(const Scene& scene) {
    SceneChange change{
        .camera = true, .light = true, .light_geometry = true, .medium = true, .objects = {}};
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        change.objects.push_back(int(i));
    }
    return change;
}

SceneChange scene_change(const Scene& before, const Scene& after) {
    const SpotLight& l0 = before.light;
    const SpotLight& l1 = after.light;
    SceneChange change;
    change.camera = before.camera != after.camera;
    change.light_geometry = l0.position != l1.position || l0.target != l1.target ||
                            l0.cone_half_angle_degrees != l1.cone_half_angle_degrees ||
                            l0.near != l1.near || l0.far != l1.far || l0.shape != l1.shape ||
                            before.lights != after.lights;
    change.light = l0 != l1 || before.lights != after.lights;
    change.medium = before.medium != after.medium;
    const size_t n = std::min(before.objects.size(), after.objects.size());
    for (size_t i = 0; i < n; ++i) {
        if (before.objects[i].transform != after.objects[i].transform ||
            before.objects[i].mesh != after.objects[i].mesh) {
            change.objects.push_back(int(i));
        }
    }
    for (size_t i = n; i < std::max(before.objects.size(), after.objects.size()); ++i) {
        change.objects.push_back(int(i));
    }
    return change;
}

}  // namespace sl
