#version 450 core
// Volume-based integration over the lit regions (Nilsson §3.2.2): each back face adds G(z), each
// front face subtracts it, into a float target with additive blending; faces behind the scene's
// surfaces are dropped (the lit regions never cross geometry, so in/out pairs go together).
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "gl/shaders/in_scattering.glsl"
#include "gl/shaders/view.glsl"
#include "gl/shaders/uncertain_interval.glsl"

layout(binding = 0) uniform sampler2D surface_depth;
// hybrid3: leave the lit parts inside the uncertain interval [a, b] to the ray marcher, whose
// samples cover the whole interval: ∫ over lit \ [a, b] = Σ ±(G(z) - G(clamp(z, a, b))).
layout(location = 0) uniform int exclude_interval;
in vec3 world_position;
layout(location = 0) out vec4 in_scattered;

void main() {
    vec3 origin = frame.camera_position.xyz;
    vec3 to_face = world_position - origin;
    float z = length(to_face);
    vec3 direction = to_face / z;
    // Faces behind the first surface do not count. Lit regions end exactly on surfaces, so
    // compare distances along the ray with a relative tolerance rather than depths.
    float surface = surface_distance(surface_depth, gl_FragCoord.xy);
    if (z > surface * (1.0 + 1e-4) + 1e-4) discard;
    // The ray's cone interval, up to the surface it hits (any z beyond it is clamped anyway).
    vec2 span = light_interval(origin, direction, 1e30);
    vec3 g = in_scattering_antiderivative(origin, direction, span, z);
    if (exclude_interval != 0) {
        vec2 excluded = uncertain_interval(ivec2(gl_FragCoord.xy));
        if (excluded.y > excluded.x) {
            g -= in_scattering_antiderivative(origin, direction, span,
                                              clamp(z, excluded.x, excluded.y));
        }
    }
    in_scattered = vec4(gl_FrontFacing ? -g : g, 0.0);
}
