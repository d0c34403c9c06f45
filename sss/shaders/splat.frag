#version 450 core
// One splat's contribution to a shaded pixel x_o of the same object: F_t(θ_o)/π R_d(|x_s − x_o|)
// times what the sample carries (eq. 3.4, 4.6); with the multipole, the reflectance and
// transmittance profiles blended by the normals (Rohat listing 5.7). Blended additively.
#include "gl/shaders/frame_uniforms.h"
#include "sss/shaders/subsurface.glsl"

flat in vec3 splat_position;
flat in vec3 splat_normal;
flat in vec3 splat_weight;
flat in float splat_thickness_mm;
flat in float splat_level;
layout(location = 0) out vec4 scattered;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 p = texelFetch(eye_positions, pixel, 0);
    if (abs(p.w - object_id) > 0.5) {
        discard;  // light does not scatter between objects
    }
    vec3 n_o = texelFetch(eye_normals, pixel, 0).xyz;
    float r_mm = distance(p.xyz, splat_position) * material.y;
    vec2 coordinates = profile_coordinates(r_mm, splat_thickness_mm);
    vec3 profile = profile_at(profile_R, coordinates, splat_level);
    if (material.w > 0.5) {
        float c = dot(n_o, splat_normal);
        profile = 0.5 * (c + 1.0) * profile +
                  0.5 * (1.0 - c) * profile_at(profile_T, coordinates, splat_level);
    }
    vec3 v = normalize(frame.camera_position.xyz - p.xyz);
    float t_o = fresnel_transmittance(material.z, max(dot(n_o, v), 0.0));
    scattered = vec4(t_o / SSS_PI * profile * splat_weight, 1.0);
}
