#version 450 core
// Environment light on translucent objects (Rohat §4.5.2, §5.3): a uniform surface sample with
// its share of the area, lit by the environment's SH9 irradiance E(n) (ibl/sh9.h), transmitted
// with the hemispherical average of Schlick's Fresnel, F0 + (1 − F0)/21.
#include "sss/shaders/subsurface_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "ibl/shaders/ibl.glsl"
#include "sss/shaders/subsurface.glsl"

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = SL_SSS_AREA_PER_SAMPLE) uniform float area_per_sample;  // world units²

out SampleData {
    vec3 position;
    vec3 normal;
    vec3 weight;
    float thickness_mm;
    float footprint_mm;  // radius of the patch the sample stands for
    float valid;
} sample_out;

void main() {
    vec3 n = normalize(normal);
    float f0 = (material.z - 1.0) / (material.z + 1.0);
    f0 *= f0;
    float transmitted = 1.0 - (f0 + (1.0 - f0) / 21.0);
    vec3 irradiance = frame.environment_options.z * sh9_irradiance(n);
    sample_out.position = position;
    sample_out.normal = n;
    sample_out.weight = irradiance * area_per_sample * material.y * material.y * transmitted;
    sample_out.thickness_mm = slab.x;  // no light direction to measure along: the thinnest slab
    sample_out.footprint_mm = sqrt(area_per_sample / SSS_PI) * material.y;
    sample_out.valid = 1.0;
    gl_Position = vec4(0.0);
}
