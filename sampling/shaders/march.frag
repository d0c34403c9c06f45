#version 450 core
// Screen-space ray marching (Moschos algorithms 1, 2, 4 and 5): per pixel of the (possibly
// reduced) buffer, the eye ray from the camera to the depth buffer's surface (or the camera's
// far plane), clipped to the light (algorithm 4 on the influence pyramid, or the exact cone and
// range), then N samples at the middle of N equal steps (or jittered within them), each adding
// e(z) · visibility · step; samples the shadow map calls dark are skipped before e is evaluated
// (algorithm 5). `hybrid3` (interval_mode) marches only the pixel's uncertain intervals instead
// (beamtree/shaders/region_lists.glsl: where its ray is inside the uncertain union, in front of
// the surface and inside the cone), with samples in proportion to their summed length:
// N = clamp(ceil(density x length), min_samples, samples), spread over the intervals as one
// stratified sequence; the lit parts between them are the analytic pass's. A pixel whose list
// overflowed marches its whole cone interval at the same density (N from the cone interval's
// length) and keeps the samples the tree calls uncertain (beamtree/shaders/classify.glsl).
// Output: rgb = I_s, a = samples evaluated (for the method's statistics).
#include "sampling/shaders/march_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "gl/shaders/scattering.glsl"
#include "gl/shaders/shadow.glsl"
#include "gl/shaders/view.glsl"
#include "analytic/shaders/in_scattering.glsl"
#include "beamtree/shaders/classify.glsl"
#include "beamtree/shaders/region_lists.glsl"
#include "sampling/shaders/ray_clip.glsl"

layout(binding = SL_MARCH_SURFACE_DEPTH_UNIT) uniform sampler2D surface_depth;
layout(location = SL_MARCH_SAMPLES) uniform int samples;
layout(location = SL_MARCH_JITTER) uniform int jitter;
layout(location = SL_MARCH_CLIP_MODE) uniform int clip_mode;       // 0 off, 1 pyramid (Moschos), 2 exact cone
layout(location = SL_MARCH_BUFFER_SCALE) uniform float buffer_scale;  // reduced buffer texels per full-res pixel
layout(location = SL_MARCH_ATTENUATION) uniform int attenuation;     // 0 the shared model, 1 Moschos eq. 3.1
layout(location = SL_MARCH_OPTICAL_THICKNESS) uniform float optical_thickness;
layout(location = SL_MARCH_ANIMATE_PHASE) uniform int animate_phase;
layout(location = SL_MARCH_TIME) uniform float time;
layout(location = SL_MARCH_INTERVAL_MODE) uniform int interval_mode;
layout(location = SL_MARCH_ADAPTIVE) uniform vec2 adaptive;  // hybrid3: x = density (samples per metre), y = min
layout(location = SL_MARCH_CLIP_PLANES) uniform vec4 clip_planes[6];

layout(location = 0) out vec4 result;  // rgb I_s, a the samples taken
// I_s again, for the frame's own target where the method adds it in this pass (a marching
// buffer of the frame's size, no blur): the resolve pass is skipped. Discarded otherwise.
layout(location = 1) out vec4 added;

void write_result(vec4 value) {
    result = value;
    added = vec4(value.rgb, 0.0);
}

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

// hybrid3: the pixel's uncertain intervals, in front of `end` and inside [start, end], sorted;
// returns their count (-1: the list overflowed).
const int MAX_INTERVALS = REGION_LIST_SIZE / 2 + 1;
int uncertain_intervals(ivec2 pixel, float start, float end, out vec2 intervals[MAX_INTERVALS]) {
    int count = region_crossing_count(pixel, 1);
    if (count < 0) return -1;
    float crossings[REGION_LIST_SIZE];
    int inside = 0;
    for (int i = 0; i < count; ++i) {
        crossings[i] = region_crossing(pixel, 1, i);
        inside -= crossings[i] > 0.0 ? 1 : -1;  // exits minus entries: inside at t = 0
    }
    for (int i = 1; i < count; ++i) {  // insertion sort by distance
        float c = crossings[i];
        int j = i - 1;
        while (j >= 0 && abs(crossings[j]) > abs(c)) {
            crossings[j + 1] = crossings[j];
            --j;
        }
        crossings[j + 1] = c;
    }
    int n = 0;
    float open = 0.0;
    for (int i = 0; i <= count; ++i) {
        bool last = i == count;
        float t = last ? 1e30 : abs(crossings[i]);
        int next = last ? 0 : inside + (crossings[i] > 0.0 ? 1 : -1);
        if (inside <= 0 && next > 0) open = t;
        if (inside > 0 && (next <= 0 || last)) {
            float a = max(open, start), b = min(t, end);
            if (b > a && n < MAX_INTERVALS) intervals[n++] = vec2(a, b);
        }
        inside = next;
    }
    return n;
}

