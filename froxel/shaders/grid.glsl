// The froxel grid (froxel/froxel.h): W x H columns over the image, D slices in view depth from the
// eye to depth_extent E. Slice boundary s lies at view depth d(s) = c ((E + c) / c)^(s / D) - c:
// linear, d ≈ c ln(1 + E / c) s / D, where d << c, exponential where d >> c. Needs
// frame_uniforms.h.

#include "froxel/shaders/froxel_interface.h"

layout(location = SL_FROXEL_GRID_SIZE) uniform ivec3 grid_size;
layout(location = SL_FROXEL_GRID_DEPTH) uniform vec2 grid_depth;  // E, c

float slice_depth(float s) {
    float E = grid_depth.x, c = grid_depth.y;
    return c * exp(s / float(grid_size.z) * log(1.0 + E / c)) - c;
}

// The continuous slice coordinate of view depth d (its inverse): slice k spans [k, k + 1].
float depth_slice(float d, vec2 depth, int slices) {
    return float(slices) * log(1.0 + max(d, 0.0) / depth.y) / log(1.0 + depth.x / depth.y);
}

// The unit eye ray through the middle of column `xy`.
vec3 column_direction(vec2 xy) {
    vec2 ndc = 2.0 * (xy + 0.5) / vec2(grid_size.xy) - 1.0;
    vec4 far_point = frame.inverse_view_projection * vec4(ndc, 1.0, 1.0);
    return normalize(far_point.xyz / far_point.w - frame.camera_position.xyz);
}
