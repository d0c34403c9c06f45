#include "beamtree/maximal_polygons.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <bit>
#include <cmath>
#include <unordered_map>
#include <utility>

#include <glm/geometric.hpp>

namespace sl::bt {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<uint32_t, Kernel>;
// Face label: 0 not yet known, +1 inside the union, -1 outside.
using FaceBase =
    CGAL::Triangulation_face_base_with_info_2<int, Kernel,
                                              CGAL::Constrained_triangulation_face_base_2<Kernel>>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Constraints that would cross throw instead of gaining an intersection vertex: a vertex the
// neighbouring planes' faces do not have would open a T-junction.
using Cdt =
    CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::No_constraint_intersection_tag>;

struct PositionHash {
    size_t operator()(const dvec3& p) const {
        size_t h = std::bit_cast<uint64_t>(p.x);
        h = h * 0x9E3779B97F4A7C15ull ^ std::bit_cast<uint64_t>(p.y);
        h = h * 0x9E3779B97F4A7C15ull ^ std::bit_cast<uint64_t>(p.z);
        return h;
    }
};

uint64_t edge_key(uint32_t a, uint32_t b) {
    return uint64_t(a) << 32 | b;
}

}  // namespace

std::optional<std::vector<std::pair<uint32_t, uint32_t>>> outline_edges(
    const std::vector<const Polygon*>& polygons, std::vector<dvec3>& positions) {
    // Distinct positions, compared exactly (the conforming step welded the shared ones).
    std::unordered_map<dvec3, uint32_t, PositionHash> ids;
    for (uint32_t i = 0; i < positions.size(); ++i) {
        ids.emplace(positions[i], i);
    }
    auto id_of = [&](const dvec3& p) {
        const auto [at, added] = ids.try_emplace(p, uint32_t(positions.size()));
        if (added) {
            positions.push_back(p);
        }
        return at->second;
    };
    // +1 per a -> b with a < b, -1 per b -> a: the interior edges come to 0.
    std::unordered_map<uint64_t, int> balance;
    for (const Polygon* polygon : polygons) {
        const size_t count = polygon->size();
        for (size_t k = 0; k < count; ++k) {
            const uint32_t a = id_of(polygon->vertices[k]);
            const uint32_t b = id_of(polygon->vertices[(k + 1) % count]);
            if (a != b) {
                balance[a < b ? edge_key(a, b) : edge_key(b, a)] += a < b ? 1 : -1;
            }
        }
    }
    std::vector<std::pair<uint32_t, uint32_t>> edges;  // directed, inside on the left
    for (const auto& [key, count] : balance) {
        if (std::abs(count) > 1) {
            return std::nullopt;  // met twice the same way: the polygons overlap
        }
        const auto lo = uint32_t(key >> 32), hi = uint32_t(key & 0xffffffffu);
        if (count == 1) {
            edges.emplace_back(lo, hi);
        } else if (count == -1) {
            edges.emplace_back(hi, lo);
        }
    }
    // Deterministic regardless of the hash map's order (the triangulation depends on the order
    // constraints go in only through which of equal-circumcircle diagonals it picks).
    std::sort(edges.begin(), edges.end());
    return edges;
}

std::optional<MaximalTriangulation> triangulate_union(const std::vector<const Polygon*>& polygons,
                                                      const dvec3& normal) {
    std::vector<dvec3> positions;
    const auto edges = outline_edges(polygons, positions);
    if (!edges) {
        return std::nullopt;
    }
    return triangulate_outline(positions, *edges, normal);
}

