#pragma once
// Regions as surfaces (docs/design.md §9): the closed, outward surface of the union of one region
// type's pieces. A face of a lit piece that another lit piece lies beyond contributes +G(z) on
// one side and -G(z) on the other at the same points: only the faces where the region meets
// another type, or the outside, are kept, so an eye ray crosses the surface twice per maximal
// interval of that type instead of at every cell it passes.
//
// Every face of a piece lies on a plane the tree knows: the influence volume's near or far
// range, the leaf's occluder or stopper, or the plane of a split node on the piece's path. The
// faces are grouped by that plane (groups whose planes coincide within 3e-2 ε merged: the same
// plane is inserted once per polygon that has the edge), and on each plane the faces from its
// front and its back cancel by signed multiplicity: an overlap of a face from either side is
// removed from both, once (beamtree/boundary.cpp, cancel). What is left is the boundary.

#include <vector>

#include "beamtree/maximal_polygons.h"
#include "beamtree/regions.h"

namespace sl::bt {

struct BoundaryFace {
    uint32_t beam = 0;  // the beam of the piece it bounds
    Polygon polygon;    // outward from the region
    // The plane it lies on and its side: 2 g + 1 on the front of plane group g, 2 g behind it;
    // -1 on none shared with another face (a sliver kept whole, a crack's fill).
    int32_t plane = -1;
};

struct BoundaryStats {
    size_t piece_faces = 0;  // faces of the region's pieces
    size_t kept_whole = 0;   // nothing on the other side of its plane covers it
    size_t split = 0;        // partitioned: part of it inside the region on both sides
    size_t dropped = 0;      // the region on both sides everywhere
    size_t faces = 0;        // boundary polygons
    size_t cracks = 0;       // ε-wide cracks the mesh closed (boundary_mesh)
    MergeStats merge;        // boundary_mesh with maximal polygons (beamtree/maximal_polygons.h)
    size_t triangles = 0;
    double ms = 0.0;  // building them
};

// How boundary_mesh triangulates: each face fanned on its own, or the faces on one plane and
// side merged into the maximal polygons of their union first (beamtree/maximal_polygons.h).
enum class BoundaryShape { fragments, maximal };

// The boundary polygons of one region type (lit or uncertain: the unlit rest is every point
// outside both), outward, before they are made conforming.
std::vector<BoundaryFace> boundary_faces(const BeamTree& tree, const Regions& regions,
                                         Region region, BoundaryStats* stats = nullptr);

// The same made conforming (beamtree/conforming.h: welded, T-vertices inserted) and closed:
// where the two sides of a shared plane, cut from the tree independently, disagree by less than
// its ε, the crack is filled (its cycle of unmatched edges as one more polygon), so that every
// directed edge is met by its opposite.
std::vector<BoundaryFace> closed_boundary(const BeamTree& tree, const Regions& regions,
                                          Region region, BoundaryStats* stats = nullptr);

// The closed boundary as a triangle mesh for the GPU (RegionMesh: float positions, outward
// triangles and the beam of each; a merged polygon's triangles carry the beam of one of its
// faces). Watertight in either shape: a plane whose merge is refused keeps its faces fanned.
RegionMesh boundary_mesh(const BeamTree& tree, const Regions& regions, Region region,
                         BoundaryStats* stats = nullptr,
                         BoundaryShape shape = BoundaryShape::maximal);

}  // namespace sl::bt
