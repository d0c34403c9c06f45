#version 450 core
// With `occlude` set, fragments behind the frame's surfaces are drawn at a quarter of their
// alpha, so outlines read through geometry without hiding what is in front.
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/view.glsl"
layout(binding = 0) uniform sampler2D surface_depth;
layout(location = 1) uniform int occlude;
in vec3 world_position;
in vec4 line_color;
layout(location = 0) out vec4 color;
void main() {
    float a = line_color.a;
    if (occlude != 0) {
        float z = length(world_position - frame.camera_position.xyz);
        if (z > surface_distance(surface_depth, gl_FragCoord.xy) * 1.001) a *= 0.25;
    }
    color = vec4(line_color.rgb * a, a);
}
