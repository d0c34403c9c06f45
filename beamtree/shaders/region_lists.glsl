// Per-pixel lists of where each eye ray crosses the beam tree's region surfaces (the boundaries
// of the lit and of the uncertain union, beamtree/boundary.h), written by region_lists.frag,
// read by the hybrids (analytic/region_lists.h): a signed distance per crossing, + where the ray
// enters the region (a front face: the surfaces face outward), - where it leaves. A ray crosses
// each surface a few times; a pixel with more than REGION_LIST_SIZE crossings of one surface
// overflows, and its readers fall back to the tree itself (beamtree/shaders/classify.glsl).

#include "beamtree/shaders/region_lists_interface.h"
const int REGION_LIST_SIZE = SL_REGION_LIST_SIZE;

layout(std430, binding = SL_REGION_COUNTS_BINDING) buffer RegionCounts { uint region_counts[]; };
layout(std430, binding = SL_REGION_CROSSINGS_BINDING) buffer RegionCrossings {
    float region_crossings[];
};

// Slot of (pixel, surface): surface 0 the lit union, 1 the uncertain one.
int region_slot(ivec2 pixel, int surface) {
    return (pixel.y * int(frame.display.y) + pixel.x) * 2 + surface;
}

// How many crossings the pixel's list holds, or -1 when it overflowed.
int region_crossing_count(ivec2 pixel, int surface) {
    uint n = region_counts[region_slot(pixel, surface)];
    return n > uint(REGION_LIST_SIZE) ? -1 : int(n);
}

float region_crossing(ivec2 pixel, int surface, int i) {
    return region_crossings[region_slot(pixel, surface) * REGION_LIST_SIZE + i];
}

// Inside the surface's region at distance t along the pixel's eye ray: the crossings before t,
// on top of where the ray starts (inside when it leaves more often than it enters). Only for a
// list that did not overflow.
bool inside_region(ivec2 pixel, int surface, int count, float t) {
    int depth = 0, before = 0;
    for (int i = 0; i < count; ++i) {
        float d = region_crossing(pixel, surface, i);
        depth -= d > 0.0 ? 1 : -1;  // at t = 0: exits minus entries
        if (abs(d) < t) before += d > 0.0 ? 1 : -1;
    }
    return depth + before > 0;
}
