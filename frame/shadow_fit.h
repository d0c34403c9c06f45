#pragma once
// Where a light's shadow map lies for one frame (docs/design.md §17, "The sun's map"). A spot
// light's map is its influence pyramid, whatever the camera sees. A sun's box holds the whole
// scene, so one map over all of it spreads its texels over what the camera never sees; its map is
// fitted instead to the part of the box the camera's view pyramid reaches (scenes/view_window.h):
// across the beams to that part's bounds, along them from the entry plane (so that every
// occluder between the light and a visible point is in the map: an orthographic map sees a point
// and its occluders at the same texel) to the farthest point of it, with a margin of 2 % of each
// extent, and never beyond the box. Nothing the camera sees changes: every eye ray lies in the
// view pyramid, so the fitted box cuts I_s only where the sun's box has none. One map, not
// cascades (results/lights.md says what it buys).

#include <glm/mat4x4.hpp>

#include "scenes/scene.h"

namespace sl::frame {

// World -> the shadow map's clip space for `light` seen by `camera` at `aspect` (width / height):
// light.projection() * light.view() for a spot light (or a point light's face); the fitted box
// above for parallel beams (or the whole box when the camera sees none of it).
glm::mat4 shadow_view_projection(const SpotLight& light, const Camera& camera, float aspect);

}  // namespace sl::frame
