// Where scene files, meshes and environments are looked up (scenes/scene_file.h).

#include <cstdlib>

#include "scenes/scene_file.h"

#ifndef SHAFTLAB_SCENES_DIR
#error "SHAFTLAB_SCENES_DIR must be defined by the build"
#endif
#ifndef SHAFTLAB_DATA_DIR
#error "SHAFTLAB_DATA_DIR must be defined by the build"
#endif
#ifndef SHAFTLAB_ENVIRONMENTS_DIR
#error "SHAFTLAB_ENVIRONMENTS_DIR must be defined by the build"
#endif

namespace sl {

namespace fs = std::filesystem;

SceneSearchPaths SceneSearchPaths::defaults() {
    SceneSearchPaths paths{SHAFTLAB_SCENES_DIR, SHAFTLAB_DATA_DIR, SHAFTLAB_ENVIRONMENTS_DIR};
    if (const char* scenes = std::getenv("SHAFTLAB_SCENES"); scenes && *scenes) {
        paths.scenes = scenes;
    }
    if (const char* data = std::getenv("SHAFTLAB_DATA"); data && *data) {
        paths.data = data;
    }
    if (const char* environments = std::getenv("SHAFTLAB_ENVIRONMENTS");
        environments && *environments) {
        paths.environments = environments;
    }
    return paths;
}

fs::path environment_file(const std::string& name, const fs::path& dir,
                          const SceneSearchPaths& paths) {
    if (fs::path(name).extension() == ".exr" || name.find('/') != std::string::npos) {
        return fs::path(name).is_relative() ? dir / name : fs::path(name);
    }
    return paths.environments / (name + ".exr");
}

}  // namespace sl
