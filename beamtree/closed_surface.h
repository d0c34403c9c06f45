#pragma once
// Which triangles of a closed mesh face out of its solid, so that the beam tree may insert only
// the ones a light sees from outside (docs/design.md §17).
//
// Why that is exact: let some connected components of the mesh be closed, consistently oriented
// surfaces that do not cut themselves, the light outside each one's solid, and keep every
// triangle of the other components. The segment from the light to a point p is blocked iff it
// crosses a triangle; if it does, take its first crossing. A triangle of another component is
// kept. A triangle of a closed component is where the segment passes from outside that component
// (the light is outside it, and an earlier crossing of the same component would be earlier) into
// it, so its outward normal faces the light. Hence the kept triangles block exactly the points
// all triangles block: a closed component's triangles facing away (about half) need not enter
// the tree. Components may overlap or cut each other (each is crossed in and out on its own); a
// component that cuts itself has regions of winding number -1 or 2, where crossings do not
// alternate, and keeps every triangle.

#include <cstdint>
#include <string>
#include <vector>

#include "scenes/mesh.h"

namespace sl::bt {

struct ClosedSurface {
    // One entry per triangle: +1 when its component is such a surface and its counter-clockwise
    // normal points out of the component's solid, -1 into it (a component wound inside out), 0
    // when its component is not such a surface (see `why_not`).
    std::vector<int8_t> outward;
    // Why the first component that is not such a surface is not; empty when every one is.
    std::string why_not;
    // Some triangle lies on a closed component.
    bool usable() const;
    // Every triangle does: the whole mesh is a closed surface.
    bool whole() const { return !outward.empty() && why_not.empty(); }
};

// Welds equal positions (flat-shaded meshes duplicate corners), splits the mesh into edge-
// connected components, and checks each for closedness, consistent winding, a non-zero volume and
// no self-intersection (CGAL), orienting each by the sign of its volume.
ClosedSurface closed_surface(const Mesh& mesh);

}  // namespace sl::bt
