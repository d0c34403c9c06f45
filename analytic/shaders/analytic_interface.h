// The interface of the analytic passes (in_scattering.glsl's medium table, face_distance.glsl's
// corners, regions*.frag, region_lists*.frag), shared by analytic/*.cpp, lightvolume/ and
// epipolar/ and the shaders (uniform locations, texture units, storage buffers).
#ifndef SL_ANALYTIC_INTERFACE_H
#define SL_ANALYTIC_INTERFACE_H

// in_scattering.glsl: the medium table (analytic/gpu_tables.h)
#define SL_MEDIUM_TABLE_UNIT 7

// face_distance.glsl: each region triangle's corners (analytic/region_faces.h)
#define SL_FACE_CORNERS_BINDING 5

// regions.frag, regions_walk.frag, region_lists_walk.frag
#define SL_ANALYTIC_SURFACE_DEPTH_UNIT 0

// regions_eye.frag
#define SL_REGIONS_EYE_WINDINGS 0

// region_lists.frag and region_lists_walk.frag
#define SL_REGION_LISTS_SURFACE 0        // 0 lit, 1 uncertain
#define SL_REGION_LISTS_MARK_SURFACES 0  // bit 0 lit, bit 1 uncertain

#endif
