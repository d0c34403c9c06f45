// The interface of march.frag and march_resolve.frag, shared by sampling/march.cpp and the
// shaders (uniform locations, texture units), so the two can never drift.
#ifndef SL_MARCH_INTERFACE_H
#define SL_MARCH_INTERFACE_H

// march.frag
#define SL_MARCH_SURFACE_DEPTH_UNIT 0
#define SL_MARCH_SAMPLES 0
#define SL_MARCH_JITTER 1
#define SL_MARCH_CLIP_MODE 2
#define SL_MARCH_BUFFER_SCALE 3
#define SL_MARCH_ATTENUATION 4
#define SL_MARCH_OPTICAL_THICKNESS 5
#define SL_MARCH_ANIMATE_PHASE 6
#define SL_MARCH_TIME 7
#define SL_MARCH_INTERVAL_MODE 8
#define SL_MARCH_ADAPTIVE 9
#define SL_MARCH_CLIP_PLANES 10  // vec4[6]

// march_resolve.frag
#define SL_RESOLVE_SURFACE_DEPTH_UNIT 0
#define SL_RESOLVE_MARCHED_UNIT 1
#define SL_RESOLVE_BUFFER_SCALE 0
#define SL_RESOLVE_BLUR 1

#endif
