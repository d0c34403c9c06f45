// Scene files (scenes/scene_file.h): any text parses into a valid scene or throws sl::Error, and
// a valid scene's lights give a view each (Scene::for_light); an animated one gives, at its start,
// middle and end, a scene whose spot lights are finite, or throws sl::Error (an overshoot).
// Meshes, base scenes and environments resolve in the project's real folders, so inputs may
// reach the OFF/OBJ loaders and the multiple:N generator too.
#include <cstdlib>

#include "scenes/animation.h"
#include "scenes/scene_file.h"
#include "tests/fuzz/fuzz_support.h"

using sl::fuzz::finite;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const sl::SceneSearchPaths paths = sl::SceneSearchPaths::defaults();
    const std::string text(reinterpret_cast<const char*>(data), size);
    return sl::fuzz::expect_load_or_error([&] {
        const sl::Scene scene = sl::parse_scene(text, "fuzz.toml", paths.scenes, paths);
        // Its lights as the methods take them: the first and the last light's views (each
        // checks that `light` is the first of them).
        const size_t lights = scene.spot_lights().size();
        scene.for_light(0);
        scene.for_light(lights - 1);
        if (!scene.animation) {
            return;
        }
        const sl::Animation& a = *scene.animation;
        for (const double t : {a.start, 0.5 * (a.start + a.end), a.end}) {
            const sl::Scene s = sl::scene_at(scene, t);
            for (const sl::SpotLight& light : s.spot_lights()) {
                if (!finite(light.position) || !finite(light.target) || !finite(light.intensity)) {
                    std::abort();
                }
            }
        }
    });
}
