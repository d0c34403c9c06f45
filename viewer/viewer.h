#pragma once
// `shaftlab view`: the interactive viewer (GLFW + Dear ImGui). A researcher opens a scene, moves
// the camera (orbit or fly) and the light, and sees at once the beam tree's lit, uncertain and
// unlit regions, what the chosen method makes of them, every buffer the passes declare, per-pass
// timings and, where a reference is cached for the view, the error as a heat map. Methods and
// their parameters come through the method interface and registry, so a new method appears here
// without changes. A scripted mode (--frames N) renders and exits, for tests and demos.

#include <string>
#include <vector>

#include "frame/volume_method.h"

namespace sl::viewer {

struct ViewerOptions {
    std::string scene;  // canonical name, multiple:N or a .toml file
    std::string method = "march";
    std::vector<std::string> settings;  // "name=value" for the method
    int width = 1280;
    int height = 720;
    frame::ShadowSettings shadow{};
    std::vector<std::string> layers;  // shown at start: volumes, outlines, light-view, error,
                                      // previewer, timings
    std::string preview;              // the previewer's texture at start (by name)
    // Whose regions the overlays show: an index into the scene's spot lights (a point light
    // counting as its six faces), as `shaftlab regions --light N`.
    int light = 0;
    float error_scale = 0.5f;  // the heat map's full scale, times the reference's RMS
    bool ui = true;            // panels drawn (F1 toggles)
    bool hidden = false;       // no visible window (still needs a display)

    // Scripted mode: draw `frames` frames (following `path` or orbiting `orbit_degrees` about the
    // target over them), then write the outputs below and exit.
    int frames = 0;
    std::string path;
    float orbit_degrees = 0.0f;
    std::string screenshot;       // PNG of the window, as shown
    std::string save_experiment;  // the view as an experiment (viewer/saved_view.h)
    std::string in_scattering;    // EXR of the last frame's I_s
};

// The layer names --layers accepts.
const std::vector<std::string>& layer_names();

// Runs the viewer; returns the exit status. Throws sl::Error on bad options or input.
int run_viewer(const ViewerOptions& options);

}  // namespace sl::viewer
