#version 450 core
// A valid sample becomes a screen-aligned quad covering the sphere of radius r_max around it
// (Rohat §5.1, listing 5.4): the screen bounds of the sphere's bounding cube, or the whole screen
// when the cube reaches behind the camera.
#include "gl/shaders/frame_uniforms.h"
#include "sss/shaders/subsurface.glsl"

layout(points) in;
layout(triangle_strip, max_vertices = 4) out;

in SampleData {
    vec3 position;
    vec3 normal;
    vec3 weight;
    float thickness_mm;
    float footprint_mm;  // radius of the patch the sample stands for
    float valid;
} sample_in[];

flat out vec3 splat_position;
flat out vec3 splat_normal;
flat out vec3 splat_weight;
flat out float splat_thickness_mm;
flat out float splat_level;  // footprint level

void main() {
    if (sample_in[0].valid < 0.5 || all(equal(sample_in[0].weight, vec3(0.0)))) {
        return;
    }
    vec3 c = sample_in[0].position;
    float R = material.x;
    vec2 lo = vec2(1e30), hi = vec2(-1e30);
    bool behind = false;
    for (int k = 0; k < 8; ++k) {
        vec3 corner = c + R * vec3((k & 1) != 0 ? 1.0 : -1.0, (k & 2) != 0 ? 1.0 : -1.0,
                                   (k & 4) != 0 ? 1.0 : -1.0);
        vec4 clip = frame.view_projection * vec4(corner, 1.0);
        if (clip.w <= 1e-6) {
            behind = true;
            break;
        }
        lo = min(lo, clip.xy / clip.w);
        hi = max(hi, clip.xy / clip.w);
    }
    if (behind) {
        lo = vec2(-1.0);
        hi = vec2(1.0);
    }
    lo = max(lo, vec2(-1.0));
    hi = min(hi, vec2(1.0));
    if (any(greaterThanEqual(lo, hi))) {
        return;  // off screen
    }
    vec2 corners[4] = vec2[](lo, vec2(hi.x, lo.y), vec2(lo.x, hi.y), hi);
    for (int k = 0; k < 4; ++k) {
        splat_position = c;
        splat_normal = sample_in[0].normal;
        splat_weight = sample_in[0].weight;
        splat_thickness_mm = sample_in[0].thickness_mm;
        splat_level = footprint_level(sample_in[0].footprint_mm);
        gl_Position = vec4(corners[k], 0.0, 1.0);
        EmitVertex();
    }
    EndPrimitive();
}
