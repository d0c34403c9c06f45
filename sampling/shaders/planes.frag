#version 450 core
// One sample of I_s per sampling plane and pixel (Dobashi et al. 2000, Nilsson §3.1): the
// integrand e of eq. 2.7 at the plane, times the shadow map's visibility H, times the ray length
// the plane stands for, dz / (V·forward) (Nilsson's footnote: planes dz apart in eye depth are
// further apart along oblique rays). Additive blending into the float target sums the planes.
#include "sampling/shaders/planes_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "gl/shaders/scattering.glsl"
#include "gl/shaders/shadow.glsl"
#include "gl/shaders/view.glsl"
#include "beamtree/shaders/classify.glsl"
#include "beamtree/shaders/region_lists.glsl"

// The hybrids' stencil (partition = gpu) rejects pixels without a region crossing before they
// are shaded.
layout(early_fragment_tests) in;
layout(binding = SL_PLANES_SURFACE_DEPTH_UNIT) uniform sampler2D surface_depth;
layout(location = SL_PLANES_DZ) uniform float dz;
layout(location = SL_PLANES_KNOWN_LIT) uniform int known_lit;  // 1: the beam tree says lit, skip the lookup
layout(location = SL_PLANES_JITTER) uniform int jitter;      // 1: per-pixel offset of the sample in its slab
// The beam tree's regions, classified here per sample (partition = gpu) instead of by cutting
// the planes on the CPU: 0 none (planes, or the CPU's pieces), 1 hybrid1 (lit: no shadow lookup,
// unlit: nothing), 2 hybrid2 (only uncertain samples: the lit ones are the analytic pass's).
// The pixel's region lists say where the sample is; where one overflowed, the tree does.
layout(location = SL_PLANES_CLASSIFY_MODE) uniform int classify_mode;

flat in float slice_depth;
layout(location = 0) out vec4 in_scattered;

// Interleaved gradient noise (Jimenez 2014): a per-pixel offset in [0, 1).
float interleaved_gradient_noise(vec2 pixel) {
    return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    int lit_count = 0, uncertain_count = 0;
    if (classify_mode != 0) {
        // A ray that crosses neither surface is outside both regions (they are bounded): the
        // common case, settled before any other work.
        lit_count = region_crossing_count(pixel, 0);
        uncertain_count = region_crossing_count(pixel, 1);
        if (uncertain_count == 0 && (lit_count == 0 || classify_mode == 2)) discard;
    }
    vec3 origin = frame.camera_position.xyz;
    vec3 direction = eye_ray_direction(gl_FragCoord.xy);
    float cos_forward = dot(direction, frame.camera_forward.xyz);
    float depth = slice_depth;
    if (jitter != 0) {
        depth += (interleaved_gradient_noise(floor(gl_FragCoord.xy)) - 0.5) * dz;
    }
    float t = depth / cos_forward;
    if (t >= eye_ray_end(surface_depth, gl_FragCoord.xy)) discard;  // behind the ray's end
    bool lit = known_lit != 0;
    if (classify_mode != 0) {
        int region;
        if (lit_count < 0 || uncertain_count < 0) {
            region = classify_region(origin + t * direction);
        } else {
            region = inside_region(pixel, 0, lit_count, t)         ? REGION_LIT
                     : inside_region(pixel, 1, uncertain_count, t) ? REGION_UNCERTAIN
                                                                   : REGION_UNLIT;
        }
        if (region == REGION_UNLIT || (classify_mode == 2 && region == REGION_LIT)) discard;
        lit = region == REGION_LIT;
    }
    vec3 e = scattering_density(origin, direction, t);
    if (all(equal(e, vec3(0.0)))) discard;
    float visibility = lit ? 1.0 : light_visibility(origin + t * direction);
    in_scattered = vec4(e * visibility * (dz / cos_forward), 0.0);
}
