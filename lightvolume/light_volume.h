#pragma once
// `lightvolume`: the lit volume made on the GPU from the shadow map and integrated in closed form
// (Billeter, Sintorn & Assarsson 2010, "Real-time volumetric shadows using polygonal light
// volumes"; NVIDIA's Volumetric Lighting, Hoobler GDC 2016). A grid of N x N vertices over the
// shadow map is displaced along each vertex's light ray to the depth the map holds there and
// closed by walls down the influence pyramid's sides and a fan over its near plane
// (shaders/grid.glsl). The closed mesh is drawn with the region pass's fragments
// (analytic/shaders/regions.frag): back faces add G(z), front faces subtract it, in float
// blending, with a full-screen -G(0) when the eye is inside (tested on the GPU against the same
// grid). The cone and the near/far range clip G itself, so the pyramid's corners outside the cone
// add nothing. It is the GPU-only counterpart of `beamtree`: its lit volume is the shadow map's,
// exact for planar receivers, with the map's error at silhouettes and none from integration.
// Parameters: resolution (grid vertices per side, 0: one per shadow-map texel), shadow_size.
// Statistics: grid resolution, faces, fragments of the volume pass.

#include <memory>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "frame/volume_method.h"

namespace sl::frame {
class MethodRegistry;
}

namespace sl::lightvolume {

// The closed grid's faces for N vertices per side, outward-wound, in the vertex numbering of
// shaders/grid.glsl: the N² displaced vertices row by row (index i + N j), the 4(N - 1) border
// vertices on the near plane counter-clockwise from (0, 0), the near plane's centre last.
std::vector<glm::uvec3> light_volume_triangles(int resolution);

// The CPU twin of shaders/grid.glsl's light_volume_vertex (in double precision from the same
// float matrix): every vertex's world position, from the shadow map's depths (size x size, the
// GL's rows, bottom first) and the inverse of the light's view-projection.
std::vector<glm::dvec3> light_volume_positions(const std::vector<float>& depths, int size,
                                               const glm::mat4& light_clip_to_world,
                                               int resolution);

// The inverse of the frame's shadow-map view-projection (FrameUniforms::light_view_projection,
// frame/shadow_fit.h), in double precision rounded to float: what the grid's vertices are
// unprojected with.
glm::mat4 light_clip_to_world(const glm::mat4& light_view_projection);

// Registers `lightvolume` (frame/method_registry.h).
void register_methods(frame::MethodRegistry& registry);

}  // namespace sl::lightvolume
