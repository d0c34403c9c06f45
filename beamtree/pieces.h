#pragma once
// Convex pieces of a mesh for tight outer volumes (docs/design.md §4.1). A wall with openings is
// one mesh whose convex hull covers its windows; the beam tree then calls every shaft through
// them uncertain. Here the mesh is cut into cells along planes through its own vertex
// coordinates (a window's edges among them), each cell keeps the triangles clipped to it, and
// neighbouring cells are merged while the hull of the merged piece holds no more empty space
// than its parts did. The space is measured on a voxel grid of the mesh: a voxel is empty when
// it touches no triangle and is reachable from outside the grid without crossing one, so cracks
// narrower than a voxel (T-junctions, a missing face's seam) neither leak nor matter, and open
// meshes are handled as closed ones are.
//
// Soundness needs only that the pieces' hulls cover every triangle, which the clipping gives
// whatever the merge decides: a ray that meets the mesh meets a triangle, hence a piece.

#include <vector>

#include "beamtree/convex_volume.h"
#include "beamtree/geometry.h"
#include "scenes/mesh.h"

namespace sl::bt {

struct PieceOptions {
    int voxels = 48;       // voxels along the mesh's longest side
    int max_cuts = 10;     // cut planes per axis (vertex coordinates, thinned evenly beyond)
    int max_pieces = 32;   // pieces are merged further (least empty space first) beyond it
    double slack = 0.02;   // a merge may add this fraction of its hull's voxels as empty ...
    int slack_voxels = 2;  // ... or this many, whichever is larger
};

struct Pieces {
    std::vector<Mesh> parts;      // each piece as its convex hull's faces (covering its triangles)
    int cells = 0;                // non-empty cells before merging
    int empty_voxels_whole = 0;   // empty voxels inside the hull of the whole mesh
    int empty_voxels_pieces = 0;  // summed over the pieces' hulls
    bool whole = false;           // the mesh's own hull was tight: one piece, the mesh itself
};

// The pieces of a mesh (its local frame). Deterministic: the same mesh gives the same pieces.
Pieces convex_pieces(const Mesh& mesh, const PieceOptions& options = {});

// Empty voxels (see above) of `mesh` that lie inside each convex volume, for tests and reports.
std::vector<int> empty_voxels_inside(const Mesh& mesh, const std::vector<ConvexVolume>& hulls,
                                     const PieceOptions& options = {});

// The mesh made closed where it only looks open: vertices within `tolerance` welded, and each
// edge that another edge runs along (a T-junction, where a face was cut without its
// neighbour) split at the vertices on it. The geometry is unchanged, so an inner volume verified
// against the result is inside the original. A real hole (a missing face) stays open: capping
// it would let an inner volume claim shadow where the light passes.
Mesh welded(const Mesh& mesh, double tolerance);

}  // namespace sl::bt
