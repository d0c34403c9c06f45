// The interface of the frame's own passes (shadow.vert, surface.vert/frag, shadow_blur.frag,
// composite.frag), shared by frame/renderer.cpp and the shaders (uniform
// locations, texture units). The units the renderer keeps bound for every pass are in
// gl/shaders/frame_uniforms.h.
#ifndef SL_FRAME_INTERFACE_H
#define SL_FRAME_INTERFACE_H

// surface.frag (the model and normal matrices are gl/shaders/object_uniforms.h)
#define SL_SURFACE_ALBEDO 2
#define SL_SURFACE_ROUGHNESS 3  // microfacet alpha
#define SL_SURFACE_F0 4
#define SL_SURFACE_TRANSLUCENT 5
#define SL_SURFACE_LIGHT_ONLY 6  // 1: the frame light's term alone (a further light, added)

// shadow_blur.frag
#define SL_SHADOW_BLUR_SOURCE_UNIT 0
#define SL_SHADOW_BLUR_DIRECTION 0
#define SL_SHADOW_BLUR_RADIUS 1

// composite.frag
#define SL_COMPOSITE_SURFACE_UNIT 0
#define SL_COMPOSITE_IN_SCATTERING_UNIT 1

#endif