vec3 sample_density(vec3 origin, vec3 direction, float t, float g) {
    return attenuation == 1 ? moschos_density(origin, direction, t, g)
                            : scattering_density_g(origin, direction, t, g);
}

void main() {
    // The full-resolution pixel this texel stands for: its centre for a reduced buffer.
    vec2 fragment = (floor(gl_FragCoord.xy) + 0.5) / buffer_scale;
    vec3 origin = frame.camera_position.xyz;
    vec3 direction = eye_ray_direction(fragment);
    float trace_end = eye_ray_end(surface_depth, fragment);
    float start = 0.0, end = trace_end;
    if (interval_mode != 0 || clip_mode == 2) {
        vec2 cone = light_interval(origin, direction, trace_end);
        start = cone.x;
        end = cone.y;
    } else if (clip_mode == 1) {
        vec3 clipped = clip_trace(origin, direction, trace_end, clip_planes);
        start = clipped.x;
        end = clipped.y;
    }
    if (!(end > start)) {
        write_result(vec4(0.0));
        return;
    }
    float offset = jitter != 0 ? interleaved_gradient_noise(floor(gl_FragCoord.xy)) : 0.5;
    float g = frame.medium_attenuation.w;
    vec3 sum = vec3(0.0);
    int taken = 0;
    if (interval_mode != 0) {
        vec2 intervals[MAX_INTERVALS];
        int n = uncertain_intervals(ivec2(fragment), start, end, intervals);
        if (n < 0) {
            // The list overflowed: samples at the same density over the whole cone interval,
            // each asking the tree, the uncertain ones kept.
            int count = int(clamp(ceil(adaptive.x * (end - start)), adaptive.y, float(samples)));
            float step_length = (end - start) / float(count);
            for (int i = 0; i < count; ++i) {
                float t = start + (float(i) + offset) * step_length;
                vec3 p = origin + t * direction;
                if (classify_region(p) != REGION_UNCERTAIN) continue;
                float visibility = light_visibility(p);
                if (visibility <= 0.0) continue;
                ++taken;
                sum += sample_density(origin, direction, t, g) * visibility * step_length;
            }
            write_result(vec4(sum, float(taken)));
            return;
        }
        float length_sum = 0.0;
        for (int k = 0; k < n; ++k) length_sum += intervals[k].y - intervals[k].x;
        if (!(length_sum > 0.0)) {
            write_result(vec4(0.0));
            return;
        }
        int count = int(clamp(ceil(adaptive.x * length_sum), adaptive.y, float(samples)));
        float step_length = length_sum / float(count);
        // Sample i at (i + offset) step lengths along the intervals laid end to end.
        int k = 0;
        float covered = 0.0;
        for (int i = 0; i < count; ++i) {
            float s = (float(i) + offset) * step_length;
            while (k + 1 < n && s > covered + (intervals[k].y - intervals[k].x)) {
                covered += intervals[k].y - intervals[k].x;
                ++k;
            }
            float t = intervals[k].x + (s - covered);
            vec3 p = origin + t * direction;
            float visibility = light_visibility(p);
            if (visibility <= 0.0) continue;
            ++taken;
            sum += sample_density(origin, direction, t, g) * visibility;
        }
        write_result(vec4(sum * step_length, float(taken)));
        return;
    }
    float step_length = (end - start) / float(samples);
    for (int i = 0; i < samples; ++i) {
        float t = start + (float(i) + offset) * step_length;
        vec3 p = origin + t * direction;
        float visibility = light_visibility(p);
        if (visibility <= 0.0) continue;  // dark-sample skipping
        ++taken;
        float gi = g;
        if (animate_phase != 0) {
            // Moschos §3.2.4: the asymmetry drifts with time and place, so the beam shimmers.
            gi = clamp(g + 0.3 * sin(2.0 * time + dot(p, vec3(1.3, 0.7, 1.1))), -0.9, 0.9);
        }
        sum += sample_density(origin, direction, t, gi) * visibility;
    }
    write_result(vec4(sum * step_length, float(taken)));
}
