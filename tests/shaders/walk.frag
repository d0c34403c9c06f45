#version 450 core
// Test pattern for tests/beamtree_gpu_test.cpp: pixel (x, y) walks the beam tree along the
// segment stored at (x, y) of `origins` (xyz origin, w t0) and `directions` (xyz unit
// direction, w t1) with the GLSL walk, writing the lengths it found lit (red), uncertain (green)
// and unlit (blue), and in alpha the pieces it reported (negative: the walk gave up).
#include "gl/shaders/frame_uniforms.h"
#include "beamtree/shaders/classify.glsl"
#include "beamtree/shaders/walk.glsl"
layout(binding = 0) uniform sampler2D origins;
layout(binding = 1) uniform sampler2D directions;
layout(location = 0) out vec4 result;
vec3 lengths = vec3(0.0);
float pieces = 0.0;
float last_end = -1.0;
void walk_piece(int region, float begin, float end) {
    lengths[region] += end - begin;
    // Pieces tile the segment: each begins where the last ended.
    if (last_end >= 0.0 && begin != last_end) pieces += 1000.0;
    last_end = end;
    pieces += 1.0;
}
void main() {
    vec4 o = texelFetch(origins, ivec2(gl_FragCoord.xy), 0);
    vec4 d = texelFetch(directions, ivec2(gl_FragCoord.xy), 0);
    bool finished = tree_walk(o.xyz, d.xyz, o.w, d.w);
    result = vec4(lengths, finished ? pieces : -pieces);
}
