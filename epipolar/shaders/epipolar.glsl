// What the epipolar passes share (epipolar/epipolar.h): the frame's slices, the unwarp from a
// pixel to its slices (the twin of epipolar/geometry.cpp, tested against it), and the two
// marches of an eye ray over its interval in the light's cone:
//   march_rectified  Chen et al. 2011 §4-5: along the slice's rectified shadow-map line, walking
//                    its 1D min-max tree, so that a run of steps whose depths all lie in front of
//                    (behind) every map depth under it is lit (shadowed) at once;
//   march_direct     the plain march through the frame's shadow map (the fix-up of pixels that
//                    cannot be interpolated, and every pixel with interpolation off).
// Needs frame_uniforms.h, lighting.glsl, scattering.glsl, shadow.glsl; march_rectified with
// EPIPOLAR_CLOSED_FORM also in_scattering.glsl.

#include "epipolar/shaders/epipolar_interface.h"

layout(location = SL_EPIPOLAR_GRID) uniform ivec2 grid;          // x = samples per slice, y = slices
layout(location = SL_EPIPOLAR_LIGHT_SCREEN) uniform vec2 light_screen;   // the light's screen position, pixels
layout(location = SL_EPIPOLAR_ARC) uniform vec3 arc;            // exit arc: start, length, 1 when periodic
layout(location = SL_EPIPOLAR_MAP_TEXELS) uniform int map_texels;      // texels of a rectified line
layout(location = SL_EPIPOLAR_DEPTH_THRESHOLD) uniform float depth_threshold;
layout(location = SL_EPIPOLAR_MAX_STEP) uniform int max_step;
layout(location = SL_EPIPOLAR_SAMPLES) uniform int samples;         // steps per eye ray
layout(location = SL_EPIPOLAR_MINMAX_LEVELS) uniform int minmax_levels;   // levels of the tree walked (0: none)
layout(location = SL_EPIPOLAR_DIRECT) uniform int direct;          // 1: interpolation off (every pixel marched)

struct Slice {
    vec4 ends;  // xy entry, zw exit (window pixels)
    vec4 line;  // xy shadow-map origin, zw step per texel (0: the line misses the map)
};
layout(std430, binding = SL_EPIPOLAR_SLICES_BINDING) readonly buffer Slices {
    Slice slices[];
};
// The frame's counters (epipolar.cpp's Counters): march.comp's work groups as an indirect
// dispatch, then what the statistics report.
layout(std430, binding = SL_EPIPOLAR_COUNTERS_BINDING) buffer Counters {
    uint march_groups, march_groups_y, march_groups_z;
    uint marched_samples, lit_samples, tree_lookups, fixup_pixels, fixup_samples;
};
// The marched samples (refine.comp), x | y << 16.
layout(std430, binding = SL_EPIPOLAR_MARCHED_LIST_BINDING) buffer MarchedList {
    uint marched_list[];
};

// ---- The unwarp (epipolar/geometry.cpp) ----

float perimeter_position(vec2 b) {
    float w = frame.display.y, h = frame.display.z;
    float d0 = abs(b.y), d1 = abs(b.x - w), d2 = abs(b.y - h), d3 = abs(b.x);
    float m = min(min(d0, d1), min(d2, d3));
    if (d0 == m) return clamp(b.x, 0.0, w);
    if (d1 == m) return w + clamp(b.y, 0.0, h);
    if (d2 == m) return w + h + (w - clamp(b.x, 0.0, w));
    return 2.0 * w + h + (h - clamp(b.y, 0.0, h));
}

// Where the ray from p through x leaves the image.
vec2 exit_point(vec2 p, vec2 x) {
    vec2 d = x - p;
    vec2 size = frame.display.yz;
    float leave = 1e30;
    for (int i = 0; i < 2; ++i) {
        if (d[i] == 0.0) continue;
        float a = (0.0 - p[i]) / d[i], b = (size[i] - p[i]) / d[i];
        leave = min(leave, max(a, b));
    }
    return p + leave * d;
}

// The fractional slice coordinate of window position x (geometry.h slice_coordinate).
float slice_coordinate(vec2 x) {
    float perimeter = 2.0 * (frame.display.y + frame.display.z);
    float along = mod(perimeter_position(exit_point(light_screen, x)) - arc.x, perimeter);
    if (arc.z < 0.5 && along > 0.5 * (arc.y + perimeter)) along -= perimeter;
    return along / arc.y * float(grid.y) - 0.5;
}

// The position of x along slice s, in samples (0 at the entry, grid.x - 1 at the exit).
float sample_coordinate(int s, vec2 x) {
    vec2 a = slices[s].ends.xy, b = slices[s].ends.zw;
    vec2 d = b - a;
    float dd = dot(d, d);
    if (!(dd > 0.0)) return 0.0;
    return dot(x - a, d) / dd * float(grid.x - 1);
}

vec2 sample_position(int s, int k) {
    return mix(slices[s].ends.xy, slices[s].ends.zw, float(k) / float(max(grid.x - 1, 1)));
}

// Camera-space depth of the point at distance t along the eye ray `direction`.
float view_depth(vec3 direction, float t) {
    return t * dot(direction, frame.camera_forward.xyz);
}

// Whether two view depths are on the same surface: closer than depth_threshold of the nearer.
bool same_surface(float a, float b) {
    return abs(a - b) <= depth_threshold * min(a, b);
}

// ---- The marches ----

layout(binding = SL_EPIPOLAR_LIGHT_DEPTH_UNIT) uniform sampler2D light_depth;  // the shadow map's depths, not comparisons

// Texel `texel` of slice s's rectified line (level 0 of its min-max tree): the depth of the
// shadow map's texel under its centre.
float line_depth(int texel, int s) {
    vec4 line = slices[s].line;
    ivec2 size = textureSize(light_depth, 0);
    vec2 uv = line.xy + (float(texel) + 0.5) * line.zw;
    return texelFetch(light_depth, clamp(ivec2(floor(uv * vec2(size))), ivec2(0), size - 1), 0).r;
}

// The plain march through the frame's shadow map: march.frag with clip = cone, no jitter, the
// shared model (the same samples, the same sums).
vec4 march_direct(vec3 origin, vec3 direction, float end_distance) {
    vec2 cone = light_interval(origin, direction, end_distance);
    float start = cone.x, end = cone.y;
    if (!(end > start)) return vec4(0.0);
    float g = frame.medium_attenuation.w;
    float step_length = (end - start) / float(samples);
    vec3 sum = vec3(0.0);
    int taken = 0;
    for (int i = 0; i < samples; ++i) {
        float t = start + (float(i) + 0.5) * step_length;
        vec3 p = origin + t * direction;
        float visibility = light_visibility(p);
        if (visibility <= 0.0) continue;
        ++taken;
        sum += scattering_density_g(origin, direction, t, g) * visibility;
    }
    return vec4(sum * step_length, float(taken));
}
