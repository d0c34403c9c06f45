// The interface of the translucent passes (subsurface.glsl and the passes that include it,
// gbuffer.vert/frag, splat_points.vert, combine.frag), shared by sss/subsurface_pass.cpp and the
// shaders (uniform locations, texture units).
#ifndef SL_SUBSURFACE_INTERFACE_H
#define SL_SUBSURFACE_INTERFACE_H

// gbuffer.vert and gbuffer.frag (the model and normal matrices are gl/shaders/object_uniforms.h)
#define SL_SSS_VIEW_PROJECTION 5
#define SL_SSS_GBUFFER_OBJECT 6  // index + 1

// subsurface.glsl
#define SL_SSS_ROI 10
#define SL_SSS_GRID 11
#define SL_SSS_LIGHT_POSITION 12
#define SL_SSS_LIGHT_DIRECTION 13
#define SL_SSS_LIGHT_INTENSITY 14
#define SL_SSS_LIGHT_RANGE 15
#define SL_SSS_MATERIAL 16
#define SL_SSS_SLAB 17
#define SL_SSS_OBJECT 18
#define SL_SSS_FOOTPRINT 20

// splat_points.vert
#define SL_SSS_AREA_PER_SAMPLE 19

// Texture units of subsurface.glsl (and combine.frag: scatter at 0, eye positions at 3)
#define SL_SSS_LIGHT_POSITIONS_UNIT 0
#define SL_SSS_LIGHT_NORMALS_UNIT 1
#define SL_SSS_BACK_POSITIONS_UNIT 2
#define SL_SSS_EYE_POSITIONS_UNIT 3
#define SL_SSS_EYE_NORMALS_UNIT 4
#define SL_SSS_PROFILE_R_UNIT 5
#define SL_SSS_PROFILE_T_UNIT 6
#define SL_SSS_VISIBLE_AREA_UNIT 7
#define SL_SSS_SCATTER_UNIT 0

#endif
