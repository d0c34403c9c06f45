#pragma once
// Convex volumes (outward faces and their planes) and the mesh predicates the bounding volumes
// are built and verified with: a mesh's convex hull (CGAL), an axis-aligned box as a volume, a
// volume grown along its normals, inside by the winding number, triangle/box overlap. Below both
// the bounding volumes (beamtree/bounding_volumes.h) and the convex pieces (beamtree/pieces.h).

#include <vector>

#include <glm/mat4x4.hpp>

#include "beamtree/geometry.h"
#include "scenes/scene.h"

namespace sl::bt {

// A convex volume as outward faces and their planes. A flat volume (a convex polygon, e.g. the
// floor) has two faces, one per orientation, and zero volume.
struct ConvexVolume {
    std::vector<Polygon> faces;
    std::vector<Plane> planes;  // planes[i] is the plane of faces[i], normal outward
    bool flat = false;

    bool empty() const { return faces.empty(); }
    // True when p is inside by more than `margin` from every face plane. A flat volume has no
    // inside: with a negative margin, true when p is within -margin of the polygon.
    bool contains(const dvec3& p, double margin) const;
    ConvexVolume transformed(const glm::dmat4& transform) const;
    double volume() const;
};

// The hull of a mesh's vertices; max_planes > 0 keeps the 6 axis-aligned support planes plus the
// largest hull faces, up to max_planes planes in all.
ConvexVolume convex_hull(const Mesh& mesh, int max_planes);
// Inside by the winding number (robust for closed meshes): |w| > 1/2, so that a consistently
// inward (inside-out) closed mesh counts as the outward one does.
bool point_inside_mesh(const Mesh& mesh, const dvec3& p);
// Triangle/box overlap by the separating axis theorem; touching counts as overlapping.
bool triangle_overlaps_box(dvec3 v0, dvec3 v1, dvec3 v2, const dvec3& center, const dvec3& half);
ConvexVolume box_volume(const Box& box);
// The largest side of the bounds (at least 1e-30): the size tolerances are taken relative to.
double max_extent(const Bounds& bounds);
// The volume grown by `delta`: its face planes pushed out by delta, or, where that carries a sharp
// edge more than 8 delta away, its Minkowski sum with a cube of half-size delta. Still convex and
// enclosing it; a flat volume is returned as it is.
ConvexVolume inflated(const ConvexVolume& volume, double delta);

}  // namespace sl::bt
