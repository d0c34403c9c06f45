// Shared by the splatting shaders: the per-draw light and material (sss/subsurface_pass.cpp sets
// them), Fresnel transmittance and the profile lookups (Rohat §5.1.1-5.1.2).

#include "sss/shaders/subsurface_interface.h"

layout(location = SL_SSS_ROI) uniform vec4 roi;              // light-map region: uv min, uv size
layout(location = SL_SSS_GRID) uniform ivec4 grid;            // N, M, frame seed, jitter on
layout(location = SL_SSS_LIGHT_POSITION) uniform vec4 light_position;   // xyz, tan of the cone's half angle
layout(location = SL_SSS_LIGHT_DIRECTION) uniform vec4 light_direction;  // unit axis, cone half angle (radians)
layout(location = SL_SSS_LIGHT_INTENSITY) uniform vec4 light_intensity;  // rgb, falloff width (radians)
layout(location = SL_SSS_LIGHT_RANGE) uniform vec4 light_range;      // near, far along the axis; z = 1 for a pyramid
layout(location = SL_SSS_MATERIAL) uniform vec4 material;         // r_max (units), mm per unit, η, multipole
layout(location = SL_SSS_SLAB) uniform vec4 slab;  // d_min, d_max (mm), profile layer, weights:
                                          // 0 jacobian, 1 seed, 2 ΔA alone (area pass)
layout(location = SL_SSS_OBJECT) uniform float object_id;       // index + 1
layout(location = SL_SSS_FOOTPRINT) uniform vec4 footprint;        // ρ_max (mm), levels (1: off)

layout(binding = SL_SSS_LIGHT_POSITIONS_UNIT) uniform sampler2D light_positions;   // xyz, id + 1
layout(binding = SL_SSS_LIGHT_NORMALS_UNIT) uniform sampler2D light_normals;
layout(binding = SL_SSS_BACK_POSITIONS_UNIT) uniform sampler2D light_back_positions;  // thickness pass
layout(binding = SL_SSS_EYE_POSITIONS_UNIT) uniform sampler2D eye_positions;
layout(binding = SL_SSS_EYE_NORMALS_UNIT) uniform sampler2D eye_normals;
layout(binding = SL_SSS_PROFILE_R_UNIT) uniform sampler2DArray profile_R;  // (r, d) per material layer
layout(binding = SL_SSS_PROFILE_T_UNIT) uniform sampler2DArray profile_T;
layout(binding = SL_SSS_VISIBLE_AREA_UNIT) uniform sampler2D visible_area;    // 1x1: Σ ΔA, N_s (seed weighting)

const float SSS_PI = 3.14159265358979;

// Fresnel transmittance 1 − F (Schlick, F0 from η), the F_t of eq. 3.4.
float fresnel_transmittance(float eta, float cos_theta) {
    float f0 = (eta - 1.0) / (eta + 1.0);
    f0 *= f0;
    float c = clamp(1.0 - cos_theta, 0.0, 1.0);
    return 1.0 - (f0 + (1.0 - f0) * c * c * c * c * c);
}

// Texture coordinates whose texel centres lie on the ends of [0, r_max] and [d_min, d_max], the
// way sss/diffusion.h tabulates: the last column is zero, so r ≥ r_max reads zero (§5.2.2).
vec2 profile_coordinates(float r_mm, float d_mm) {
    vec2 size = vec2(textureSize(profile_R, 0).xy);
    float r_max_mm = material.x * material.y;
    float u = clamp(r_mm / r_max_mm, 0.0, 1.0);
    float v = clamp((d_mm - slab.x) / max(slab.y - slab.x, 1e-6), 0.0, 1.0);
    return (vec2(u, v) * (size - 1.0) + 0.5) / size;
}

// The footprint level of a sample of radius ρ (sss::FootprintLevels::coordinate).
float footprint_level(float rho_mm) {
    return sqrt(clamp(rho_mm / footprint.x, 0.0, 1.0)) * (footprint.y - 1.0);
}

// R (or T) at (r, d) for footprint level t: between the two tabulated levels around it.
vec3 profile_at(sampler2DArray profile, vec2 coordinates, float level) {
    float k = floor(level);
    float next = min(k + 1.0, footprint.y - 1.0);
    vec3 a = texture(profile, vec3(coordinates, slab.z + k)).rgb;
    vec3 b = texture(profile, vec3(coordinates, slab.z + next)).rgb;
    return mix(a, b, level - k);
}
