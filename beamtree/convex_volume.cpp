#include "beamtree/convex_volume.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "core/check.h"
#include "core/error.h"

namespace sl::bt {

namespace {

Plane plane_of(const Polygon& face) {
    const dvec3 n = glm::normalize(area_vector(face));
    return {n, -glm::dot(n, centroid(face))};
}

// A polyhedron's faces with their planes.
ConvexVolume volume_of(const Polyhedron& polyhedron) {
    ConvexVolume volume;
    for (const Polygon& face : polyhedron.faces) {
        volume.faces.push_back(face);
        volume.planes.push_back(plane_of(face));
    }
    return volume;
}

}  // namespace

double max_extent(const Bounds& b) {
    const glm::vec3 e = b.extent();
    return std::max({double(e.x), double(e.y), double(e.z), 1e-30});
}

bool ConvexVolume::contains(const dvec3& p, double margin) const {
    if (planes.empty()) {
        return false;
    }
    if (flat) {
        // No interior: within -margin of the polygon's plane and inside its edges by margin.
        if (margin >= 0.0 || std::abs(planes[0].distance(p)) > -margin) {
            return false;
        }
        const Polygon& face = faces[0];
        for (size_t i = 0; i < face.size(); ++i) {
            const dvec3 edge = face.vertices[(i + 1) % face.size()] - face.vertices[i];
            const dvec3 outward = glm::normalize(glm::cross(edge, planes[0].normal));
            if (glm::dot(outward, p - face.vertices[i]) >= -margin) {
                return false;
            }
        }
        return true;
    }
    for (const Plane& plane : planes) {
        if (plane.distance(p) >= -margin) {
            return false;
        }
    }
    return true;
}

ConvexVolume ConvexVolume::transformed(const glm::dmat4& transform) const {
    ConvexVolume result;
    result.flat = flat;
    const bool mirrored = glm::determinant(glm::dmat3(transform)) < 0.0;
    for (const Polygon& face : faces) {
        std::vector<dvec3> vertices;
        for (const dvec3& v : face.vertices) {
            vertices.emplace_back(transform * glm::dvec4(v, 1.0));
        }
        if (mirrored) {
            std::reverse(vertices.begin(), vertices.end());
        }
        result.faces.emplace_back(std::move(vertices));
        result.planes.push_back(plane_of(result.faces.back()));
    }
    return result;
}

double ConvexVolume::volume() const {
    if (flat) {
        return 0.0;
    }
    Polyhedron p;
    p.faces = faces;
    return bt::volume(p);
}

ConvexVolume box_volume(const Box& box) {
    const dvec3 lo(box.min), hi(box.max);
    std::vector<Plane> planes = {{{1, 0, 0}, -hi.x}, {{-1, 0, 0}, lo.x}, {{0, 1, 0}, -hi.y},
                                 {{0, -1, 0}, lo.y}, {{0, 0, 1}, -hi.z}, {{0, 0, -1}, lo.z}};
    const double radius = 2.0 * std::max(glm::length(lo), glm::length(hi)) + 1.0;
    return volume_of(polyhedron_from_planes(planes, radius, 1e-12 * radius));
}

namespace {

// The plane of a set of coplanar points, sorted and without duplicates, from the points alone:
// through the first, the one farthest from it and the one farthest from their line, facing
// like `hint` (which it replaces where the three are degenerate).
Plane plane_of_corners(const std::vector<dvec3>& corners, const Plane& hint) {
    const dvec3 p0 = corners[0];
    dvec3 p1 = p0, p2 = p0;
    for (const dvec3& c : corners) {
        if (glm::distance(c, p0) > glm::distance(p1, p0)) {
            p1 = c;
        }
    }
    const dvec3 axis = glm::normalize(p1 - p0);
    const auto off_line = [&](const dvec3& c) { return glm::length(glm::cross(c - p0, axis)); };
    for (const dvec3& c : corners) {
        if (off_line(c) > off_line(p2)) {
            p2 = c;
        }
    }
    Plane plane;
    if (!Plane::through(p0, p1, p2, plane)) {
        return hint;
    }
    return glm::dot(plane.normal, hint.normal) < 0.0 ? plane.flipped() : plane;
}

// The faces of the convex hull of `points` (CGAL), coplanar facets merged, in a canonical order.
struct Merged {
    std::vector<dvec3> corners;  // sorted, distinct
    Plane plane;
    Polygon face;
};

std::vector<Merged> hull_faces(const std::vector<dvec3>& points, double tolerance) {
    using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
    using Point = Kernel::Point_3;
    std::vector<Point> cgal_points;
    cgal_points.reserve(points.size());
    for (const dvec3& p : points) {
        cgal_points.emplace_back(p.x, p.y, p.z);
    }
    CGAL::Surface_mesh<Point> hull;
    CGAL::convex_hull_3(cgal_points.begin(), cgal_points.end(), hull);

    // The facets in a canonical order: CGAL lists them (and starts each at a vertex) in an order
    // that follows heap addresses, so the same mesh gave differently rounded planes, merged in a
    // different order, from one build to the next within a process. Each facet starts at its
    // lexicographically smallest corner (keeping its winding) and the facets are sorted.
    std::vector<std::vector<dvec3>> facets;
    facets.reserve(hull.number_of_faces());
    for (const auto face : hull.faces()) {
        std::vector<dvec3>& corners = facets.emplace_back();
        for (const auto vertex : CGAL::vertices_around_face(hull.halfedge(face), hull)) {
            const Point& p = hull.point(vertex);
            corners.emplace_back(p.x(), p.y(), p.z());
        }
        std::rotate(corners.begin(),
                    std::min_element(corners.begin(), corners.end(), lexicographic_less),
                    corners.end());
    }
    std::sort(facets.begin(), facets.end(), [&](const auto& a, const auto& b) {
        return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(),
                                            lexicographic_less);
    });

