// The interface of epipolar's passes (epipolar.glsl and every pass that includes it,
// minmax.comp, interpolate.comp, overlay.vert), shared by epipolar/epipolar.cpp and the shaders
// (uniform locations, texture and image units, storage-buffer bindings), so the two can never
// drift. Units 4 and 5 hold the frame's shadow map and moments, 7 the medium table.
#ifndef SL_EPIPOLAR_INTERFACE_H
#define SL_EPIPOLAR_INTERFACE_H

// Uniform locations of epipolar.glsl (and of grid in interpolate.comp and overlay.vert)
#define SL_EPIPOLAR_GRID 0
#define SL_EPIPOLAR_LIGHT_SCREEN 1
#define SL_EPIPOLAR_ARC 2
#define SL_EPIPOLAR_MAP_TEXELS 3
#define SL_EPIPOLAR_DEPTH_THRESHOLD 4
#define SL_EPIPOLAR_MAX_STEP 5
#define SL_EPIPOLAR_SAMPLES 6
#define SL_EPIPOLAR_MINMAX_LEVELS 7
#define SL_EPIPOLAR_DIRECT 8

// minmax.comp
#define SL_EPIPOLAR_TREE_LEVELS 0

// Texture units
#define SL_EPIPOLAR_SURFACE_DEPTH_UNIT 0
#define SL_EPIPOLAR_COORDINATES_UNIT 1
#define SL_EPIPOLAR_TREE_UNIT 2
#define SL_EPIPOLAR_SCATTERING_UNIT 2
#define SL_EPIPOLAR_LIGHT_DEPTH_UNIT 3
#define SL_EPIPOLAR_MARKS_UNIT 6

// Image units
#define SL_EPIPOLAR_COORDINATES_IMAGE 0
#define SL_EPIPOLAR_MARKS_IMAGE 1
#define SL_EPIPOLAR_TREE_IMAGE 2
#define SL_EPIPOLAR_SCATTERING_IMAGE 3

// Storage buffers
#define SL_EPIPOLAR_SLICES_BINDING 0
#define SL_EPIPOLAR_COUNTERS_BINDING 1
#define SL_EPIPOLAR_MARCHED_LIST_BINDING 2

#endif
