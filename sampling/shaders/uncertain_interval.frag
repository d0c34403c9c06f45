#version 450 core
// hybrid3's interval buffer: every uncertain-region face drawn once; front faces give the
// nearest entry (MIN blending), back faces the farthest exit (MAX blending), and the signed count
// (ADD blending) is positive where the camera itself is inside an uncertain region (its front
// faces lie behind the camera).
#include "gl/shaders/frame_uniforms.h"
in vec3 world_position;
layout(location = 0) out float entry;
layout(location = 1) out float leave;
layout(location = 2) out float inside;
void main() {
    float t = length(world_position - frame.camera_position.xyz);
    entry = gl_FrontFacing ? t : 1e30;
    leave = gl_FrontFacing ? 0.0 : t;
    inside = gl_FrontFacing ? -1.0 : 1.0;
}
