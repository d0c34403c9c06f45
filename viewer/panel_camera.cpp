#include "viewer/window.h"

#include <imgui.h>

#include "scenes/scene_file.h"

namespace sl::viewer {

void Viewer::ui_view() {
    int mode = mode_ == CameraMode::orbit ? 0 : 1;
    ImGui::RadioButton("orbit", &mode, 0);
    ImGui::SameLine();
    ImGui::RadioButton("fly", &mode, 1);
    mode_ = mode == 0 ? CameraMode::orbit : CameraMode::fly;
    help_marker(
        "orbit: left drag turns about the target, right drag pans, wheel zooms.\n"
        "fly: drag looks, WASD/QE move (shift: faster), wheel sets the speed.\n"
        "ctrl + left/right drag moves the light's position/target.");
    ImGui::SliderFloat("fov", &scene_.camera.fov_y_degrees, 10.0f, 120.0f, "%.1f deg");
    ImGui::SliderFloat("exposure", &scene_.camera.exposure, 0.05f, 20.0f, "%.2f",
                       ImGuiSliderFlags_Logarithmic);
    ImGui::Text("position %.2f %.2f %.2f", scene_.camera.position.x, scene_.camera.position.y,
                scene_.camera.position.z);
    ImGui::Text("target   %.2f %.2f %.2f", scene_.camera.target.x, scene_.camera.target.y,
                scene_.camera.target.z);
    if (mode_ == CameraMode::fly)
        ImGui::Text("fly speed %.2f m/s", fly_speed_);
    if (ImGui::Button("reset view")) {
        const Scene original = load_scene(options_.scene, SceneSearchPaths::defaults());
        scene_.camera = original.camera;
        controller_ = CameraController(scene_.camera);
    }
}

}  // namespace sl::viewer
