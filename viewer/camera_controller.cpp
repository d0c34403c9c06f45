#include "viewer/camera_controller.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace sl::viewer {

namespace {

constexpr float kMaxPitch = glm::radians(89.0f);

// A frame (e1, e2, up) with e1 = the horizontal direction of yaw 0.
void horizontal_frame(glm::vec3 up, glm::vec3& e1, glm::vec3& e2) {
    const glm::vec3 helper = std::abs(up.z) < 0.9f ? glm::vec3(0, 0, -1) : glm::vec3(1, 0, 0);
    e1 = glm::normalize(helper - glm::dot(helper, up) * up);
    e2 = glm::cross(up, e1);
}

}  // namespace

CameraController::CameraController(const Camera& camera)
    : world_up_(glm::normalize(camera.up)), target_(camera.target) {
    const glm::vec3 offset = camera.target - camera.position;
    distance_ = std::max(glm::length(offset), 1e-4f);
    const glm::vec3 f = offset / distance_;
    glm::vec3 e1, e2;
    horizontal_frame(world_up_, e1, e2);
    pitch_ = std::clamp(std::asin(std::clamp(glm::dot(f, world_up_), -1.0f, 1.0f)), -kMaxPitch,
                        kMaxPitch);
    yaw_ = std::atan2(glm::dot(f, e2), glm::dot(f, e1));
}

glm::vec3 CameraController::forward() const {
    glm::vec3 e1, e2;
    horizontal_frame(world_up_, e1, e2);
    return std::cos(pitch_) * (std::cos(yaw_) * e1 + std::sin(yaw_) * e2) +
           std::sin(pitch_) * world_up_;
}

glm::vec3 CameraController::right() const {
    return glm::normalize(glm::cross(forward(), world_up_));
}

glm::vec3 CameraController::up() const {
    return glm::cross(right(), forward());
}

glm::vec3 CameraController::position() const {
    return target_ - distance_ * forward();
}

void CameraController::orbit(float yaw, float pitch) {
    // The camera circles the target: turning the camera's position by +yaw turns its view too.
    yaw_ += yaw;
    pitch_ = std::clamp(pitch_ + pitch, -kMaxPitch, kMaxPitch);
}

void CameraController::look(float yaw, float pitch) {
    const glm::vec3 eye = position();
    yaw_ += yaw;
    pitch_ = std::clamp(pitch_ + pitch, -kMaxPitch, kMaxPitch);
    target_ = eye + distance_ * forward();
}

void CameraController::zoom(float factor) {
    distance_ = std::clamp(distance_ * factor, 1e-3f, 1e5f);
}

void CameraController::move(glm::vec3 d) {
    target_ += d.x * right() + d.y * up() + d.z * forward();
}

void CameraController::apply(Camera& camera) const {
    camera.position = position();
    camera.target = target_;
    camera.up = world_up_;
}

}  // namespace sl::viewer
