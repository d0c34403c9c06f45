#version 450 core
// Epipolar pass 2 (Engelhardt & Dachsbacher 2010 §3.2; Yusov 2013 §3.2): which samples are
// marched. Every max_step-th sample and the last of each slice are, and so is each sample beside a
// depth discontinuity (view depths further apart than depth_threshold of the nearer), or beside
// a fast change of a point light's distance from the ray (its closest approach, further apart
// than depth_threshold of the nearer: a point light's unshadowed in-scattering grows as 1/h near
// it, Nilsson eq. 2.17, which a line between two samples misses; Yusov 2013 §3.2 refines where
// the coarse in-scattering changes for the same reason; a sun has no such peak). The others are
// interpolated (interpolate.comp) between the nearest marched samples on each side, which no
// discontinuity separates from them. Output per sample: 1 where it is marched, else 0; and the
// marched samples appended to a list, so that march.comp's invocations are all busy.
layout(local_size_x = 64, local_size_y = 1) in;
#include "epipolar/shaders/epipolar_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "gl/shaders/scattering.glsl"
#include "gl/shaders/shadow.glsl"
#include "gl/shaders/view.glsl"
#include "analytic/shaders/in_scattering.glsl"
#include "epipolar/shaders/epipolar.glsl"

layout(binding = SL_EPIPOLAR_COORDINATES_UNIT) uniform sampler2D coordinates;
layout(r32i, binding = SL_EPIPOLAR_MARKS_IMAGE) uniform writeonly iimage2D marks;

// The distance from the light to the sample's eye ray, between the eye and the ray's end.
float light_distance(vec4 c) {
    vec3 direction = eye_ray_direction(c.xy);
    vec3 to_light = frame.light_position.xyz - frame.camera_position.xyz;
    float t = clamp(dot(to_light, direction), 0.0, c.z);
    return length(to_light - t * direction);
}

void main() {
    ivec2 id = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(id, grid))) return;
    bool marched = id.x % max_step == 0 || id.x == grid.x - 1;
    if (!marched) {
        vec4 previous = texelFetch(coordinates, id - ivec2(1, 0), 0);
        vec4 current = texelFetch(coordinates, id, 0);
        vec4 next = texelFetch(coordinates, id + ivec2(1, 0), 0);
        marched = !same_surface(previous.w, current.w) || !same_surface(current.w, next.w);
        // A sun has no position: its unshadowed in-scattering along a ray is smooth (constant
        // phase angle, exponential in t), so only depth breaks refine.
        if (frame.light_cone.w <= 0.0) {
            float h = light_distance(current), before = light_distance(previous), after = light_distance(next);
            marched = marched || !same_surface(before, h) || !same_surface(h, after);
        }
    }
    imageStore(marks, id, ivec4(marched ? 1 : 0));
    if (marched) {
        uint index = atomicAdd(marched_samples, 1u);
        marched_list[index] = uint(id.x) | (uint(id.y) << 16);
        atomicMax(march_groups, index / 64u + 1u);
    }
}
