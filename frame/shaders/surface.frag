#version 450 core
// Surface pass: I_obj·T(Z) of Nilsson eq. 2.7 for Lambertian surfaces lit by the spot light
// (cone eq. 2.9, falloff eq. 2.8/2.13, shadow-map visibility) plus a constant ambient term; with
// an environment, the spot light's microfacet specular and the environment's light (ibl.glsl).
// With several lights, once per light, each further one adding its own term (light_only).
#include "frame/shaders/frame_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "gl/shaders/shadow.glsl"
#include "ibl/shaders/ibl.glsl"

layout(location = SL_SURFACE_ALBEDO) uniform vec3 albedo;
layout(location = SL_SURFACE_ROUGHNESS) uniform float roughness;  // microfacet α
layout(location = SL_SURFACE_F0) uniform vec3 f0;
// x > 0.5: translucent (sss/subsurface_pass.h adds the scattered light; here only the specular
// term, always, and the ambient light reflected with the profile's total reflectance in yzw).
layout(location = SL_SURFACE_TRANSLUCENT) uniform vec4 translucent;
// 1 for a scene's further lights: this light's term alone, added to the first light's pass (the
// ambient and environment light come with the first).
layout(location = SL_SURFACE_LIGHT_ONLY) uniform int light_only;

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
    vec3 l = -light_travel(-to_light);
    float cos_theta = dot(n, l);

    vec3 irradiance = vec3(0.0);
    vec3 v = normalize(to_eye);
    bool is_translucent = translucent.x > 0.5;
    vec3 radiance = light_only != 0 ? vec3(0.0) : (is_translucent ? translucent.yzw : albedo) * frame.ambient.rgb;
    if (cos_theta > 0.0 && in_light_range(-to_light)) {
        // Normal offset: move the lookup point off the surface by a few shadow texels, measured
        // at this distance from the light (parallel beams: the box's width), so that surfaces
        // do not shadow themselves.
        float span = light_parallel() ? 2.0 * frame.light_cone.w : 2.0 * r * tan(frame.light_cone.x);
        float texel_world = span * frame.shadow.x;
        vec3 lookup = world_position + n * frame.shadow.z * texel_world;
        irradiance = frame.light_intensity.rgb * cone_factor(-to_light) *
                     light_attenuation(-to_light) * cos_theta * light_visibility(lookup);
        radiance += albedo / PI * irradiance;
        if (environment_on() || is_translucent) {
            radiance += irradiance / cos_theta * spot_specular(n, v, l, roughness, f0);
        }
    }
    if (environment_on() && light_only == 0) {
        radiance += environment_radiance(n, v, albedo, roughness, f0);
    }
    surface_radiance = vec4(radiance * transmittance(length(to_eye)), 1.0);
}
