#version 450 core
// I_eye = I_obj·T(Z) + I_s (Nilsson eq. 2.7), then the preview tone map: exposure, Reinhard per
// channel, sRGB encoding (the same curve as core/image.cpp tone_map_srgb8).
#include "frame/shaders/frame_interface.h"
#include "gl/shaders/frame_uniforms.h"

layout(binding = SL_COMPOSITE_SURFACE_UNIT) uniform sampler2D surface_radiance;
layout(binding = SL_COMPOSITE_IN_SCATTERING_UNIT) uniform sampler2D in_scattering;

in vec2 uv;
layout(location = 0) out vec4 hdr;
layout(location = 1) out vec4 display;

vec3 encode_srgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, 12.92 * c, lessThanEqual(c, vec3(0.0031308)));
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec3 radiance = texelFetch(surface_radiance, pixel, 0).rgb + texelFetch(in_scattering, pixel, 0).rgb;
    hdr = vec4(radiance, 1.0);
    vec3 x = max(radiance * frame.display.x, 0.0);
    display = vec4(encode_srgb(x / (1.0 + x)), 1.0);
}
