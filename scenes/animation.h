#pragma once
// Keyframed animation of a scene (docs/design.md §10): tracks for the light, the camera and each
// object's placement, read from the `[animation]` table of a scene file (or of a path file given
// to `shaftlab view --path`). The format:
//
//   [animation]
//   start = 0.0              seconds (default 0)
//   end = 4.0                seconds, > start (default: the last key's time)
//   fps = 30                 the step the harness and the viewer play it at (default 30)
//   interpolation = "linear" | "catmull-rom"   (default "linear")
//
//   [[animation.light]]      time, and any of: position, target, cone_angle, intensity; in a
//                            scene of [[lights]], also `light = N` (the N-th entry, from 1)
//                            and that light type's keys: a spot's as above, a point light's
//                            position and intensity, a directional light's direction and
//                            irradiance (its entry plane, when the scene gave none, follows
//                            the direction: the plane touching its region)
//   [[animation.camera]]     time, and any of: position, target, fov
//   [[animation.objects]]    name (an object of the scene), time, and any of: translate,
//                            rotate, scale (as in [[objects]]; they replace the object's own)
//
// Every quantity is its own track: interpolated between the keys that set it, held before the
// first and after the last; a quantity no key sets keeps the scene's value. Per track (the
// light, each [[lights]] entry, the camera, each object) the keys' times increase strictly and
// lie in [start, end].
// Catmull-Rom is the non-uniform cardinal spline with tangents (p[i+1] - p[i-1]) / (t[i+1] -
// t[i-1]) (one-sided at the ends); it passes through every key. Rotations interpolate their
// angles component by component.

#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "scenes/scene.h"

namespace sl {

enum class Interpolation { linear, catmull_rom };

template <typename T>
struct Track {
    std::vector<double> times;  // strictly increasing
    std::vector<T> values;
    bool empty() const { return times.empty(); }
    T at(double time, Interpolation interpolation) const;  // requires !empty()
};

class Animation {
public:
    struct ObjectTracks {
        int object = 0;  // index into Scene::objects
        Track<glm::vec3> translate, rotate, scale;
    };
    // One [[lights]] entry's tracks (keys with `light = N`): intensity is a directional light's
    // irradiance.
    struct LightTracks {
        int light = 0;  // index into Scene::lights
        Track<glm::vec3> position, target, intensity, direction;
        Track<float> cone_angle;
    };

    double start = 0.0;
    double end = 0.0;
    double fps = 30.0;
    Interpolation interpolation = Interpolation::linear;
    Track<glm::vec3> light_position, light_target, light_intensity;
    Track<float> cone_angle;
    Track<glm::vec3> camera_position, camera_target;
    Track<float> fov;
    std::vector<ObjectTracks> objects;
    std::vector<LightTracks> lights;  // for a scene of [[lights]]; the light_* tracks for [light]

    // Frames played at `fps` from start to end, both included when (end - start)·fps is whole;
    // a file may ask for at most kMaxFrames.
    static constexpr int kMaxFrames = 1000000;
    int frame_count() const;
    double frame_time(int frame) const { return start + double(frame) / fps; }
    bool moves_light() const;
    bool moves_objects() const { return !objects.empty(); }
};

// A TOML file whose only table is `[animation]` (a path for `shaftlab view --path`), or a scene
// file: its `[animation]` table alone is read.
Animation load_animation_file(const std::filesystem::path& path, const Scene& scene);
Animation parse_animation(const std::string& text, const std::string& origin, const Scene& scene);

// The scene at `time`: `scene` with its animation's tracks applied. Throws sl::Error when time is
// outside [start, end], or when an interpolated value is invalid (a target on its position, a
// cone angle outside (0, 89), a zero scale: Catmull-Rom may overshoot).
Scene scene_at(const Scene& scene, double time);
// The same with an explicit animation (the viewer's --path).
Scene scene_at(const Scene& scene, const Animation& animation, double time);

// What changed between two states of one scene (same objects and meshes), for the methods'
// per-frame update (frame/volume_method.h).
struct SceneChange {
    bool camera = false;
    bool light = false;           // anything of the light
    bool light_geometry = false;  // its position, direction, cone or range (not its colour)
    bool medium = false;          // coefficients, phase function, model
    std::vector<int> objects;     // indices of the objects whose transform or mesh changed

    // Anything the beam tree and its regions depend on.
    bool regions() const { return light_geometry || !objects.empty(); }
    bool any() const { return camera || light || medium || !objects.empty(); }
    // Everything, as when a scene is first prepared.
    static SceneChange everything(const Scene& scene);
};
SceneChange scene_change(const Scene& before, const Scene& after);

}  // namespace sl
