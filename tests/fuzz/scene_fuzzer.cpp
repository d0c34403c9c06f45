// Scene files (scenes/scene_file.h): any text parses into a valid scene or throws sl::Error.
// Meshes, base scenes and environments resolve in the project's real folders, so inputs may
// reach the OFF/OBJ loaders and the multiple:N generator too.
#include "scenes/scene_file.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const sl::SceneSearchPaths paths = sl::SceneSearchPaths::defaults();
    const std::string text(reinterpret_cast<const char*>(data), size);
    return sl::fuzz::expect_load_or_error(
        [&] { sl::parse_scene(text, "fuzz.toml", paths.scenes, paths); });
}
