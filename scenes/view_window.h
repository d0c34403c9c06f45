#pragma once
// The part of a sun's box that a camera's view reaches (docs/design.md §17): what the sun's
// shadow map is fitted to (frame/shadow_fit.h) and what its beam tree covers when it is built
// for that view (beamtree/beam_tree.h). The view pyramid runs from the eye to the far plane, and
// every eye ray lies in it: across the beams outside the window, and along them beyond its far
// side, the camera sees no point of the box. Along the beams the window starts at the entry
// plane, so that every occluder between the light and a point the camera sees lies in it.

#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "scenes/scene.h"

namespace sl {

// In the box's clip space (light.projection() * light.view(): [-1, 1]³, x along the light's
// right vector, y along its up vector, z from the entry plane at -1 to the box's far side at 1).
// Across the beams the window is the rectangle [lo, hi] (x, y) less what `cuts` cut off its
// corners: the convex polygon around the view pyramid's part of the box seen along the beams.
struct ViewWindow {
    glm::dvec3 lo{-1.0}, hi{1.0};
    // Lines (a, b, c) in x, y, (a, b) a unit vector: a x + b y <= c inside. Only those that cut
    // the rectangle, none along its sides.
    std::vector<glm::dvec3> cuts;
};

// The bounds of the part of the box of `light` (SpotLight::parallel) inside the view pyramid of
// `camera` at `aspect` (width / height), across the beams and to its farthest point along them,
// each widened by 2 % of its extent (and at least by 5e-4 on each side) and never beyond the box;
// lo.z is the entry plane (-1). Across the beams, the cuts: the edges of that part's convex hull
// seen along the beams, each moved out by 2 % of the larger extent (and 5e-4). nullopt when the
// view pyramid misses the box.
std::optional<ViewWindow> view_window(const SpotLight& light, const Camera& camera, float aspect);

}  // namespace sl
