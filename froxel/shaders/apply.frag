#version 450 core
// Each pixel reads the integrated froxels at its surface's view depth (or the grid's far side):
// bilinear between columns, linear in the slice coordinate between the slices' far sides (texel k
// holds I at slice boundary k + 1; I = 0 at the eye).
#include "froxel/shaders/froxel_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "froxel/shaders/grid.glsl"

layout(binding = SL_FROXEL_APPLY_SURFACE_DEPTH_UNIT) uniform sampler2D surface_depth;
layout(binding = SL_FROXEL_APPLY_INTEGRATED_UNIT) uniform sampler3D integrated;
layout(location = 0) out vec4 in_scattered;

void main() {
    vec2 uv = gl_FragCoord.xy / frame.display.yz;
    float depth = texelFetch(surface_depth, ivec2(gl_FragCoord.xy), 0).r;
    float d = grid_depth.x;
    if (depth < 1.0) {
        vec4 p = frame.inverse_view_projection * vec4(2.0 * uv - 1.0, 2.0 * depth - 1.0, 1.0);
        d = min(d, dot(p.xyz / p.w - frame.camera_position.xyz, frame.camera_forward.xyz));
    }
    float s = depth_slice(d, grid_depth, grid_size.z);
    float D = float(grid_size.z);
    vec3 value = texture(integrated, vec3(uv, (max(s, 1.0) - 0.5) / D)).rgb;
    in_scattered = vec4(s < 1.0 ? s * value : value, 0.0);
}
