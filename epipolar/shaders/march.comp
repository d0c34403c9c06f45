#version 450 core
// Epipolar pass 5 (Yusov 2013 §3.4): the marched samples (refine.comp's list), each along the eye ray
// through its window position to its surface, with the 1D min-max tree of its slice
// (rectified_march.glsl). Output per marched sample: rgb I_s, a the samples lit. The samples lit and
// the tree's texels read are summed in `Counters`.
layout(local_size_x = 64, local_size_y = 1) in;
#include "epipolar/shaders/epipolar_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "gl/shaders/scattering.glsl"
#include "gl/shaders/shadow.glsl"
#include "gl/shaders/view.glsl"
#include "analytic/shaders/in_scattering.glsl"
#include "epipolar/shaders/epipolar.glsl"
#include "epipolar/shaders/rectified_march.glsl"

layout(binding = SL_EPIPOLAR_COORDINATES_UNIT) uniform sampler2D coordinates;
layout(rgba32f, binding = SL_EPIPOLAR_SCATTERING_IMAGE) uniform writeonly image2D scattering;

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= marched_samples) return;
    ivec2 id = ivec2(marched_list[index] & 0xffffu, marched_list[index] >> 16);
    vec4 c = texelFetch(coordinates, id, 0);
    vec4 result = vec4(0.0);
    if (c.w >= 0.0) {
        int lookups = 0;
        result = march_rectified(frame.camera_position.xyz, eye_ray_direction(c.xy), c.z, id.y,
                                 lookups);
        atomicAdd(lit_samples, uint(result.a));
        atomicAdd(tree_lookups, uint(lookups));
    }
    imageStore(scattering, id, result);
}
