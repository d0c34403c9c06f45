#version 450 core
// Epipolar pass 4 (Chen et al. 2011 §5; Yusov 2013 §3.3): the levels of every slice's 1D min-max
// tree above 6 (rectify.comp makes 0 to 6), one invocation per slice, each level's texels the
// minimum and maximum of their two children. Level l >= 1 of a row starts at column W - 2W / 2^l
// (W = map_texels).

#include "epipolar/shaders/epipolar_interface.h"

layout(local_size_x = 64, local_size_y = 1) in;
layout(location = SL_EPIPOLAR_TREE_LEVELS) uniform ivec3 levels;  // x = the top level, y = map_texels, z = slices
layout(rg32f, binding = SL_EPIPOLAR_TREE_IMAGE) uniform image2D tree;

int level_start(int l) {
    return levels.y - ((2 * levels.y) >> l);
}

void main() {
    int slice = int(gl_GlobalInvocationID.x);
    if (slice >= levels.z) return;
    for (int l = 7; l <= levels.x; ++l) {
        for (int i = 0; i < (levels.y >> l); ++i) {
            int below = level_start(l - 1) + 2 * i;
            vec2 a = imageLoad(tree, ivec2(below, slice)).rg, b = imageLoad(tree, ivec2(below + 1, slice)).rg;
            imageStore(tree, ivec2(level_start(l) + i, slice), vec4(min(a.x, b.x), max(a.y, b.y), 0.0, 0.0));
        }
    }
}
