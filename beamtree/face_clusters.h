#pragma once
// Face clusters: an object's exact faces cut into small groups of spatial neighbours, each with
// the box around its corners, so that the beam tree can leave out the rest of a group once its
// box lies wholly behind what is in (docs/design.md §4): the object's own box asks that of the
// whole object, which a building (one object, its inside behind its roof and walls) never
// answers yes to while it is being built.
//
// The groups are the leaves of a median split of the faces' centroids along the longest axis of
// their bounds, down to at most `per_cluster` faces (and at least half as many, of a mesh that
// has that many): compact where the faces are, whatever the mesh's order of them.

#include <cstdint>
#include <utility>
#include <vector>

#include "beamtree/geometry.h"

namespace sl::bt {

// The clusters' size in the library's objects (VolumeLibrary), chosen by measurement
// (results/beamtree.md).
constexpr size_t kFacesPerCluster = 64;

struct FaceClusters {
    // Per face, its cluster: an index into `bounds`.
    std::vector<uint32_t> cluster;
    // Per cluster, the least and greatest corners of the box around its faces' corners.
    std::vector<std::pair<dvec3, dvec3>> bounds;
    // The faces by cluster, each cluster's in increasing order: cluster c's are
    // faces[first[c]] to faces[first[c + 1] - 1] (`first` has one entry more than `bounds`).
    std::vector<uint32_t> faces;
    std::vector<uint32_t> first;
};

// Every face of `faces` in exactly one cluster of at most `per_cluster` (≥ 1) faces; faces
// without corners count as faces at the origin.
FaceClusters cluster_faces(const std::vector<Polygon>& faces, size_t per_cluster);

}  // namespace sl::bt
