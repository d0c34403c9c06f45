#pragma once
// Maximal polygons (docs/design.md §9): the pieces of a region's boundary that lie on one plane, on
// one side of it, merged into the maximal polygons of their union and triangulated anew, so that
// the GPU draws a few large triangles where it drew a fan per cell face. A rasterizer pays per
// triangle and per block of pixels a triangle touches (llvmpipe shades 4×4 blocks), so a
// fragmented boundary costs far more than the pixels it covers.
//
// The input is conforming (beamtree/conforming.h: welded, T-vertices inserted): two pieces that
// share an edge share its vertices exactly, so the union's interior edges are the ones met once
// each way, and they cancel exactly, with no tolerance. The edges left bound the union (outer
// loops, holes, loops that touch at a corner) and keep every vertex on them, the T-vertices the
// faces on other planes meet there included, so the result meets its neighbours edge for edge
// as the pieces did. Those edges are the constraints of a 2D constrained Delaunay triangulation
// (CGAL, exact predicates) in the plane; a triangle is inside where it lies to the left of the
// constraints that bound its component.

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "beamtree/geometry.h"
#include "beamtree/regions.h"

namespace sl::bt {

struct MaximalTriangulation {
    std::vector<dvec3> vertices;        // the input positions on the union's boundary
    std::vector<glm::uvec3> triangles;  // counter-clockwise around the normal, as the input
    size_t boundary_edges = 0;          // edges left after the interior ones cancelled
};

// Triangulates the union of `polygons`: coplanar (within the tolerance their plane was grouped
// with), each wound counter-clockwise around `normal`, overlapping nowhere, conforming. Returns
// nothing where the input is not such a set as far as exact 2D predicates on its projection can
// tell, and then the caller keeps the polygons as they are:
//   - an edge met twice the same way (an overlap);
//   - two positions that project to one point, or boundary edges that cross or run through a
//     vertex in the projection (the triangulation would have to add a vertex the neighbours
//     lack);
//   - a triangle that would lie inside by one boundary edge and outside by another;
//   - a summed area that differs from the polygons' by more than 1e-9 of it.
// So a result is always a watertight replacement: its directed edges are the boundary edges plus
// interior edges met once each way.
std::optional<MaximalTriangulation> triangulate_union(const std::vector<const Polygon*>& polygons,
                                                      const dvec3& normal);

// Of directed edges between vertex ids (the edges of closed loops), those that no edge the other
// way meets, each as often as it is unmet, sorted; `most` gets the largest such count (more than
// one: loops that overlap). The interior edges of a union cancel this way; what is left is its
// outline, or, on a closed surface, its cracks.
using Edge = std::pair<uint32_t, uint32_t>;
std::vector<Edge> unmatched_edges(const std::vector<Edge>& edges, int* most = nullptr);

// The triangulation of closed loops of directed edges (indices into `positions`, interior on the
// left seen along `normal`): the part of triangulate_union after the cancellation, with the same
// refusals; its area is checked against the loops' own (shoelace over the edges).
std::optional<MaximalTriangulation> triangulate_outline(const std::vector<dvec3>& positions,
                                                        const std::vector<Edge>& edges,
                                                        const dvec3& normal);

// A face of a closed surface to triangulate: its polygon (conforming with the rest), the beam it
// bounds, and the plane and side it lies on (faces with the same `plane` are merged; -1: on no
// plane shared with another face).
struct PlanarFace {
    const Polygon* polygon = nullptr;
    uint32_t beam = 0;
    int32_t plane = -1;
};

struct MergeStats {
    size_t merged_planes = 0;     // planes (and sides) triangulated as maximal polygons
    size_t unmerged_planes = 0;   // refused (an overlap, or the triangulation), left fanned
    size_t flat_planes = 0;       // of zero area (welded flat), left as they are
    size_t dropped_vertices = 0;  // outline vertices two merged planes shared and did not need
    int rounds = 0;               // triangulations until none was refused
};

// The mesh of a closed, conforming surface (boundary.h's closed_boundary, BoundaryShape::maximal)
// with the faces on each plane and side merged into the maximal polygons of their union and the
// outline vertices only two merged planes share dropped (collinear within `tolerance`, the
// welding tolerance: each outline then runs a -> b where it ran a -> v -> b, and its neighbour
// b -> a, so they still meet edge for edge), each outline triangulated. Faces on no shared plane,
// faces of zero area and a set whose triangulation is refused stay fanned as they are, their
// vertices pinned; a refusal makes the outlines again without dropping its vertices, until none
// is refused (after kDroppingRounds, nothing is dropped).
RegionMesh maximal_polygon_mesh(const std::vector<PlanarFace>& faces, double tolerance,
                                MergeStats& stats);

}  // namespace sl::bt
