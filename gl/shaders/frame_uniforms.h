// One uniform block shared by C++ (frame/renderer.cpp fills it) and GLSL (every pass reads it), so
// the two can never drift: std140, vec4 and mat4 members only (no padding rules to get wrong).
#ifndef SL_FRAME_UNIFORMS_H
#define SL_FRAME_UNIFORMS_H

#ifdef __cplusplus
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
namespace sl::gl::shared {
using mat4 = glm::mat4;
using vec4 = glm::vec4;
#define SL_UNIFORM_BLOCK(name, slot) struct alignas(16) name
#define SL_UNIFORM_BLOCK_END(instance) ;
#else
#define SL_UNIFORM_BLOCK(name, slot) layout(std140, binding = slot) uniform name
#define SL_UNIFORM_BLOCK_END(instance) instance;
#endif

#define SL_FRAME_UNIFORMS_BINDING 0
// Texture units the renderer keeps bound through the surface and volume passes (methods use
// others): the depth-compare shadow map and the VSM moments.
#define SL_SHADOW_MAP_UNIT 4
#define SL_SHADOW_MOMENTS_UNIT 5
// The surface pass's image-based lighting: the prefiltered cube map and the split-sum DFG table.
#define SL_ENVIRONMENT_UNIT 8
#define SL_DFG_UNIT 9
#define SL_MAX_ENVIRONMENT_LEVELS 12

SL_UNIFORM_BLOCK(FrameUniforms, SL_FRAME_UNIFORMS_BINDING) {
    mat4 view_projection;  // camera: world -> clip
    mat4 inverse_view_projection;
    mat4 light_view_projection;  // shadow map: world -> light clip
    vec4 camera_position;        // xyz
    vec4 camera_forward;         // xyz unit viewing axis: eye depth = dot(p - camera, forward)
    vec4 light_position;         // xyz; w = near range
    vec4 light_direction;        // xyz unit axis; w = far range (the backplate)
    vec4 light_intensity;        // rgb
    vec4 light_cone;             // x = cone half-angle (rad), y = falloff width (rad, 0 = hard),
                                 // z = 1 for a pyramid (SpotShape), 0 for a cone; w > 0:
                                 // parallel beams (a directional light) in a box of this
                                 // half-width, light_position on its entry plane (near = 0),
                                 // light_intensity the irradiance
    vec4 medium_sigma_s;         // rgb; w = phase function (PhaseFunction's order)
    vec4 medium_sigma_t;         // rgb; w = model (0 simplified, 1 physical)
    vec4 medium_attenuation;     // x = a0, y = a1 (simplified model, Nilsson eq. 2.13);
                                 // z = 1 for an anisotropic phase function, w = g
    vec4 ambient;                // rgb incident radiance from every direction
    vec4 shadow;                 // x = 1 / map size, y = PCF radius in texels (0 = hard),
                                 // z = normal offset in texels, w = 1 for VSM
    vec4 display;                // x = exposure; yz = viewport size in pixels
    // Image-based lighting (ibl/, ibl/shaders/ibl.glsl): x = 1 when on, y = shading (0 Moschos
    // algorithms 7-8, 1 split-sum), z = prefiltered levels, w = 1 for the cone (figure 3.24)
    // chain, 0 for the importance-sampled one.
    vec4 environment;
    vec4 environment_options;  // x = 1 to draw the skybox, y = distribution (0 Beckmann, 1 GGX),
                               // z = intensity (radiance scale)
    vec4 environment_sh9[9];   // rgb: L_lm in ibl/sh9.h's order and axes
    // Per cone level: x = roughness (figure 3.24), y = tan² θ, z = tan² θ / α² (D(n)·π tan² θ).
    vec4 environment_levels[SL_MAX_ENVIRONMENT_LEVELS];
}
SL_UNIFORM_BLOCK_END(frame)

#ifdef __cplusplus
}  // namespace sl::gl::shared
#endif

#endif
