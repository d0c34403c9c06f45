#version 450 core
// Epipolar pass 1 (Engelhardt & Dachsbacher 2010 §3.1; Yusov 2013 §3.1): each sample's window
// position on its slice, samples_per_slice of them evenly from the slice's entry to its exit, and
// the eye ray through it to the surface there (the depth buffer's texel under it).
// Output per sample: xy window position, z the ray's end distance (surface or far plane), w its
// view depth; w = -1 for a slice that crosses no pixel.
layout(local_size_x = 64, local_size_y = 1) in;
#include "epipolar/shaders/epipolar_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "gl/shaders/scattering.glsl"
#include "gl/shaders/shadow.glsl"
#include "gl/shaders/view.glsl"
#include "analytic/shaders/in_scattering.glsl"
#include "epipolar/shaders/epipolar.glsl"

layout(binding = SL_EPIPOLAR_SURFACE_DEPTH_UNIT) uniform sampler2D surface_depth;
layout(rgba32f, binding = SL_EPIPOLAR_COORDINATES_IMAGE) uniform writeonly image2D coordinates;

void main() {
    ivec2 id = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(id, grid))) return;
    vec4 ends = slices[id.y].ends;
    if (ends.xy == ends.zw) {
        imageStore(coordinates, id, vec4(ends.xy, 0.0, -1.0));
        return;
    }
    // Inside the image by a hair, so that the texel under it exists.
    vec2 x = clamp(sample_position(id.y, id.x), vec2(1e-3), frame.display.yz - 1e-3);
    float end = eye_ray_end(surface_depth, x);
    imageStore(coordinates, id, vec4(x, end, view_depth(eye_ray_direction(x), end)));
}
