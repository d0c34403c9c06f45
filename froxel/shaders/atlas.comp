#version 450 core
// The buffer previewer's view of a froxel volume: its slices side by side, nearest first, left to
// right and bottom to top.

#include "froxel/shaders/froxel_interface.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = SL_FROXEL_ATLAS_VOLUME_UNIT) uniform sampler3D volume;
layout(rgba32f, binding = SL_FROXEL_ATLAS_IMAGE) uniform writeonly image2D atlas;
layout(location = SL_FROXEL_ATLAS_COLUMNS) uniform int columns;

void main() {
    ivec3 size = textureSize(volume, 0);
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 tile = texel / size.xy;
    int slice = tile.y * columns + tile.x;
    if (tile.x >= columns || slice >= size.z) {
        imageStore(atlas, texel, vec4(0.0));
        return;
    }
    imageStore(atlas, texel, vec4(texelFetch(volume, ivec3(texel % size.xy, slice), 0).rgb, 1.0));
}
