#pragma once
// The frames an animation cell plays (docs/design.md §11): the scene's [animation] sampled at a
// fixed time step from its start, or, for a scene without one, an orbit of the camera about its
// target (around the camera's up axis, `orbit_degrees` over the frames) so that any scene can be
// measured moving.

#include <string>

#include "experiments/experiment.h"
#include "scenes/scene.h"

namespace sl::experiments {

class Sequence {
public:
    // Throws sl::Error when the protocol asks for more frames than the animation holds at its
    // step, or the step is longer than the animation.
    Sequence(const Scene& scene, const Protocol& protocol);

    int frames() const { return frames_; }
    double step() const { return step_; }
    bool orbit() const { return orbit_; }
    // Seconds since the animation's start (an orbit: k · step at 30 fps).
    double time(int frame) const;
    Scene state(int frame) const;
    std::string description() const;

private:
    const Scene* scene_;
    bool orbit_ = false;
    int frames_ = 0;
    double step_ = 0.0;
    double start_ = 0.0;
    double orbit_degrees_ = 0.0;
};

// The camera turned about its target by `degrees` around its up axis.
Camera orbited(const Camera& camera, double degrees);

}  // namespace sl::experiments
