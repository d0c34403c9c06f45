#version 450 core
// One sample of the N x M grid over the light map's region of interest (Rohat §5.1): reads the
// light-view position and normal at the cell's centre (or a jittered point inside it) and
// computes what the sample carries: E(x_s) ΔA_s F_t(θ_i) in mm² units of the profile.
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "sss/shaders/subsurface.glsl"

out SampleData {
    vec3 position;
    vec3 normal;
    vec3 weight;
    float thickness_mm;
    float footprint_mm;  // radius of the patch the sample stands for
    float valid;
} sample_out;

// A hash of the cell and the frame (PCG-style), for the jitter.
vec2 jitter_of(uint cell, uint seed) {
    uint h = cell * 747796405u + seed * 2891336453u + 1u;
    h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
    uint a = (h >> 22u) ^ h;
    uint b = a * 1664525u + 1013904223u;
    return vec2(a & 0xffffu, b & 0xffffu) / 65536.0;
}

void main() {
    int i = gl_VertexID % grid.x, j = gl_VertexID / grid.x;
    vec2 inside = grid.w != 0 ? jitter_of(uint(gl_VertexID), uint(grid.z)) : vec2(0.5);
    vec2 uv = roi.xy + (vec2(i, j) + inside) / vec2(grid.xy) * roi.zw;
    ivec2 size = textureSize(light_positions, 0);
    ivec2 texel = clamp(ivec2(uv * vec2(size)), ivec2(0), size - 1);
    vec4 p = texelFetch(light_positions, texel, 0);
    vec3 n = texelFetch(light_normals, texel, 0).xyz;
    sample_out.position = p.xyz;
    sample_out.normal = n;
    sample_out.valid = 0.0;
    sample_out.weight = vec3(0.0);
    sample_out.thickness_mm = 0.0;
    sample_out.footprint_mm = 0.0;
    gl_Position = vec4(0.0);
    if (abs(p.w - object_id) > 0.5) {
        return;  // not this object: another object, or nothing written (§5.1)
    }
    vec3 from_light = p.xyz - light_position.xyz;
    float r = length(from_light);
    vec3 l = -from_light / r;
    float cos_i = dot(n, l);
    float axial = dot(from_light, light_direction.xyz);
    if (cos_i <= 0.0 || axial < light_range.x || axial > light_range.y) {
        return;
    }
    // The cone factor of the light (lighting.glsl's, for this light): 1 everywhere for a pyramid
    // (light_range.z = 1), whose sides are the light map's, which the samples lie within.
    float angle = acos(clamp(axial / r, -1.0, 1.0));
    float cone = light_range.z > 0.5 ? 1.0
                 : light_intensity.w <= 0.0
                     ? (angle <= light_direction.w ? 1.0 : 0.0)
                     : smoothstep(0.0, 1.0, (light_direction.w - angle) / light_intensity.w);
    vec3 irradiance = light_intensity.rgb * cone * light_falloff(r) * cos_i;  // E(x_s)
    // The patch this sample stands for: the cell's solid angle ω = (2 tan θ)² Δu Δv cos³ φ seen
    // from the light, on a surface at distance r tilted by θ_i: ΔA = ω r² / cos θ_i.
    float cos_phi = axial / r;
    float cell = roi.z * roi.w / float(grid.x * grid.y);
    float omega = 4.0 * light_position.w * light_position.w * cell * cos_phi * cos_phi * cos_phi;
    float area = omega * r * r / cos_i;
    float mm2 = material.y * material.y;
    if (slab.w > 1.5) {  // the visible-area pass: ΔA alone
        sample_out.weight = vec3(area);
        sample_out.valid = 1.0;
        return;
    }
    if (slab.w > 0.5) {
        // The seed's eq. 4.6: A_vis / N_s with A_vis = Σ ΔA over this light's valid samples.
        vec2 sums = texelFetch(visible_area, ivec2(0), 0).xy;
        area = sums.y > 0.0 ? sums.x / sums.y : 0.0;
    }
    sample_out.weight = irradiance * area * mm2 * fresnel_transmittance(material.z, cos_i);
    sample_out.footprint_mm = sqrt(area * mm2 / SSS_PI);
    if (material.w > 0.5) {
        vec4 back = texelFetch(light_back_positions, texel, 0);
        sample_out.thickness_mm =
            abs(back.w - object_id) < 0.5 ? distance(back.xyz, p.xyz) * material.y : 0.0;
    }
    sample_out.valid = 1.0;
}
