#pragma once
// The beam tree's geometry kernel, in double precision: oriented planes, convex polygons split by
// planes with a thickness ε (Nilsson §4.3), and convex polyhedra clipped by planes.

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

namespace sl::bt {

using glm::dvec3;

// The points x with dot(normal, x) + offset = 0; `normal` is unit length. distance() > 0 is the
// front side.
struct Plane {
    dvec3 normal{0.0, 0.0, 1.0};
    double offset = 0.0;

    double distance(const dvec3& p) const {
        return normal.x * p.x + normal.y * p.y + normal.z * p.z + offset;
    }
    Plane flipped() const { return {-normal, -offset}; }
    // Through a, b, c with the normal along (b - a) x (c - a). Returns false when degenerate.
    static bool through(const dvec3& a, const dvec3& b, const dvec3& c, Plane& plane);
};

// The corner of a box (its least and greatest corners) where dot(n, p) is least (ties: the least
// corner), and where it is greatest: what a plane with normal n meets first and last.
inline dvec3 least_corner(const std::pair<dvec3, dvec3>& box, const dvec3& n) {
    return {n.x >= 0.0 ? box.first.x : box.second.x, n.y >= 0.0 ? box.first.y : box.second.y,
            n.z >= 0.0 ? box.first.z : box.second.z};
}
inline dvec3 greatest_corner(const std::pair<dvec3, dvec3>& box, const dvec3& n) {
    return {n.x >= 0.0 ? box.second.x : box.first.x, n.y >= 0.0 ? box.second.y : box.first.y,
            n.z >= 0.0 ? box.second.z : box.first.z};
}

// Lexicographic order of points (x, then y, then z): a canonical order that does not depend on
// how the points were produced or stored.
inline bool lexicographic_less(const dvec3& a, const dvec3& b) {
    return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
}

// A hash of a position's exact bits, for maps keyed by welded positions (equal only when equal
// to the last bit).
struct PositionHash {
    size_t operator()(const dvec3& p) const {
        size_t h = std::bit_cast<uint64_t>(p.x);
        h = h * 0x9E3779B97F4A7C15ull ^ std::bit_cast<uint64_t>(p.y);
        h = h * 0x9E3779B97F4A7C15ull ^ std::bit_cast<uint64_t>(p.z);
        return h;
    }
};

// A convex planar polygon. Bit i of `on_split_plane` marks the edge from vertex i to i + 1 as
// lying on a plane through the light (created by splitting with a beam plane): attaching the
// polygon to the tree needs no new plane along such an edge. Edges past the 64th are never
// marked, which costs at most a redundant plane.
struct Polygon {
    std::vector<dvec3> vertices;
    uint64_t on_split_plane = 0;

    Polygon() = default;
    explicit Polygon(std::vector<dvec3> v) : vertices(std::move(v)) {}
    bool empty() const { return vertices.size() < 3; }
    // No vertices and no marked edges, keeping the storage for the next polygon.
    void clear() {
        vertices.clear();
        on_split_plane = 0;
    }
    size_t size() const { return vertices.size(); }
    bool edge_on_split_plane(size_t i) const { return i < 64 && (on_split_plane >> i & 1u); }
};

// Area vector: normal times area (Newell's method), exact for planar polygons of any winding.
dvec3 area_vector(const Polygon& polygon);
double area(const Polygon& polygon);
// area(polygon) > threshold for a convex polygon, usually decided by its first triangle: what the
// beam tree asks of every fragment it splits (a sliver thinner than its planes is dropped).
bool area_exceeds(const Polygon& polygon, double threshold);
dvec3 centroid(const Polygon& polygon);

// Where a polygon lies relative to a plane of thickness ε, without building any part of it.
enum class Side { front, back, straddling, coplanar };
Side side(const Polygon& polygon, const Plane& plane, double epsilon);

struct Split {
    Polygon front;           // may be empty
    Polygon back;            // may be empty
    bool coplanar = false;   // every vertex within ε of the plane (then both sides are empty)
    std::vector<dvec3> cut;  // when it straddles: the points where it meets the plane
};
// Splits a convex polygon by a plane of thickness ε (Nilsson §4.3): a polygon within ε of one
// side goes to that side whole; one that straddles the slab is cut exactly at the plane, so the
// parts conserve its area. The new edge is marked with `cut_on_split_plane`.
Split split(const Polygon& polygon, const Plane& plane, double epsilon,
            bool cut_on_split_plane = false);

// A sphere around a polygon's vertices, for deciding in one distance where a plane leaves the
// whole polygon (the usual case in a deep tree) before looking at its vertices.
struct Ball {
    dvec3 center{0.0};
    double radius = 0.0;  // the farthest vertex from the center, padded for round-off

    // Side::front or Side::back where every vertex is farther than ε on that side of the plane,
    // exactly where side() finds so vertex by vertex; Side::straddling where the ball cannot
    // tell (the polygon may still lie on one side).
    Side side(const Plane& plane, double epsilon) const {
        const double d = plane.distance(center);
        const double reach = radius + epsilon + 1e-12 * std::abs(plane.offset);  // + round-off
        return d > reach ? Side::front : d < -reach ? Side::back : Side::straddling;
    }
};
Ball bounding_ball(const Polygon& polygon);

// Which parts of a straddling polygon split_straddling() makes.
enum class Parts : uint8_t { both, front, back };

// side() and split() in one pass over the distances, for a fragment descending a tree: where the
// polygon lies, and when it straddles, its parts in `front` and `back` (empty ones on entry)
// exactly as split() cuts them; with `parts` front or back, only that one (the other stays empty:
// a part the caller would drop costs no cut). Where it lies on one side, `touching` (when given)
// receives the edges whose both ends lie within `coincident` of the plane, one bit per edge as
// Polygon::on_split_plane marks them (an edge shared with a polygon whose edge made the plane).
Side split_straddling(const Polygon& polygon, const Plane& plane, double epsilon,
                      bool cut_on_split_plane, Polygon& front, Polygon& back,
                      uint64_t* touching = nullptr, double coincident = 0.0,
                      Parts parts = Parts::both);

// The convex polygon spanned by points lying on `plane`, counter-clockwise around its normal,
// with duplicates (within epsilon) removed; empty when fewer than three remain.
Polygon convex_polygon_on_plane(std::vector<dvec3> points, const Plane& plane, double epsilon);

// A convex polyhedron as outward-facing convex faces (counter-clockwise seen from outside).
struct Polyhedron {
    std::vector<Polygon> faces;
    bool empty() const { return faces.size() < 4; }
};

// Keeps the part with distance <= 0 (the back side), closing it with a cap on the plane.
Polyhedron clip(const Polyhedron& polyhedron, const Plane& plane, double epsilon);
double volume(const Polyhedron& polyhedron);
// The polyhedron bounded by the given planes (outward normals), inside `bounds_radius` of the
// origin; faces of redundant planes are dropped.
Polyhedron polyhedron_from_planes(const std::vector<Plane>& planes, double bounds_radius,
                                  double epsilon);

}  // namespace sl::bt
