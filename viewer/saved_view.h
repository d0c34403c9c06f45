#pragma once
// "Save as experiment": the viewer's current scene view, method, parameters and size written as
// an experiment the harness runs (`shaftlab bench FILE`) — two files, written all or nothing:
//   FILE             the experiment: one cell (the scene file below × the method × the size),
//                    the method's parameters in [sweep.params.<method>], the run's shadow map;
//   FILE.scene.toml  (FILE's stem + ".scene.toml") the scene as seen: `[scene] base` = the scene
//                    the viewer opened, with the camera, light and medium as they are now.

#include <filesystem>
#include <string>

#include "frame/volume_method.h"
#include "scenes/scene.h"

namespace sl::viewer {

struct SavedView {
    std::filesystem::path experiment;
    std::filesystem::path scene;
};

// `opened` is the scene as named on the command line (a canonical name, multiple:N or a file).
SavedView save_view_as_experiment(const std::filesystem::path& experiment, const Scene& scene,
                                  const std::string& opened, const frame::VolumeMethod& method,
                                  int width, int height, const frame::ShadowSettings& shadow);

}  // namespace sl::viewer
