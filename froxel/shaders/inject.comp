#version 450 core
// Froxel injection (Wronski 2014, Hillaire 2015): each froxel's in-scattering density S, the mean
// of the light's source term over `samples` points stratified along the froxel's depth span on
// its column's ray, each with the frame's shadow-map visibility: S = σs p(cos α) I c(Ω) T(r)/r² (or
// 1/(a1 r² + a0), the simplified model), i.e. e(z) of Nilsson eq. 2.7 without the eye-side T(z),
// which the integration applies. With jitter the points move by a per-froxel offset that changes
// every frame (interleaved gradient noise plus a Halton step), for the temporal filter to average.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
#include "froxel/shaders/froxel_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "gl/shaders/scattering.glsl"
#include "gl/shaders/shadow.glsl"
#include "froxel/shaders/grid.glsl"

layout(rgba32f, binding = SL_FROXEL_INJECT_IMAGE) uniform writeonly image3D scattering;
layout(location = SL_FROXEL_INJECT_SAMPLES) uniform int samples;
layout(location = SL_FROXEL_INJECT_JITTER) uniform int jitter;
layout(location = SL_FROXEL_INJECT_FRAME_OFFSET) uniform float frame_offset;  // the frame's Halton step, in [0, 1)

vec3 source(vec3 p, vec3 direction) {
    vec3 from_light = p - frame.light_position.xyz;
    float r = length(from_light);
    if (!(r > 0.0) || !in_light_range(from_light)) return vec3(0.0);
    float cone = cone_factor(from_light);
    if (cone == 0.0) return vec3(0.0);
    float phase = phase_function(-dot(light_travel(from_light), direction));
    return frame.medium_sigma_s.rgb * phase * frame.light_intensity.rgb * cone *
           light_attenuation(from_light);
}

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(id, grid_size))) return;
    vec3 direction = column_direction(vec2(id.xy));
    float along = dot(direction, frame.camera_forward.xyz);  // view depth per unit of distance
    float offset = 0.5;
    if (jitter != 0) {
        vec2 q = vec2(id.xy) + 5.588238 * float(id.z);
        offset = fract(fract(52.9829189 * fract(dot(q, vec2(0.06711056, 0.00583715)))) +
                       frame_offset);
    }
    vec3 sum = vec3(0.0);
    for (int k = 0; k < samples; ++k) {
        float d = slice_depth(float(id.z) + (float(k) + offset) / float(samples));
        vec3 p = frame.camera_position.xyz + direction * (d / along);
        vec3 s = source(p, direction);
        if (any(greaterThan(s, vec3(0.0)))) s *= light_visibility(p);
        sum += s;
    }
    imageStore(scattering, id, vec4(sum / float(samples), 0.0));
}
