#pragma once
// Conforming polygon sets for rasterization. The beam tree's splits cut one side of an edge and
// not the other, leaving T-junctions: a vertex of one polygon in the middle of another's edge.
// Rasterized, the two sides of such an edge are different float segments, so a pixel centre near
// it can be covered twice or not at all; the analytic pass then counts a face of an entry/exit
// pair without the other. Inserting the T-vertices makes both sides the same sequence of
// segments (no cracks, no double hits), provided each polygon is then triangulated without
// (near-)zero-area triangles (fan_triangles): a fan from a corner has one for every collinear
// vertex on that corner's edges, and its interpolated depth is ill-conditioned.

#include <cstdint>
#include <vector>

#include "beamtree/geometry.h"

namespace sl::bt {

// Makes a set of convex polygons conforming. First welds: positions chained within `tolerance`
// of each other become one (the tree computes a corner shared by several cells once per cell,
// and float can round the copies apart); welded-away edges and vertices go. Then inserts, into
// every edge, the vertices that lie within `tolerance` of its interior, in order along it. The
// polygons may lie on any planes (here the faces of region pieces; the sampling planes' pieces,
// all on one plane, use the cheaper 2D sampling::remove_t_junctions). A point hierarchy over the
// distinct positions finds those near each edge. Edge flags (`on_split_plane`) are cleared:
// they no longer line up with the edges.
void make_conforming(const std::vector<Polygon*>& polygons, double tolerance);

// True when some vertex of the polygon lies (within a sine of 1e-4) on the line through its
// neighbours, as inserted T-vertices do.
bool has_collinear_vertex(const Polygon& polygon);

// The triangles of a convex polygon for rasterization, calling emit(a, b, c) with its winding.
// A fan from the first corner (n - 2 triangles) when no vertex is collinear with its neighbours;
// otherwise a fan around the centroid, vertex index n (n triangles, each on an edge of the
// polygon, so none of zero area). Returns whether index n was used.
template <class Emit>
bool fan_triangles(const Polygon& polygon, Emit&& emit) {
    const auto n = uint32_t(polygon.size());
    if (!has_collinear_vertex(polygon)) {
        for (uint32_t i = 1; i + 1 < n; ++i) {
            emit(0, i, i + 1);
        }
        return false;
    }
    for (uint32_t i = 0; i < n; ++i) {
        emit(n, i, (i + 1) % n);
    }
    return true;
}

}  // namespace sl::bt
