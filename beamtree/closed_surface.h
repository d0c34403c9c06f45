#pragma once
// Which triangles of a closed mesh face out of its solid, so that the beam tree may insert only
// the ones a light sees from outside (docs/design.md §17).
//
// Why that is exact: let every connected component of the mesh be a closed, consistently
// oriented surface that does not cut itself, and the light lie outside every component's solid.
// The segment from the light to a point p is blocked iff it crosses a triangle; if it does,
// take its first crossing. There the segment passes from outside that triangle's component
// (the light is outside it, and an earlier crossing of the same component would be earlier)
// into it, so the triangle's outward normal faces the light. Hence the triangles whose outward
// side faces the light block exactly the points all triangles block: the others (about half)
// need not enter the tree. Components may overlap each other (each is crossed in and out on its
// own); a component that cuts itself has regions of winding number -1 or 2, where crossings
// do not alternate, and is refused.

#include <cstdint>
#include <string>
#include <vector>

#include "scenes/mesh.h"

namespace sl::bt {

struct ClosedSurface {
    // Empty when the mesh is not such a surface (see `why_not`); else one entry per triangle:
    // +1 when its counter-clockwise normal points out of its component's solid, -1 into it (a
    // component wound inside out).
    std::vector<int8_t> outward;
    std::string why_not;
    bool usable() const { return !outward.empty(); }
};

// Welds equal positions (flat-shaded meshes duplicate corners), splits the mesh into edge-
// connected components, checks each for closedness, consistent winding, a non-zero volume and
// no self-intersection (CGAL), and orients each by the sign of its volume.
ClosedSurface closed_surface(const Mesh& mesh);

}  // namespace sl::bt
