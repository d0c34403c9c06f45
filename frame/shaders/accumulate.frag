#version 450 core
// One light's I_s added into the frame's (several lights, frame/renderer.cpp): the renderer blends
// this pass ONE, ONE.
#include "frame/shaders/frame_interface.h"

layout(binding = SL_ACCUMULATE_SOURCE_UNIT) uniform sampler2D source;

layout(location = 0) out vec4 result;

void main() {
    result = vec4(texelFetch(source, ivec2(gl_FragCoord.xy), 0).rgb, 0.0);
}
