#version 450 core
// Epipolar pass 6 (Engelhardt & Dachsbacher 2010 §3.2): every sample that was not marched takes
// the linear interpolation, by its index, of the nearest marched samples on each side of it on
// its slice (refine.comp: at most max_step away, and no depth discontinuity between).

#include "epipolar/shaders/epipolar_interface.h"

layout(local_size_x = 64, local_size_y = 1) in;
layout(location = SL_EPIPOLAR_GRID) uniform ivec2 grid;
layout(binding = SL_EPIPOLAR_MARKS_UNIT) uniform isampler2D marks;
layout(rgba32f, binding = SL_EPIPOLAR_SCATTERING_IMAGE) uniform image2D scattering;

void main() {
    ivec2 id = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(id, grid))) return;
    if (texelFetch(marks, id, 0).x != 0) return;  // marched
    int left = id.x - 1, right = id.x + 1;
    while (texelFetch(marks, ivec2(left, id.y), 0).x == 0) --left;
    while (texelFetch(marks, ivec2(right, id.y), 0).x == 0) ++right;
    float w = float(id.x - left) / float(right - left);
    vec4 a = imageLoad(scattering, ivec2(left, id.y)), b = imageLoad(scattering, ivec2(right, id.y));
    imageStore(scattering, id, vec4(mix(a.rgb, b.rgb, w), 0.0));
}