    // One plane per hull facet, coplanar facets merged; remember the corners of each plane's
    // facets.
    std::vector<Plane> planes;
    std::vector<std::vector<dvec3>> plane_corners;
    for (const std::vector<dvec3>& corners : facets) {
        Plane plane;
        if (corners.size() < 3 || !Plane::through(corners[0], corners[1], corners[2], plane)) {
            continue;
        }
        auto same = std::find_if(planes.begin(), planes.end(), [&](const Plane& known) {
            return glm::dot(known.normal, plane.normal) > 1.0 - 1e-10 &&
                   std::abs(known.offset - plane.offset) <= tolerance;
        });
        if (same != planes.end()) {
            auto& corners_of_plane = plane_corners[size_t(same - planes.begin())];
            corners_of_plane.insert(corners_of_plane.end(), corners.begin(), corners.end());
        } else {
            planes.push_back(plane);
            plane_corners.push_back(corners);
        }
    }
    // Each merged plane and its face from its set of corners alone, and the planes in the order
    // of those sets: CGAL triangulates a coplanar region (a box side, a flat cap) one way or
    // another from build to build, so the first facet's plane, the summed facet areas and the
    // order of first appearance were not functions of the mesh.
    std::vector<Merged> merged(planes.size());
    for (size_t i = 0; i < planes.size(); ++i) {
        Merged& m = merged[i];
        m.corners = std::move(plane_corners[i]);
        std::sort(m.corners.begin(), m.corners.end(), lexicographic_less);
        m.corners.erase(std::unique(m.corners.begin(), m.corners.end()), m.corners.end());
        m.plane = plane_of_corners(m.corners, planes[i]);
        m.face = convex_polygon_on_plane(m.corners, m.plane, tolerance);
    }
    std::sort(merged.begin(), merged.end(), [](const Merged& a, const Merged& b) {
        return std::lexicographical_compare(a.corners.begin(), a.corners.end(), b.corners.begin(),
                                            b.corners.end(), lexicographic_less);
    });

    return merged;
}

}  // namespace

