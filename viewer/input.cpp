#include "viewer/window.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cmath>

#include <glm/trigonometric.hpp>

namespace sl::viewer {

void Viewer::handle_input(double dt) {
    const ImGuiIO& io = ImGui::GetIO();
    // The camera is written only when it moves: an untouched view keeps the scene's exact
    // camera (and with it the cache key of its reference).
    bool moved = false;
    auto* window = static_cast<GLFWwindow*>(platform_->native_window());
    if (!io.WantCaptureKeyboard) {
        if (ImGui::IsKeyPressed(GLFW_KEY_TAB, false)) {
            mode_ = mode_ == CameraMode::orbit ? CameraMode::fly : CameraMode::orbit;
        }
        if (ImGui::IsKeyPressed(GLFW_KEY_F1, false))
            options_.ui = !options_.ui;
        if (ImGui::IsKeyPressed(GLFW_KEY_F12, false))
            take_screenshot_ = true;
        if (ImGui::IsKeyPressed(GLFW_KEY_V, false))
            overlay_settings_.volumes = !overlay_settings_.volumes;
        if (ImGui::IsKeyPressed(GLFW_KEY_O, false))
            overlay_settings_.outlines = !overlay_settings_.outlines;
        auto down = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS ? 1.0f : 0.0f; };
        const glm::vec3 move(down(GLFW_KEY_D) - down(GLFW_KEY_A),
                             down(GLFW_KEY_E) - down(GLFW_KEY_Q),
                             down(GLFW_KEY_W) - down(GLFW_KEY_S));
        if (move != glm::vec3(0.0f)) {
            const float boost = io.KeyShift ? 4.0f : 1.0f;
            controller_.move(move * float(fly_speed_ * boost * dt));
            moved = true;
        }
    }
    if (!io.WantCaptureMouse) {
        const glm::vec2 d(io.MouseDelta.x, io.MouseDelta.y);
        constexpr float kTurn = 0.005f;  // radians per pixel
        if (io.KeyCtrl && (io.MouseDown[0] || io.MouseDown[1])) {
            // Drag the light's position (left) or target (right) in the camera's view plane.
            glm::vec3& point = io.MouseDown[0] ? scene_.light.position : scene_.light.target;
            const float distance = glm::length(point - scene_.camera.position);
            const float per_pixel = 2.0f * distance *
                                    std::tan(glm::radians(scene_.camera.fov_y_degrees) / 2.0f) /
                                    float(std::max(height_, 1));
            if (d != glm::vec2(0.0f)) {
                point += per_pixel * (d.x * controller_.right() - d.y * controller_.up());
                scene_changed();
            }
        } else if (io.KeyAlt && io.MouseDown[0] && selected_object_ >= 0) {
            // Drag the chosen object in the camera's view plane.
            Object& object = scene_.objects[size_t(selected_object_)];
            const float distance = glm::length(object.placement.translate - scene_.camera.position);
            const float per_pixel = 2.0f * distance *
                                    std::tan(glm::radians(scene_.camera.fov_y_degrees) / 2.0f) /
                                    float(std::max(height_, 1));
            if (d != glm::vec2(0.0f)) {
                object.placement.translate +=
                    per_pixel * (d.x * controller_.right() - d.y * controller_.up());
                object.transform = object.placed();
                scene_changed();
            }
        } else if (mode_ == CameraMode::orbit) {
            const bool dragged = d != glm::vec2(0.0f);
            if (io.MouseDown[0] && dragged) {
                controller_.orbit(-d.x * kTurn, -d.y * kTurn);
                moved = true;
            }
            if ((io.MouseDown[1] || io.MouseDown[2]) && dragged) {
                const float pan = controller_.distance() * 0.0015f;
                controller_.move({-d.x * pan, d.y * pan, 0.0f});
                moved = true;
            }
            if (io.MouseWheel != 0.0f) {
                controller_.zoom(std::pow(0.9f, io.MouseWheel));
                moved = true;
            }
        } else {
            if ((io.MouseDown[1] || io.MouseDown[0]) && d != glm::vec2(0.0f)) {
                controller_.look(-d.x * kTurn, -d.y * kTurn);
                moved = true;
            }
            if (io.MouseWheel != 0.0f)
                fly_speed_ = std::clamp(fly_speed_ * std::pow(1.25f, io.MouseWheel), 0.05f, 200.0f);
        }
    }
    if (moved) {
        controller_.apply(scene_.camera);
    }
}

}  // namespace sl::viewer
