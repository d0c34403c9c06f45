// The interface of froxel's passes (grid.glsl, inject.comp, temporal.comp, integrate.comp,
// apply.frag, atlas.comp), shared by froxel/froxel.cpp and the shaders (uniform locations,
// texture units, image units), so the two can never drift.
#ifndef SL_FROXEL_INTERFACE_H
#define SL_FROXEL_INTERFACE_H

// grid.glsl (every pass)
#define SL_FROXEL_GRID_SIZE 20
#define SL_FROXEL_GRID_DEPTH 21

// inject.comp
#define SL_FROXEL_INJECT_IMAGE 0
#define SL_FROXEL_INJECT_SAMPLES 0
#define SL_FROXEL_INJECT_JITTER 1
#define SL_FROXEL_INJECT_FRAME_OFFSET 2

// temporal.comp
#define SL_FROXEL_TEMPORAL_CURRENT_UNIT 0
#define SL_FROXEL_TEMPORAL_PREVIOUS_UNIT 1
#define SL_FROXEL_TEMPORAL_IMAGE 0
#define SL_FROXEL_TEMPORAL_HISTORY 3
#define SL_FROXEL_TEMPORAL_PREVIOUS_VIEW_PROJECTION 4
#define SL_FROXEL_TEMPORAL_PREVIOUS_CAMERA 5
#define SL_FROXEL_TEMPORAL_PREVIOUS_FORWARD 6
#define SL_FROXEL_TEMPORAL_PREVIOUS_DEPTH 7

// integrate.comp
#define SL_FROXEL_INTEGRATE_DENSITIES_UNIT 0
#define SL_FROXEL_INTEGRATE_IMAGE 0

// apply.frag
#define SL_FROXEL_APPLY_SURFACE_DEPTH_UNIT 0
#define SL_FROXEL_APPLY_INTEGRATED_UNIT 1

// atlas.comp
#define SL_FROXEL_ATLAS_VOLUME_UNIT 0
#define SL_FROXEL_ATLAS_IMAGE 0
#define SL_FROXEL_ATLAS_COLUMNS 0

#endif
