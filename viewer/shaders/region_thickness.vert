#version 450 core
// The beam tree's region pieces (closed convex polyhedra, outward faces) in world space, with the
// region each face bounds (0 lit, 1 uncertain, 2 unlit).
#include "gl/shaders/frame_uniforms.h"
layout(location = 0) in vec3 position;
layout(location = 1) in float region;
out vec3 world_position;
flat out int region_index;
void main() {
    world_position = position;
    region_index = int(region + 0.5);
    gl_Position = frame.view_projection * vec4(position, 1.0);
}
