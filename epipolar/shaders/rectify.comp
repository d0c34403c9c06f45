#version 450 core
// Epipolar pass 3 (Chen et al. 2011 §4-5): each slice's line through the shadow map, resampled at
// map_texels evenly spaced texels (line_depth: the depth of the map's texel under each; level 0
// of the slice's min-max tree, read from the map itself), and levels 1 to 6 of the tree: one
// invocation per 64 texels, in order, each level's node written when its last texel is in
// (minmax.comp makes the levels above). Level l >= 1 of a row starts at column W - 2W / 2^l
// (W = map_texels, a multiple of 64).
layout(local_size_x = 64, local_size_y = 1) in;
#include "epipolar/shaders/epipolar_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "gl/shaders/scattering.glsl"
#include "gl/shaders/shadow.glsl"
#include "gl/shaders/view.glsl"
#include "analytic/shaders/in_scattering.glsl"
#include "epipolar/shaders/epipolar.glsl"

layout(rg32f, binding = SL_EPIPOLAR_TREE_IMAGE) uniform writeonly image2D tree;

void main() {
    int block = int(gl_GlobalInvocationID.x), slice = int(gl_GlobalInvocationID.y);
    if (block >= map_texels / 64 || slice >= grid.y) return;
    vec2 node[7];
    for (int l = 1; l <= 6; ++l) node[l] = vec2(1.0, 0.0);
    for (int i = 0; i < 64; ++i) {
        int texel = block * 64 + i;
        float depth = line_depth(texel, slice);
        for (int l = 1; l <= 6; ++l) {
            node[l] = vec2(min(node[l].x, depth), max(node[l].y, depth));
            if (((i + 1) & ((1 << l) - 1)) == 0) {
                if (l <= minmax_levels) {
                    imageStore(tree, ivec2(map_texels - ((2 * map_texels) >> l) + (texel >> l), slice),
                               vec4(node[l], 0.0, 0.0));
                }
                node[l] = vec2(1.0, 0.0);
            }
        }
    }
}