ConvexVolume convex_hull(const Mesh& mesh, int max_planes) {
    const Bounds bounds = mesh.bounds();
    const double extent = max_extent(bounds);
    const double tolerance = 1e-9 * extent;
    std::vector<dvec3> points(mesh.positions.begin(), mesh.positions.end());

    // A flat mesh (all vertices on one plane) has a polygon for its hull.
    size_t largest = 0;
    double largest_area = 0.0;
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
        const glm::uvec3 t = mesh.triangles[i];
        const double a =
            glm::length(glm::cross(points[t.y] - points[t.x], points[t.z] - points[t.x]));
        if (a > largest_area) {
            largest_area = a;
            largest = i;
        }
    }
    // Every mesh was validated when it was made (scenes/mesh.h: at least one triangle, indices in
    // range); the pieces are hulls of clipped triangles of such meshes.
    SL_CHECK(!mesh.triangles.empty());
    Plane support;
    const glm::uvec3 t = mesh.triangles[largest];
    SL_DCHECK(t.x < points.size() && t.y < points.size() && t.z < points.size());
    if (!Plane::through(points[t.x], points[t.y], points[t.z], support)) {
        fail("mesh has no triangle of non-zero area");
    }
    const bool flat = std::all_of(points.begin(), points.end(), [&](const dvec3& p) {
        return std::abs(support.distance(p)) <= tolerance;
    });
    ConvexVolume volume;
    if (flat) {
        Polygon up = convex_polygon_on_plane(points, support, tolerance);
        std::vector<dvec3> reversed(up.vertices.rbegin(), up.vertices.rend());
        Polygon down(std::move(reversed));
        volume.flat = true;
        volume.faces = {up, down};
        volume.planes = {plane_of(up), plane_of(down)};
        return volume;
    }

    std::vector<Merged> merged = hull_faces(points, tolerance);
    if (max_planes <= 0 || int(merged.size()) <= max_planes) {
        // The full hull: each face is the convex polygon of its facets' corners.
        for (Merged& m : merged) {
            if (!m.face.empty()) {
                volume.faces.push_back(std::move(m.face));
                volume.planes.push_back(m.plane);
            }
        }
        return volume;
    }
    // Conservative reduction: every kept plane supports the mesh, so their intersection still
    // encloses it; the axis-aligned support planes keep it bounded.
    const dvec3 lo(bounds.min), hi(bounds.max);
    std::vector<Plane> chosen = {{{1, 0, 0}, -hi.x}, {{-1, 0, 0}, lo.x}, {{0, 1, 0}, -hi.y},
                                 {{0, -1, 0}, lo.y}, {{0, 0, 1}, -hi.z}, {{0, 0, -1}, lo.z}};
    std::stable_sort(merged.begin(), merged.end(),
                     [](const Merged& a, const Merged& b) { return area(a.face) > area(b.face); });
    for (const Merged& m : merged) {
        const Plane& plane = m.plane;
        if (int(chosen.size()) >= max_planes) {
            break;
        }
        const bool axis_aligned = std::any_of(
            chosen.begin(), chosen.begin() + 6,
            [&](const Plane& c) { return glm::dot(c.normal, plane.normal) > 1.0 - 1e-10; });
        if (!axis_aligned) {
            chosen.push_back(plane);
        }
    }
    const double radius =
        2.0 * std::max(glm::length(dvec3(bounds.min)), glm::length(dvec3(bounds.max))) + extent;
    return volume_of(polyhedron_from_planes(chosen, radius, 1e-12 * radius));
}

bool point_inside_mesh(const Mesh& mesh, const dvec3& p) {
    // Generalised winding number: the solid angles of the triangles seen from p, summed
    // (Van Oosterom & Strackee); 1 inside a closed outward mesh, 0 outside.
    double solid_angle = 0.0;
    for (const glm::uvec3& t : mesh.triangles) {
        const dvec3 a = dvec3(mesh.positions[t.x]) - p;
        const dvec3 b = dvec3(mesh.positions[t.y]) - p;
        const dvec3 c = dvec3(mesh.positions[t.z]) - p;
        const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
        const double numerator = glm::dot(a, glm::cross(b, c));
        const double denominator =
            la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
        solid_angle += 2.0 * std::atan2(numerator, denominator);
    }
    return std::abs(solid_angle / (4.0 * std::numbers::pi)) > 0.5;
}

