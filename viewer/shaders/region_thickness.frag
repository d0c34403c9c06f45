#version 450 core
// The length of every eye ray inside each region type, up to the first surface, accumulated with
// additive blending: each back face adds min(z, surface), each front face subtracts it. For one
// convex piece that is max(0, min(exit, s) - min(entry, s)), its share of [0, s]; the pieces tile
// the influence volume, so the channels sum to the ray's length inside it. A front face behind
// the camera is clipped away and counts as 0: the camera's own distance.
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/view.glsl"
layout(binding = 0) uniform sampler2D surface_depth;
in vec3 world_position;
flat in int region_index;
layout(location = 0) out vec4 thickness;
void main() {
    float z = length(world_position - frame.camera_position.xyz);
    float surface = surface_distance(surface_depth, gl_FragCoord.xy);
    float signed_z = (gl_FrontFacing ? -1.0 : 1.0) * min(z, surface);
    thickness = vec4(0.0);
    thickness[region_index] = signed_z;
}
