#version 450 core
// Temporal reprojection of the froxel densities (Hillaire 2015; Unity HDRP and Godot do the
// like): each froxel's centre is found in the previous frame's grid (its camera and slicing), and
// the density there, clamped to the range of this frame's seven nearest froxels (itself and its
// six neighbours, as TAA clamps colour), is blended in: S = mix(S_new, clamp(S_old), history).
// Froxels that were outside the previous grid keep S_new.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
#include "froxel/shaders/froxel_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "froxel/shaders/grid.glsl"

layout(binding = SL_FROXEL_TEMPORAL_CURRENT_UNIT) uniform sampler3D current;  // this frame's densities
layout(binding = SL_FROXEL_TEMPORAL_PREVIOUS_UNIT) uniform sampler3D previous;  // the last frame's result
layout(rgba32f, binding = SL_FROXEL_TEMPORAL_IMAGE) uniform writeonly image3D result;
layout(location = SL_FROXEL_TEMPORAL_HISTORY) uniform float history;
layout(location = SL_FROXEL_TEMPORAL_PREVIOUS_VIEW_PROJECTION) uniform mat4 previous_view_projection;
layout(location = SL_FROXEL_TEMPORAL_PREVIOUS_CAMERA) uniform vec4 previous_camera;   // xyz
layout(location = SL_FROXEL_TEMPORAL_PREVIOUS_FORWARD) uniform vec4 previous_forward;  // xyz
layout(location = SL_FROXEL_TEMPORAL_PREVIOUS_DEPTH) uniform vec2 previous_depth;    // E, c of the previous grid

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(id, grid_size))) return;
    vec3 s = texelFetch(current, id, 0).rgb;
    vec3 lo = s, hi = s;
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = -1; side <= 1; side += 2) {
            ivec3 n = id;
            n[axis] = clamp(n[axis] + side, 0, grid_size[axis] - 1);
            vec3 v = texelFetch(current, n, 0).rgb;
            lo = min(lo, v);
            hi = max(hi, v);
        }
    }
    vec3 direction = column_direction(vec2(id.xy));
    float d = slice_depth(float(id.z) + 0.5);
    vec3 p = frame.camera_position.xyz + direction * (d / dot(direction, frame.camera_forward.xyz));
    vec4 clip = previous_view_projection * vec4(p, 1.0);
    vec3 result_value = s;
    if (clip.w > 0.0) {
        vec2 uv = 0.5 * clip.xy / clip.w + 0.5;
        float w = depth_slice(dot(p - previous_camera.xyz, previous_forward.xyz), previous_depth,
                              grid_size.z) / float(grid_size.z);
        vec3 at = vec3(uv, w);
        if (all(greaterThanEqual(at, vec3(0.0))) && all(lessThanEqual(at, vec3(1.0)))) {
            vec3 old = clamp(texture(previous, at).rgb, lo, hi);
            result_value = mix(s, old, history);
        }
    }
    imageStore(result, id, vec4(result_value, 0.0));
}
