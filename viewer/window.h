#pragma once
// The viewer's window (viewer/viewer.h runs it): the state every panel reads and edits, and where
// each part is defined. One concern per file:
//   viewer.cpp          start-up, the frame loop, scene changes (beam tree, method prepare),
//                       drawing the frame and the panel layout
//   input.cpp           mouse and keyboard: camera (orbit, fly) and light drags
//   panel_camera.cpp    the camera panel
//   panel_method.cpp    the method combo and its declared parameters
//   panel_scene.cpp     the light and medium panels
//   panel_environment.cpp  the image-based lighting panel (live uniforms, baked settings)
//   panel_regions.cpp   the region overlay's panel and the light view of the leaves
//   panel_buffers.cpp   the buffer previewer (every texture the passes declare)
//   panel_timings.cpp   GPU and CPU timings with their history graphs, method counters
//   error_view.cpp      the error heat map against a cached reference, computed in the background
//   saving.cpp          screenshots, the I_s EXR and "save as experiment"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/image.h"
#include "core/metrics.h"
#include "frame/renderer.h"
#include "frame/volume_method.h"
#include "gl/objects.h"
#include "gl/platform.h"
#include "reference/reference.h"
#include "scenes/animation.h"
#include "scenes/scene.h"
#include "viewer/camera_controller.h"
#include "viewer/region_overlay.h"
#include "viewer/texture_preview.h"
#include "viewer/viewer.h"

namespace sl::viewer {

using Clock = std::chrono::steady_clock;

constexpr size_t kHistory = 240;  // frames in the timing graphs
constexpr int kLightViewSize = 256;

// A ring of the last kHistory values, oldest first when read with offset().
struct History {
    std::vector<float> values = std::vector<float>(kHistory, 0.0f);
    size_t next = 0;
    void push(double v) {
        values[next] = float(v);
        next = (next + 1) % kHistory;
    }
    float latest() const { return values[(next + kHistory - 1) % kHistory]; }
    float max() const { return *std::max_element(values.begin(), values.end()); }
};

// The CPU reference for the current view, computed on a thread of its own and cached on disk.
struct ReferenceJob {
    std::thread thread;
    std::atomic<double> progress{0.0};
    std::atomic<bool> done{false};
    std::string error;
};

// A tooltip with `text` for the last item, when it is hovered.
void help_marker(const std::string& text);

class Viewer {
public:
    explicit Viewer(const ViewerOptions& options);
    ~Viewer();
    Viewer(const Viewer&) = delete;
    Viewer& operator=(const Viewer&) = delete;
    int run();

private:
    bool scripted() const { return options_.frames > 0; }
    // Scripted mode: frame frame_'s scene along the path and the orbit; when the scene changed,
    // the time of the change.
    std::optional<Clock::time_point> play_script_frame(float orbit_step);
    // Scripted mode, after the last frame: the files asked for and the run's summary.
    void finish_script();
    void switch_method(const std::string& name);
    // The light, an object or the medium changed: the overlay's regions and the method's
    // per-frame update (VolumeMethod::update), through the path every moving frame takes.
    void scene_changed();
    // The regions of the light the overlays show, built and uploaded for them.
    void build_overlay();
    void prepare_method();
    void handle_input(double dt);  // input.cpp: keys and mouse; true where the camera moved
    bool handle_keys(double dt);
    bool handle_mouse();
    // The world-space move of `point` dragged by `pixels` in the camera's view plane.
    glm::vec3 view_plane_drag(const glm::vec3& point, glm::vec2 pixels) const;
    void draw_frame();
    void update_error_view();  // error_view.cpp
    void draw_ui();
    // The panels (panel_*.cpp, error_view.cpp, saving.cpp).
    void ui_view();
    void ui_light();
    void ui_lights();  // a scene of [[lights]]
    void ui_objects();
    void ui_medium();
    void ui_environment();
    void ui_method();
    void ui_regions();
    void ui_error();
    void ui_save();
    void ui_timings();
    void ui_previewer();
    void ui_light_view();
    gl::TextureViews all_textures() const;     // panel_buffers.cpp
    void screenshot(const std::string& path);  // saving.cpp
    void write_in_scattering(const std::string& path);
    bool layer(const char* name) const;

    ViewerOptions options_;
    std::unique_ptr<gl::WindowPlatform> platform_;
    Scene scene_;
    CameraController controller_;
    CameraMode mode_ = CameraMode::orbit;
    std::optional<Animation> path_;  // scripted mode: --path, or the scene's own animation
    int selected_object_ = -1;       // alt + drag moves it (panel "objects")
    // [[lights]]: the spot light (or point-light face) whose regions the overlays show, and the
    // [[lights]] entry the light panel edits.
    size_t overlay_light_ = 0;
    size_t edited_light_ = 0;
    float fly_speed_ = 2.0f;  // metres per second
    std::unique_ptr<frame::VolumeMethod> method_;
    std::unique_ptr<frame::SceneRenderer> renderer_;
    int width_ = 0, height_ = 0;
    RegionOverlay overlay_;
    OverlaySettings overlay_settings_;
    std::map<std::string, bool> layers_;
    TexturePreview preview_;
    PreviewSettings preview_settings_;
    std::string preview_name_;
    std::string fitted_name_;  // the buffer whose range the previewer last fitted
    gl::Program blit_program_;
    gl::VertexArray empty_array_;

    // The last scene the beam tree and the method accepted (empty before the first).
    std::optional<Scene> applied_;
    std::string status_;               // the last error, shown in red
    Environment environment_pending_;  // baked settings being edited in the panel
    bool environment_editing_ = false;

    // Regions and timings.
    size_t beams_ = 0;
    bt::ExactOccluders exact_;  // [beamtree] occluders
    std::array<size_t, 3> region_faces_{};
    std::array<double, 3> region_volume_{};
    double influence_volume_ = 0.0;
    double tree_ms_ = 0.0, extract_ms_ = 0.0, prepare_ms_ = 0.0, update_ms_ = 0.0;
    // Scripted mode: per scene change, from the change to the end of the first frame showing it.
    std::vector<double> change_latency_ms_;
    frame::FrameTimings timings_;
    frame::MethodStatistics statistics_;
    History frame_history_, cpu_history_, shadow_history_, surface_history_, volume_history_,
        composite_history_;
    Clock::time_point last_frame_ = Clock::now();

    // Error view.
    reference::ReferenceOptions reference_options_{};
    uint64_t reference_key_ = 0;
    std::optional<Image> reference_;
    std::unique_ptr<ReferenceJob> job_;
    gl::Texture heat_map_;
    float heat_scale_ = 0.5f;
    ErrorMetrics error_{};

    std::string save_path_;
    std::string saved_message_;
    bool take_screenshot_ = false;
    int frame_ = 0;
};

}  // namespace sl::viewer
