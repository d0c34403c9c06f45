#version 450 core
// One direction of a separable Gaussian over the VSM moments, (2r+1) taps, σ = (r + 1) / 2.

#include "frame/shaders/frame_interface.h"

layout(binding = SL_SHADOW_BLUR_SOURCE_UNIT) uniform sampler2D source;
layout(location = SL_SHADOW_BLUR_DIRECTION) uniform ivec2 direction;
layout(location = SL_SHADOW_BLUR_RADIUS) uniform int radius;
layout(location = 0) out vec2 moments;
void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(source, 0);
    float sigma = 0.5 * float(radius + 1);
    vec2 sum = vec2(0.0);
    float weights = 0.0;
    for (int i = -radius; i <= radius; ++i) {
        float w = exp(-0.5 * float(i * i) / (sigma * sigma));
        sum += w * texelFetch(source, clamp(pixel + i * direction, ivec2(0), size - 1), 0).rg;
        weights += w;
    }
    moments = sum / weights;
}
