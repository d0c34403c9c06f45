// One uniform block shared by C++ (gl/renderer.cpp fills it) and GLSL (every pass reads it), so
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

SL_UNIFORM_BLOCK(FrameUniforms, SL_FRAME_UNIFORMS_BINDING) {
    mat4 view_projection;  // camera: world -> clip
    mat4 inverse_view_projection;
    mat4 light_view_projection;  // shadow map: world -> light clip
    vec4 camera_position;        // xyz
    vec4 camera_forward;         // xyz unit viewing axis: eye depth = dot(p - camera, forward)
    vec4 light_position;         // xyz; w = near range
    vec4 light_direction;        // xyz unit axis; w = far range (the backplate)
    vec4 light_intensity;        // rgb
    vec4 light_cone;             // x = cone half-angle (rad), y = falloff width (rad, 0 = hard)
    vec4 medium_sigma_s;         // rgb; w = phase function (PhaseFunction's order)
    vec4 medium_sigma_t;         // rgb; w = model (0 simplified, 1 physical)
    vec4 medium_attenuation;     // x = a0, y = a1 (simplified model, Nilsson eq. 2.13);
                                 // z = 1 for an anisotropic phase function, w = g
    vec4 ambient;                // rgb incident radiance from every direction
    vec4 shadow;                 // x = 1 / map size, y = PCF radius in texels (0 = hard),
                                 // z = normal offset in texels, w = 1 for VSM
    vec4 display;                // x = exposure; yz = viewport size in pixels
}
SL_UNIFORM_BLOCK_END(frame)

#ifdef __cplusplus
}  // namespace sl::gl::shared
#endif

#endif
