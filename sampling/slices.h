#pragma once
// Sampling planes (Dobashi et al. 2000, Nilsson §3.1): planes parallel to the image plane every
// `dz` of eye depth, each clipped on the CPU to the light's influence pyramid before it is
// rasterized (Mitchell 2004, Nilsson figure 3.6), so that no fragment is spent where the light
// cannot reach.

#include <vector>

#include "beamtree/geometry.h"
#include "scenes/scene.h"

namespace sl::sampling {

struct Slice {
    double depth = 0.0;   // eye depth of the plane: dot(p - camera, forward)
    bt::Polygon polygon;  // the plane's part inside the influence pyramid, world space
};

// Slice k samples the slab [k dz, (k + 1) dz) of eye depth at its middle, z_k = (k + ½) dz (the
// midpoint rule); only slices that meet the pyramid are returned, nearest first. Slabs are
// aligned to the camera, so slices do not crawl when the light moves. Throws sl::Error for a
// dz that is not positive and finite, or one that would make more than `max_slices`.
std::vector<Slice> influence_slices(const Camera& camera, const SpotLight& light, double dz,
                                    size_t max_slices = 100000);

// Makes a set of convex polygons that tile part of one plane conforming: every vertex of one that
// lies on an edge of another (a T-junction, left by the beam tree's splits) is inserted into that
// edge. Rasterized with the same vertices on both sides of every edge, the pieces then cover each
// pixel exactly once (no cracks, no double hits).
void remove_t_junctions(const std::vector<bt::Polygon*>& pieces, double tolerance);

// The eye-depth range [near, far] the influence pyramid spans (near may be negative when the
// pyramid reaches behind the camera).
std::pair<double, double> influence_depth_range(const Camera& camera, const SpotLight& light);

}  // namespace sl::sampling
