// The per-pixel region lists' storage (region_lists.glsl), shared by analytic/region_lists.cpp,
// which allocates and binds it, and the shaders.
#ifndef SL_REGION_LISTS_INTERFACE_H
#define SL_REGION_LISTS_INTERFACE_H

#define SL_REGION_COUNTS_BINDING 3
#define SL_REGION_CROSSINGS_BINDING 4
#define SL_REGION_LIST_SIZE 16  // crossings of one surface a pixel keeps

#endif
