#include "viewer/window.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>

#include <glm/trigonometric.hpp>

namespace sl::viewer {

void Viewer::handle_input(double dt) {
    // The camera is written only when it moves: an untouched view keeps the scene's exact
    // camera (and with it the cache key of its reference).
    bool moved = false;
    if (!ImGui::GetIO().WantCaptureKeyboard) {
        moved |= handle_keys(dt);
    }
    if (!ImGui::GetIO().WantCaptureMouse) {
        moved |= handle_mouse();
    }
    if (moved) {
        controller_.apply(scene_.camera);
    }
}

bool Viewer::handle_keys(double dt) {
    const ImGuiIO& io = ImGui::GetIO();
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
    auto* window = static_cast<GLFWwindow*>(platform_->native_window());
    auto down = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS ? 1.0f : 0.0f; };
    const glm::vec3 move(down(GLFW_KEY_D) - down(GLFW_KEY_A), down(GLFW_KEY_E) - down(GLFW_KEY_Q),
                         down(GLFW_KEY_W) - down(GLFW_KEY_S));
    if (move == glm::vec3(0.0f)) {
        return false;
    }
    const float boost = io.KeyShift ? 4.0f : 1.0f;
    controller_.move(move * float(fly_speed_ * boost * dt));
    return true;
}

glm::vec3 Viewer::view_plane_drag(const glm::vec3& point, glm::vec2 pixels) const {
    // A pixel at the point's distance spans this many metres of the camera's view plane.
    const float distance = glm::length(point - scene_.camera.position);
    const float per_pixel = 2.0f * distance *
                            std::tan(glm::radians(scene_.camera.fov_y_degrees) / 2.0f) /
                            float(std::max(height_, 1));
    return per_pixel * (pixels.x * controller_.right() - pixels.y * controller_.up());
}

bool Viewer::handle_mouse() {
    const ImGuiIO& io = ImGui::GetIO();
    const glm::vec2 d(io.MouseDelta.x, io.MouseDelta.y);
    const bool dragged = d != glm::vec2(0.0f);
    constexpr float kTurn = 0.005f;  // radians per pixel
    bool moved = false;
    if (io.KeyCtrl && (io.MouseDown[0] || io.MouseDown[1]) && scene_.lights.empty()) {
        // Drag the light's position (left) or target (right) in the camera's view plane (a scene
        // of one light: several are the scene file's).
        glm::vec3& point = io.MouseDown[0] ? scene_.light.position : scene_.light.target;
        if (dragged) {
            point += view_plane_drag(point, d);
            scene_changed();
        }
    } else if (io.KeyAlt && io.MouseDown[0] && selected_object_ >= 0) {
        // Drag the chosen object in the camera's view plane.
        Object& object = scene_.objects[size_t(selected_object_)];
        if (dragged) {
            object.placement.translate += view_plane_drag(object.placement.translate, d);
            object.transform = object.placed();
            scene_changed();
        }
    } else if (mode_ == CameraMode::orbit) {
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
        if ((io.MouseDown[1] || io.MouseDown[0]) && dragged) {
            controller_.look(-d.x * kTurn, -d.y * kTurn);
            moved = true;
        }
        if (io.MouseWheel != 0.0f)
            fly_speed_ = std::clamp(fly_speed_ * std::pow(1.25f, io.MouseWheel), 0.05f, 200.0f);
    }
    return moved;
}

}  // namespace sl::viewer
