#pragma once
// The viewer's camera: a target point, a heading (yaw about the world's up axis, pitch above the
// horizon) and a distance, so that orbiting (the target stays, the camera circles it) and flying
// (the camera stays, the view turns; moves carry both) are two ways of editing the same state.

#include <glm/vec3.hpp>

#include "scenes/scene.h"

namespace sl::viewer {

enum class CameraMode { orbit, fly };

class CameraController {
public:
    // Takes the camera's position and target; its up vector is the world's up axis.
    explicit CameraController(const Camera& camera);

    // Orbit: turns the camera about the target (radians; pitch stays within ±89°).
    void orbit(float yaw, float pitch);
    // Fly: turns the view about the camera.
    void look(float yaw, float pitch);
    // Orbit: scales the distance to the target (factor > 0).
    void zoom(float factor);
    // Moves camera and target together along the view's right, up and forward axes (metres).
    void move(glm::vec3 right_up_forward);

    // Writes position and target into `camera` (up, field of view and ranges stay).
    void apply(Camera& camera) const;

    glm::vec3 position() const;
    glm::vec3 forward() const;  // unit
    glm::vec3 right() const;    // unit, horizontal
    glm::vec3 up() const;       // unit, completes the view frame
    const glm::vec3& target() const { return target_; }
    float distance() const { return distance_; }

private:
    glm::vec3 world_up_;
    glm::vec3 target_;
    float yaw_ = 0.0f;
    float pitch_ = 0.0f;
    float distance_ = 1.0f;
};

}  // namespace sl::viewer
