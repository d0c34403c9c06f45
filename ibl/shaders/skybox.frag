#version 450 core
// The environment behind the scene (Moschos algorithm 7, line 2: level 0 where nothing was drawn),
// seen through the medium up to the far plane.
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "ibl/shaders/ibl.glsl"

in vec2 uv;
layout(location = 0) out vec4 surface_radiance;

void main() {
    vec2 ndc = uv * 2.0 - 1.0;
    vec4 near_point = frame.inverse_view_projection * vec4(ndc, -1.0, 1.0);
    vec4 far_point = frame.inverse_view_projection * vec4(ndc, 1.0, 1.0);
    vec3 to_far = far_point.xyz / far_point.w - frame.camera_position.xyz;
    vec3 direction = normalize(far_point.xyz / far_point.w - near_point.xyz / near_point.w);
    vec3 radiance = frame.environment_options.z * textureLod(environment_map, direction, 0.0).rgb;
    surface_radiance = vec4(radiance * transmittance(length(to_far)), 1.0);
    gl_FragDepth = 1.0;  // drawn with GL_LEQUAL: only where no surface was
}