// Triangle/box overlap by the separating axis theorem (Akenine-Möller 2001). Touching counts as
// overlapping: only a strict gap separates.
bool triangle_overlaps_box(dvec3 v0, dvec3 v1, dvec3 v2, const dvec3& center, const dvec3& half) {
    v0 -= center;
    v1 -= center;
    v2 -= center;
    const dvec3 e[3] = {v1 - v0, v2 - v1, v0 - v2};
    auto separated_on = [&](const dvec3& axis) {
        const double p0 = glm::dot(v0, axis), p1 = glm::dot(v1, axis), p2 = glm::dot(v2, axis);
        const double r =
            half.x * std::abs(axis.x) + half.y * std::abs(axis.y) + half.z * std::abs(axis.z);
        return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
    };
    for (int i = 0; i < 3; ++i) {
        dvec3 axis(0.0);
        axis[i] = 1.0;
        if (separated_on(axis)) {
            return false;
        }
    }
    if (separated_on(glm::cross(e[0], e[1]))) {
        return false;
    }
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            dvec3 box_axis(0.0);
            box_axis[i] = 1.0;
            const dvec3 axis = glm::cross(box_axis, e[j]);
            if (glm::dot(axis, axis) > 0.0 && separated_on(axis)) {
                return false;
            }
        }
    }
    return true;
}

ConvexVolume inflated(const ConvexVolume& volume, double delta) {
    if (volume.flat || volume.empty()) {
        return volume;
    }
    // The face planes pushed out by delta: the same faces, each delta further out.
    std::vector<Plane> planes = volume.planes;
    double radius = 1.0;
    std::vector<dvec3> corners;  // distinct: each is on several faces
    for (const Polygon& face : volume.faces) {
        for (const dvec3& v : face.vertices) {
            radius = std::max(radius, 2.0 * glm::length(v) + 1.0);
            corners.push_back(v);
        }
    }
    std::sort(corners.begin(), corners.end(), lexicographic_less);
    corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
    for (Plane& plane : planes) {
        plane.offset -= delta;
    }
    const Polyhedron offset = polyhedron_from_planes(planes, radius, 1e-12 * radius);
    // At a sharp edge the offset runs delta / sin(angle / 2) away (52 times the part's size, on a
    // thin piece of the engine). Where a corner of the offset lies more than 8 delta from every
    // corner of the volume, the volume is grown instead as the hull of each corner moved to the
    // 8 corners of a cube of half-size delta (its Minkowski sum with the cube, within delta·√3):
    // tight everywhere, but with a small face at every edge and corner, which cost the tree
    // beams and the boundary meshes faces, so only there. (The boundary meshes' errors once
    // blamed on those faces were the analytic pass's interpolated crossings, docs/design.md §9.)
    bool runs_off = false;
    for (const Polygon& face : offset.faces) {
        for (const dvec3& w : face.vertices) {
            double nearest = std::numeric_limits<double>::max();
            for (const dvec3& v : corners) {
                nearest = std::min(nearest, glm::length(w - v));
            }
            runs_off |= nearest > 8.0 * delta;
        }
    }
    if (!runs_off) {
        return volume_of(offset);
    }
    std::vector<dvec3> points;
    dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
    for (const dvec3& v : corners) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
        for (int corner = 0; corner < 8; ++corner) {
            points.push_back(
                v + delta * dvec3(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1));
        }
    }
    const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) + 2.0 * delta;
    ConvexVolume result;
    for (Merged& m : hull_faces(points, 1e-9 * extent)) {
        if (!m.face.empty()) {
            result.faces.push_back(std::move(m.face));
            result.planes.push_back(m.plane);
        }
    }
    return result;
}

}  // namespace sl::bt
