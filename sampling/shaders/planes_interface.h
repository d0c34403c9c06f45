// The interface of planes.vert and planes.frag, shared by sampling/planes.cpp and the shaders
// (uniform locations, texture units, vertex attributes), so the two can never drift.
#ifndef SL_PLANES_INTERFACE_H
#define SL_PLANES_INTERFACE_H

#define SL_PLANES_POSITION_ATTRIBUTE 0
#define SL_PLANES_DEPTH_ATTRIBUTE 1
#define SL_PLANES_SURFACE_DEPTH_UNIT 0
#define SL_PLANES_DZ 0
#define SL_PLANES_KNOWN_LIT 1
#define SL_PLANES_JITTER 2
#define SL_PLANES_CLASSIFY_MODE 3

#endif