std::optional<MaximalTriangulation> triangulate_outline(
    const std::vector<dvec3>& positions, const std::vector<std::pair<uint32_t, uint32_t>>& edges,
    const dvec3& normal) {
    if (edges.size() < 3) {
        return std::nullopt;
    }
    const dvec3 n = glm::normalize(normal);
    // The plane's 2D frame (u, v, normal), right-handed: counter-clockwise around the normal is
    // counter-clockwise in (u, v).
    const dvec3 helper = std::abs(n.x) < 0.6 ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
    const dvec3 u = glm::normalize(glm::cross(helper, n));
    const dvec3 v = glm::cross(n, u);
    const dvec3 origin = positions[edges.front().first];

    // Only the vertices on the boundary edges: the interior ones go with the interior edges.
    std::unordered_map<uint32_t, uint32_t> compact;
    std::vector<std::pair<Kernel::Point_2, uint32_t>> points;
    MaximalTriangulation result;
    double outline_area = 0.0;  // the loops' own (shoelace), seen along n
    for (const auto& [a, b] : edges) {
        outline_area += 0.5 * glm::dot(glm::cross(positions[a] - origin, positions[b] - origin), n);
        for (const uint32_t id : {a, b}) {
            const auto [at, added] = compact.try_emplace(id, uint32_t(result.vertices.size()));
            if (added) {
                result.vertices.push_back(positions[id]);
                const dvec3 d = positions[id] - origin;
                points.emplace_back(Kernel::Point_2(glm::dot(d, u), glm::dot(d, v)), at->second);
            }
        }
    }
    Cdt cdt;
    cdt.insert(points.begin(), points.end());
    if (cdt.number_of_vertices() != points.size()) {
        return std::nullopt;  // two positions on one point of the projection
    }
    std::vector<Cdt::Vertex_handle> handle(points.size());
    for (auto vertex = cdt.finite_vertices_begin(); vertex != cdt.finite_vertices_end(); ++vertex) {
        handle[vertex->info()] = vertex;
    }
    try {
        for (const auto& [a, b] : edges) {
            cdt.insert_constraint(handle[compact.at(a)], handle[compact.at(b)]);
        }
    } catch (const std::exception&) {
        return std::nullopt;  // boundary edges that cross in the projection
    }
    for (auto face = cdt.all_faces_begin(); face != cdt.all_faces_end(); ++face) {
        face->info() = 0;
    }
    // Seeds: the face to the left of each boundary edge is inside, the one to its right outside.
    std::vector<Cdt::Face_handle> inside;
    auto label = [&](Cdt::Face_handle face, int value) {
        if (face->info() == -value || (value > 0 && cdt.is_infinite(face))) {
            return false;
        }
        if (face->info() == 0) {
            face->info() = value;
            if (value > 0) {
                inside.push_back(face);
            }
        }
        return true;
    };
    for (const auto& [a, b] : edges) {
        Cdt::Face_handle face;
        int i = 0;
        const Cdt::Vertex_handle va = handle[compact.at(a)], vb = handle[compact.at(b)];
        if (!cdt.is_edge(va, vb, face, i)) {
            return std::nullopt;  // a vertex lies on the edge in the projection: it was split
        }
        // A face's vertices run counter-clockwise; the edge opposite vertex i runs from
        // ccw(i) to cw(i) in that order.
        const bool face_left = face->vertex(Cdt::ccw(i)) == va;
        const Cdt::Face_handle left = face_left ? face : face->neighbor(i);
        const Cdt::Face_handle right = face_left ? face->neighbor(i) : face;
        if (!label(left, 1) || !label(right, -1)) {
            return std::nullopt;
        }
    }
    // Inside spreads across every edge that is not a boundary edge.
    for (size_t k = 0; k < inside.size(); ++k) {
        const Cdt::Face_handle face = inside[k];
        for (int i = 0; i < 3; ++i) {
            if (!face->is_constrained(i) && !label(face->neighbor(i), 1)) {
                return std::nullopt;  // inside by one boundary edge, outside by another
            }
        }
    }
    double output_area = 0.0;
    for (const Cdt::Face_handle face : inside) {
        const glm::uvec3 t(face->vertex(0)->info(), face->vertex(1)->info(),
                           face->vertex(2)->info());
        result.triangles.push_back(t);
        const dvec3 &p = result.vertices[t.x], &q = result.vertices[t.y], &r = result.vertices[t.z];
        output_area += 0.5 * glm::dot(glm::cross(q - p, r - p), n);
    }
    if (!(std::abs(output_area - outline_area) <= 1e-9 * std::abs(outline_area))) {
        return std::nullopt;
    }
    result.boundary_edges = edges.size();
    return result;
}

}  // namespace sl::bt
