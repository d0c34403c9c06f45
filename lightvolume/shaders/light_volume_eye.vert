#version 450 core
// The eye inside the light volume: the full-screen triangle of analytic/shaders/regions_eye.frag
// (each ray's missing front face at z = 0), collapsed to a point when the eye is outside. Every
// invocation tests the same eye, so the three vertices agree.
#include "gl/shaders/frame_uniforms.h"
#include "lightvolume/shaders/grid.glsl"
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    bool inside = light_volume_contains(frame.camera_position.xyz);
    gl_Position = inside ? vec4(2.0 * p - 1.0, 0.0, 1.0) : vec4(0.0, 0.0, 0.0, 1.0);
}
