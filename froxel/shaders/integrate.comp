#version 450 core
// Front-to-back integration of every froxel column (Hillaire 2015, "Physically based and unified
// volumetric rendering in Frostbite", the energy-conserving step): over slice k of length Δt along
// the column's ray, with density S and extinction σt held constant,
//   I += T (S - S e^(-σt Δt)) / σt,   T *= e^(-σt Δt)
// (S Δt where σt = 0: the simplified model has no eye-side extinction). Texel k holds I at the
// slice's far side. A constant slab of any length integrates to its closed form, whatever the
// slice count.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
#include "froxel/shaders/froxel_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "froxel/shaders/grid.glsl"

layout(binding = SL_FROXEL_INTEGRATE_DENSITIES_UNIT) uniform sampler3D densities;
layout(rgba32f, binding = SL_FROXEL_INTEGRATE_IMAGE) uniform writeonly image3D integrated;

void main() {
    ivec2 xy = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(xy, grid_size.xy))) return;
    vec3 direction = column_direction(vec2(xy));
    float along = dot(direction, frame.camera_forward.xyz);
    vec3 sigma_t = frame.medium_sigma_t.w > 0.5 ? frame.medium_sigma_t.rgb : vec3(0.0);
    vec3 sum = vec3(0.0), transmittance = vec3(1.0);
    float near = 0.0;
    for (int k = 0; k < grid_size.z; ++k) {
        float far = slice_depth(float(k + 1));
        float dt = (far - near) / along;
        near = far;
        vec3 s = texelFetch(densities, ivec3(xy, k), 0).rgb;
        vec3 e = exp(-sigma_t * dt);
        for (int c = 0; c < 3; ++c) {
            float step_integral = sigma_t[c] > 0.0 ? s[c] * (1.0 - e[c]) / sigma_t[c] : s[c] * dt;
            sum[c] += transmittance[c] * step_integral;
        }
        transmittance *= e;
        imageStore(integrated, ivec3(xy, k), vec4(sum, 0.0));
    }
}
