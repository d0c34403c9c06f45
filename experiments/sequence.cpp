#include "experiments/sequence.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "scenes/animation.h"

namespace sl::experiments {

namespace {
constexpr int kOrbitFrames = 120;   // an orbit's frames when the protocol says 0
constexpr double kOrbitFps = 30.0;  // an orbit's time axis
}  // namespace

Camera orbited(const Camera& camera, double degrees) {
    Camera turned = camera;
    const glm::vec3 axis = glm::normalize(camera.up);
    const glm::mat4 rotation = glm::rotate(glm::mat4(1.0f), float(glm::radians(degrees)), axis);
    turned.position =
        camera.target + glm::vec3(rotation * glm::vec4(camera.position - camera.target, 0.0f));
    return turned;
}

Sequence::Sequence(const Scene& scene, const Protocol& protocol) : scene_(&scene) {
    if (!scene.animation) {
        orbit_ = true;
        frames_ = protocol.frames > 0 ? protocol.frames : kOrbitFrames;
        step_ = protocol.step > 0.0 ? protocol.step : 1.0 / kOrbitFps;
        orbit_degrees_ = protocol.orbit_degrees;
        return;
    }
    const Animation& a = *scene.animation;
    start_ = a.start;
    step_ = protocol.step > 0.0 ? protocol.step : 1.0 / a.fps;
    const double length = a.end - a.start;
    // The frames at start + k·step that lie in [start, end] (a hair of rounding forgiven).
    const double fit = std::floor(length / step_ * (1.0 + 1e-9) + 1e-9);
    if (fit + 1.0 > 1e6) {
        fail("{}: {} s at a step of {} s is more than 10^6 frames", scene.name, length, step_);
    }
    const int available = int(fit) + 1;
    if (protocol.frames > available) {
        fail(
            "{}: [protocol] frames = {}, but the animation holds {} frames at a step of {} s "
            "({} s to {} s)",
            scene.name, protocol.frames, available, step_, a.start, a.end);
    }
    frames_ = protocol.frames > 0 ? protocol.frames : available;
}

double Sequence::time(int frame) const {
    const double t = start_ + double(frame) * step_;
    return orbit_ ? t : std::min(t, scene_->animation->end);
}

Scene Sequence::state(int frame) const {
    if (orbit_) {
        Scene s = *scene_;
        s.camera = orbited(scene_->camera,
                           orbit_degrees_ * double(frame) / double(std::max(frames_ - 1, 1)));
        return s;
    }
    return scene_at(*scene_, time(frame));
}

std::string Sequence::description() const {
    return orbit_ ? fmt::format("an orbit of {}° in {} frames", orbit_degrees_, frames_)
                  : fmt::format("{} frames of its animation, {:.4g} s apart", frames_, step_);
}

}  // namespace sl::experiments
