#pragma once
// Coplanar faces: a triangle mesh's triangles joined into the convex polygons they tile, for the
// beam tree's exact occluders (docs/design.md §4). A quad of two triangles goes into the tree as
// one polygon: its diagonal makes no plane through the light, so nothing behind it is cut along
// that plane, and the tree has one leaf where it had two. The union of the triangles is the
// polygon exactly (their shared edges cancel), so an opaque polygon blocks what they block.
//
// Triangles join across an edge that exactly two triangles share, walked in opposite directions
// (consistently wound, so also of one component of a closed surface and wound alike), when the
// new corner lies on the face's plane to 1e-9 of the mesh's extent (far below the tree's
// ε = 1e-6 of the light's range, for meshes of the scene's size) and the face stays strictly
// convex (no corner turning less than 1e-9 radians, so no straight corner: each edge of a face
// makes its own plane). Faces stop growing at kMaxCorners corners.

#include <cstdint>
#include <vector>

#include "scenes/mesh.h"

namespace sl::bt {

struct CoplanarFaces {
    static constexpr size_t kMaxCorners = 16;
    // Each face's corners, indices into the mesh's positions, counter-clockwise as its triangles.
    std::vector<std::vector<uint32_t>> faces;
    // Per face, one of its triangles (all are wound alike), as an index into mesh.triangles.
    std::vector<uint32_t> triangle;
};

// Every triangle of `mesh` in exactly one face; a degenerate triangle is a face of its own.
CoplanarFaces coplanar_faces(const Mesh& mesh);

}  // namespace sl::bt
