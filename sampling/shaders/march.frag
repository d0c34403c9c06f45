#version 450 core
// Screen-space ray marching (Moschos algorithms 1, 2, 4 and 5): per pixel of the (possibly
// reduced) buffer, the eye ray from the camera to the depth buffer's surface (or the camera's
// far plane), clipped to the light (algorithm 4 on the influence pyramid, or the exact cone and
// range), then N samples at the middle of N equal steps (or jittered within them), each adding
// e(z) · visibility · step; samples the shadow map calls dark are skipped before e is evaluated
// (algorithm 5). `hybrid3` marches only its uncertain interval instead (interval_mode).
// Output: rgb = I_s, a = samples evaluated (for the method's statistics).
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "gl/shaders/scattering.glsl"
#include "gl/shaders/shadow.glsl"
#include "gl/shaders/view.glsl"
#include "analytic/shaders/in_scattering.glsl"
#include "gl/shaders/uncertain_interval.glsl"
#include "sampling/shaders/ray_clip.glsl"

layout(binding = 0) uniform sampler2D surface_depth;
layout(location = 0) uniform int samples;
layout(location = 1) uniform int jitter;
layout(location = 2) uniform int clip_mode;       // 0 off, 1 pyramid (Moschos), 2 exact cone
layout(location = 3) uniform float buffer_scale;  // reduced buffer texels per full-res pixel
layout(location = 4) uniform int attenuation;     // 0 the shared model, 1 Moschos eq. 3.1
layout(location = 5) uniform float optical_thickness;
layout(location = 6) uniform int animate_phase;
layout(location = 7) uniform float time;
layout(location = 8) uniform int interval_mode;
layout(location = 10) uniform vec4 clip_planes[6];

layout(location = 0) out vec4 result;

float interleaved_gradient_noise(vec2 pixel) {
    return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

// Moschos eq. 3.1: L_A(x1) L_flux(x1) L_A(x2) with L_A(x) = exp(-x / l) and the cone's flux
// f = I 2π(1 - cos φ), so that L_flux = I / x1²; σs p and the spot effect as in the shared
// model. Not the reference's model unless l = 1/σt: an option for Moschos' pictures.
vec3 moschos_density(vec3 origin, vec3 direction, float t, float g) {
    vec3 from_light = origin + t * direction - frame.light_position.xyz;
    float r = length(from_light);
    if (!(r > 0.0) || !in_light_range(from_light)) return vec3(0.0);
    float cone = cone_factor(from_light);
    float p = phase_function_g(-dot(from_light / r, direction), g);
    return frame.medium_sigma_s.rgb * p * frame.light_intensity.rgb * cone / (r * r) *
           exp(-r / optical_thickness) * exp(-t / optical_thickness);
}

void main() {
    // The full-resolution pixel this texel stands for: its centre for a reduced buffer.
    vec2 fragment = (floor(gl_FragCoord.xy) + 0.5) / buffer_scale;
    vec3 origin = frame.camera_position.xyz;
    vec3 direction = eye_ray_direction(fragment);
    float trace_end = min(surface_distance(surface_depth, fragment), far_plane_distance(fragment));
    float start = 0.0, end = trace_end;
    if (interval_mode != 0) {
        vec2 interval = uncertain_interval(ivec2(fragment));
        start = interval.x;
        end = min(interval.y, trace_end);
        vec2 cone = light_interval(origin, direction, trace_end);
        start = max(start, cone.x);
        end = min(end, cone.y);
    } else if (clip_mode == 1) {
        vec3 clipped = clip_trace(origin, direction, trace_end, clip_planes);
        start = clipped.x;
        end = clipped.y;
    } else if (clip_mode == 2) {
        vec2 cone = light_interval(origin, direction, trace_end);
        start = cone.x;
        end = cone.y;
    }
    if (!(end > start)) {
        result = vec4(0.0);
        return;
    }
    float step_length = (end - start) / float(samples);
    float offset = jitter != 0 ? interleaved_gradient_noise(floor(gl_FragCoord.xy)) : 0.5;
    vec3 sum = vec3(0.0);
    int taken = 0;
    for (int i = 0; i < samples; ++i) {
        float t = start + (float(i) + offset) * step_length;
        vec3 p = origin + t * direction;
        float visibility = light_visibility(p);
        if (visibility <= 0.0) continue;  // dark-sample skipping
        ++taken;
        float g = frame.medium_attenuation.w;
        if (animate_phase != 0) {
            // Moschos §3.2.4: the asymmetry drifts with time and place, so the beam shimmers.
            g = clamp(g + 0.3 * sin(2.0 * time + dot(p, vec3(1.3, 0.7, 1.1))), -0.9, 0.9);
        }
        vec3 e = attenuation == 1 ? moschos_density(origin, direction, t, g)
                                  : scattering_density_g(origin, direction, t, g);
        sum += e * visibility;
    }
    result = vec4(sum * step_length, float(taken));
}
