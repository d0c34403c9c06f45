#version 450 core
// Adds the scattered radiance of translucent pixels to the surface pass, attenuated by the
// medium like every surface (I_obj·T(Z), Nilsson eq. 2.7); blended additively.
#include "sss/shaders/subsurface_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
layout(binding = SL_SSS_SCATTER_UNIT) uniform sampler2D scatter;
layout(binding = SL_SSS_EYE_POSITIONS_UNIT) uniform sampler2D eye_positions;
layout(location = 0) out vec4 radiance;
void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 p = texelFetch(eye_positions, pixel, 0);
    if (p.w < 0.5) {
        discard;
    }
    float z = distance(frame.camera_position.xyz, p.xyz);
    radiance = vec4(texelFetch(scatter, pixel, 0).rgb * transmittance(z), 0.0);
}
