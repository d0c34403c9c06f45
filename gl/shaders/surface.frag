#version 450 core
// Surface pass: I_obj·T(Z) of Nilsson eq. 2.7 for Lambertian surfaces lit by the spot light
// (cone eq. 2.9, falloff eq. 2.8/2.13, shadow-map visibility) plus a constant ambient term.
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "gl/shaders/shadow.glsl"

layout(location = 2) uniform vec3 albedo;

in vec3 world_position;
in vec3 world_normal;
layout(location = 0) out vec4 surface_radiance;

void main() {
    vec3 n = normalize(world_normal);
    vec3 to_eye = frame.camera_position.xyz - world_position;
    if (!gl_FrontFacing) {
        n = -n;  // open surfaces (planes) are lit from the side the camera sees
    }
    vec3 to_light = frame.light_position.xyz - world_position;
    float r = length(to_light);
    vec3 l = to_light / r;
    float cos_theta = dot(n, l);

    vec3 irradiance = vec3(0.0);
    if (cos_theta > 0.0 && in_light_range(-to_light)) {
        // Normal offset: move the lookup point off the surface by a few shadow texels, measured
        // at this distance from the light, so that surfaces do not shadow themselves.
        float texel_world = 2.0 * r * tan(frame.light_cone.x) * frame.shadow.x;
        vec3 lookup = world_position + n * frame.shadow.z * texel_world;
        irradiance = frame.light_intensity.rgb * cone_factor(-to_light) * light_falloff(r) *
                     cos_theta * light_visibility(lookup);
    }
    vec3 radiance = albedo / PI * irradiance + albedo * frame.ambient.rgb;
    surface_radiance = vec4(radiance * transmittance(length(to_eye)), 1.0);
}
