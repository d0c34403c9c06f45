// Scene files (scenes/scene_file.h): any text parses into a valid scene or throws sl::Error, and
// a valid scene's lights give a view each (Scene::for_light).
// Meshes, base scenes and environments resolve in the project's real folders, so inputs may
// reach the OFF/OBJ loaders and the multiple:N generator too.
#include "scenes/scene_file.h"
#include "tests/fuzz/fuzz_support.h"

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
    });
}
