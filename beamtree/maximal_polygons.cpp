#include "beamtree/maximal_polygons.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>

#include <glm/geometric.hpp>

#include <tbb/parallel_for.h>

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

}  // namespace

std::vector<Edge> unmatched_edges(const std::vector<Edge>& edges, int* most) {
    // (lo << 32 | hi, +1 for lo -> hi, -1 for hi -> lo), summed per key.
    std::vector<std::pair<uint64_t, int>> keyed;
    keyed.reserve(edges.size());
    for (const auto& [a, b] : edges) {
        if (a != b) {
            keyed.emplace_back(a < b ? uint64_t(a) << 32 | b : uint64_t(b) << 32 | a,
                               a < b ? 1 : -1);
        }
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<Edge> unmatched;
    int largest = 0;
    for (size_t i = 0; i < keyed.size();) {
        int count = 0;
        size_t j = i;
        for (; j < keyed.size() && keyed[j].first == keyed[i].first; ++j) {
            count += keyed[j].second;
        }
        const auto lo = uint32_t(keyed[i].first >> 32), hi = uint32_t(keyed[i].first);
        for (int c = 0; c < std::abs(count); ++c) {
            unmatched.push_back(count > 0 ? Edge{lo, hi} : Edge{hi, lo});
        }
        largest = std::max(largest, std::abs(count));
        i = j;
    }
    std::sort(unmatched.begin(), unmatched.end());
    if (most) {
        *most = largest;
    }
    return unmatched;
}

std::optional<MaximalTriangulation> triangulate_union(const std::vector<const Polygon*>& polygons,
                                                      const dvec3& normal) {
    // Vertex ids by exact position (the conforming step welded the shared ones).
    std::unordered_map<dvec3, uint32_t, PositionHash> ids;
    std::vector<dvec3> positions;
    std::vector<Edge> edges;
    for (const Polygon* polygon : polygons) {
        const size_t first = edges.size();
        for (const dvec3& p : polygon->vertices) {
            const auto [at, added] = ids.try_emplace(p, uint32_t(positions.size()));
            if (added) {
                positions.push_back(p);
            }
            if (edges.size() > first) {
                edges.back().second = at->second;
            }
            edges.emplace_back(at->second, 0);
        }
        if (edges.size() > first) {
            edges.back().second = edges[first].first;
        }
    }
    int most = 0;
    const std::vector<Edge> outline = unmatched_edges(edges, &most);
    if (most > 1) {
        return std::nullopt;  // met twice the same way: the polygons overlap
    }
    return triangulate_outline(positions, outline, normal);
}

namespace {

// An outline's vertices in its plane's 2D frame (u, v, normal), right-handed: counter-clockwise
// around the normal is counter-clockwise in (u, v). Only the vertices on the boundary edges: the
// interior ones go with the interior edges.
struct PlanarOutline {
    std::unordered_map<uint32_t, uint32_t> compact;            // global id -> local
    std::vector<std::pair<Kernel::Point_2, uint32_t>> points;  // (u, v), local id
    std::vector<dvec3> vertices;                               // by local id
    double area = 0.0;                                         // the loops' own (shoelace)
};

PlanarOutline project(const std::vector<dvec3>& positions, const std::vector<Edge>& edges,
                      const dvec3& n) {
    const dvec3 helper = std::abs(n.x) < 0.6 ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
    const dvec3 u = glm::normalize(glm::cross(helper, n));
    const dvec3 v = glm::cross(n, u);
    const dvec3 origin = positions[edges.front().first];
    PlanarOutline out;
    for (const auto& [a, b] : edges) {
        out.area += 0.5 * glm::dot(glm::cross(positions[a] - origin, positions[b] - origin), n);
        for (const uint32_t id : {a, b}) {
            const auto [at, added] = out.compact.try_emplace(id, uint32_t(out.vertices.size()));
            if (added) {
                out.vertices.push_back(positions[id]);
                const dvec3 d = positions[id] - origin;
                out.points.emplace_back(Kernel::Point_2(glm::dot(d, u), glm::dot(d, v)),
                                        at->second);
            }
        }
    }
    return out;
}

// The faces inside the outline: the face to the left of each boundary edge is inside, the one to
// its right outside, and inside spreads across every edge that is not a boundary edge. Nothing
// where a boundary edge is not an edge of the triangulation or a face would be both.
std::optional<std::vector<Cdt::Face_handle>> inside_faces(
    Cdt& cdt, const std::vector<Cdt::Vertex_handle>& handle, const PlanarOutline& outline,
    const std::vector<Edge>& edges) {
    for (auto face = cdt.all_faces_begin(); face != cdt.all_faces_end(); ++face) {
        face->info() = 0;
    }
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
        const Cdt::Vertex_handle va = handle[outline.compact.at(a)];
        const Cdt::Vertex_handle vb = handle[outline.compact.at(b)];
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
    for (size_t k = 0; k < inside.size(); ++k) {
        const Cdt::Face_handle face = inside[k];
        for (int i = 0; i < 3; ++i) {
            if (!face->is_constrained(i) && !label(face->neighbor(i), 1)) {
                return std::nullopt;  // inside by one boundary edge, outside by another
            }
        }
    }
    return inside;
}

}  // namespace

std::optional<MaximalTriangulation> triangulate_outline(const std::vector<dvec3>& positions,
                                                        const std::vector<Edge>& edges,
                                                        const dvec3& normal) {
    if (edges.size() < 3) {
        return std::nullopt;
    }
    const dvec3 n = glm::normalize(normal);
    PlanarOutline outline = project(positions, edges, n);
    Cdt cdt;
    cdt.insert(outline.points.begin(), outline.points.end());
    if (cdt.number_of_vertices() != outline.points.size()) {
        return std::nullopt;  // two positions on one point of the projection
    }
    std::vector<Cdt::Vertex_handle> handle(outline.points.size());
    for (auto vertex = cdt.finite_vertices_begin(); vertex != cdt.finite_vertices_end(); ++vertex) {
        handle[vertex->info()] = vertex;
    }
    try {
        for (const auto& [a, b] : edges) {
            cdt.insert_constraint(handle[outline.compact.at(a)], handle[outline.compact.at(b)]);
        }
    } catch (const std::exception&) {
        return std::nullopt;  // boundary edges that cross in the projection
    }
    const std::optional<std::vector<Cdt::Face_handle>> inside =
        inside_faces(cdt, handle, outline, edges);
    if (!inside) {
        return std::nullopt;
    }
    MaximalTriangulation result;
    result.vertices = std::move(outline.vertices);
    double output_area = 0.0;
    for (const Cdt::Face_handle face : *inside) {
        const glm::uvec3 t(face->vertex(0)->info(), face->vertex(1)->info(),
                           face->vertex(2)->info());
        result.triangles.push_back(t);
        const dvec3 &p = result.vertices[t.x], &q = result.vertices[t.y], &r = result.vertices[t.z];
        output_area += 0.5 * glm::dot(glm::cross(q - p, r - p), n);
    }
    if (!(std::abs(output_area - outline.area) <= 1e-9 * std::abs(outline.area))) {
        return std::nullopt;
    }
    result.boundary_edges = edges.size();
    return result;
}

namespace {

// The faces on one plane and side, and what becomes of them.
struct FaceSet {
    std::vector<uint32_t> faces;  // indices into the boundary's faces
    dvec3 normal{0.0};            // their summed area vector
    bool fanned = false;          // kept as they are: no shared plane, an overlap, or refused
    bool flat = false;            // of zero area (welded into a line): kept for their edges
    std::vector<Edge> outline;    // the union's outline, before any vertex is dropped
};

// The outline of a set: its faces' directed edges (global vertex ids) that are not met the other
// way, sorted; false where an edge is met twice the same way.
bool outline_of(const std::vector<std::vector<uint32_t>>& face_ids, FaceSet& set) {
    std::vector<Edge> edges;
    for (const uint32_t f : set.faces) {
        const std::vector<uint32_t>& ids = face_ids[f];
        for (size_t k = 0; k < ids.size(); ++k) {
            edges.emplace_back(ids[k], ids[(k + 1) % ids.size()]);
        }
    }
    int most = 0;
    set.outline = unmatched_edges(edges, &most);
    return most <= 1;
}

// The merged sets' outline edges as one directed graph: per vertex its outgoing and incoming
// edges (compressed rows), each edge with the set it belongs to.
class OutlineGraph {
public:
    OutlineGraph(const std::vector<FaceSet>& sets, size_t vertex_count) : sets_(sets.size()) {
        for (uint32_t s = 0; s < sets.size(); ++s) {
            if (sets[s].fanned) {
                continue;
            }
            for (const auto& [a, b] : sets[s].outline) {
                from_.push_back(a);
                to_.push_back(b);
                owner_.push_back(s);
            }
        }
        const size_t edge_count = from_.size();
        out_begin_.assign(vertex_count + 1, 0);
        in_begin_.assign(vertex_count + 1, 0);
        for (size_t e = 0; e < edge_count; ++e) {
            ++out_begin_[from_[e] + 1];
            ++in_begin_[to_[e] + 1];
        }
        for (size_t v = 0; v < vertex_count; ++v) {
            out_begin_[v + 1] += out_begin_[v];
            in_begin_[v + 1] += in_begin_[v];
        }
        out_edges_.resize(edge_count);
        in_edges_.resize(edge_count);
        std::vector<uint32_t> out_at(out_begin_.begin(), out_begin_.end() - 1),
            in_at(in_begin_.begin(), in_begin_.end() - 1);
        for (uint32_t e = 0; e < edge_count; ++e) {
            out_edges_[out_at[from_[e]]++] = e;
            in_edges_[in_at[to_[e]]++] = e;
        }
        alive_.assign(edge_count, true);
    }

    // Drops vertex v where two sets pass through it once each, one a -> v -> b and the other
    // b -> v -> a, with no edge between a and b yet, and v within sqrt(tolerance2) of segment
    // ab (strictly between a and b): both then run a -> b and b -> a directly.
    bool drop(uint32_t v, const std::vector<dvec3>& positions, double tolerance2) {
        if (out_begin_[v + 1] - out_begin_[v] != 2 || in_begin_[v + 1] - in_begin_[v] != 2) {
            return false;
        }
        const uint32_t o1 = out_edges_[out_begin_[v]], o2 = out_edges_[out_begin_[v] + 1];
        uint32_t i1 = in_edges_[in_begin_[v]], i2 = in_edges_[in_begin_[v] + 1];
        if (owner_[o1] == owner_[o2] || !alive_[o1] || !alive_[o2] || !alive_[i1] || !alive_[i2]) {
            return false;
        }
        if (owner_[i1] != owner_[o1]) {
            std::swap(i1, i2);
        }
        if (owner_[i1] != owner_[o1] || owner_[i2] != owner_[o2]) {
            return false;
        }
        const uint32_t a = from_[i1], b = to_[o1];
        if (a == b || from_[i2] != b || to_[o2] != a || linked(owner_[o1], a, b) ||
            linked(owner_[o2], a, b)) {
            return false;
        }
        const dvec3 ab = positions[b] - positions[a], av = positions[v] - positions[a];
        const double length2 = glm::dot(ab, ab);
        const double t = glm::dot(av, ab);
        const dvec3 off = glm::cross(ab, av);
        if (!(t > 0.0 && t < length2 && glm::dot(off, off) <= tolerance2 * length2)) {
            return false;
        }
        to_[i1] = b;
        alive_[o1] = false;
        replace_in(b, o1, i1);
        to_[i2] = a;
        alive_[o2] = false;
        replace_in(a, o2, i2);
        return true;
    }

    // Each set's live edges, sorted.
    std::vector<std::vector<Edge>> outlines() const {
        std::vector<std::vector<Edge>> out(sets_);
        for (size_t e = 0; e < from_.size(); ++e) {
            if (alive_[e]) {
                out[owner_[e]].emplace_back(from_[e], to_[e]);
            }
        }
        for (std::vector<Edge>& outline : out) {
            std::sort(outline.begin(), outline.end());
        }
        return out;
    }

private:
    bool has_edge(uint32_t set, uint32_t a, uint32_t b) const {
        for (uint32_t k = out_begin_[a]; k < out_begin_[a + 1]; ++k) {
            const uint32_t e = out_edges_[k];
            if (alive_[e] && owner_[e] == set && to_[e] == b) {
                return true;
            }
        }
        return false;
    }
    bool linked(uint32_t set, uint32_t a, uint32_t b) const {
        return has_edge(set, a, b) || has_edge(set, b, a);
    }
    void replace_in(uint32_t vertex, uint32_t old_edge, uint32_t new_edge) {
        for (uint32_t k = in_begin_[vertex]; k < in_begin_[vertex + 1]; ++k) {
            if (in_edges_[k] == old_edge) {
                in_edges_[k] = new_edge;
            }
        }
    }

    size_t sets_;
    std::vector<uint32_t> from_, to_, owner_;
    std::vector<uint32_t> out_begin_, in_begin_, out_edges_, in_edges_;
    std::vector<bool> alive_;
};

// Drops the vertices two merged outlines share and need not keep: a vertex used by exactly two
// sets, each passing through it once (in from a, out to b in one; in from b, out to a in the
// other), within `tolerance` of the segment ab, and not pinned (a vertex of a fanned set, which
// keeps its faces as they are). Both outlines then run a -> b and b -> a directly, so they still
// meet edge for edge: watertight, and the triangulation needs no triangle to that vertex. What
// it moves is at most the tolerance (the welding tolerance). Vertices in id order, so the result
// does not depend on the schedule. Returns each set's outline and the vertices dropped.
size_t simplify_outlines(const std::vector<dvec3>& positions, const std::vector<FaceSet>& sets,
                         const std::vector<bool>& pinned, double tolerance,
                         std::vector<std::vector<Edge>>& outlines) {
    OutlineGraph graph(sets, positions.size());
    size_t dropped = 0;
    for (uint32_t v = 0; v < positions.size(); ++v) {
        if (!pinned[v] && graph.drop(v, positions, tolerance * tolerance)) {
            ++dropped;
        }
    }
    outlines = graph.outlines();
    return dropped;
}

// Global vertex ids, in order of first use, and each face's ids.
struct WeldedFaces {
    std::vector<dvec3> positions;
    std::vector<std::vector<uint32_t>> face_ids;
};

WeldedFaces weld(const std::vector<PlanarFace>& faces) {
    WeldedFaces out;
    out.face_ids.resize(faces.size());
    std::unordered_map<dvec3, uint32_t, PositionHash> ids;
    for (size_t f = 0; f < faces.size(); ++f) {
        for (const dvec3& p : faces[f].polygon->vertices) {
            const auto [at, added] = ids.try_emplace(p, uint32_t(out.positions.size()));
            if (added) {
                out.positions.push_back(p);
            }
            out.face_ids[f].push_back(at->second);
        }
    }
    return out;
}

// The faces by plane and side, in the order they come (a face on no shared plane alone), each
// set with its normal and outline, or fanned where it has none.
std::vector<FaceSet> sets_by_plane(const std::vector<PlanarFace>& faces,
                                   const WeldedFaces& welded) {
    std::vector<FaceSet> sets;
    std::vector<int32_t> set_of_plane;
    for (uint32_t f = 0; f < faces.size(); ++f) {
        if (faces[f].plane < 0) {
            FaceSet& alone = sets.emplace_back();
            alone.faces = {f};
            alone.fanned = true;
            continue;
        }
        if (size_t(faces[f].plane) >= set_of_plane.size()) {
            set_of_plane.resize(size_t(faces[f].plane) + 1, -1);
        }
        int32_t& set = set_of_plane[size_t(faces[f].plane)];
        if (set < 0) {
            set = int32_t(sets.size());
            sets.emplace_back();
        }
        sets[size_t(set)].faces.push_back(f);
    }
    tbb::parallel_for(size_t(0), sets.size(), [&](size_t i) {
        FaceSet& set = sets[i];
        if (set.fanned) {
            return;
        }
        for (const uint32_t f : set.faces) {
            set.normal += area_vector(*faces[f].polygon);
        }
        set.flat = !(glm::length(set.normal) > 0.0);
        set.fanned = set.flat || !outline_of(welded.face_ids, set);
    });
    return sets;
}

// Triangulates every set's outline, in rounds: a set whose triangulation is refused is fanned,
// which pins its vertices, and the outlines are simplified again (the first kDroppingRounds
// rounds; after that they are kept whole). Returns each merged set's triangulation.
std::vector<std::optional<MaximalTriangulation>> triangulate_sets(const WeldedFaces& welded,
                                                                  std::vector<FaceSet>& sets,
                                                                  double tolerance, MergeStats& s) {
    std::vector<bool> pinned(welded.positions.size(), false);
    auto pin = [&](const FaceSet& set) {
        for (const uint32_t f : set.faces) {
            for (const uint32_t id : welded.face_ids[f]) {
                pinned[id] = true;
            }
        }
    };
    for (const FaceSet& set : sets) {
        if (set.fanned) {
            pin(set);
        }
    }
    std::vector<std::optional<MaximalTriangulation>> merged(sets.size());
    std::vector<std::vector<Edge>> outlines, triangulated(sets.size());
    constexpr int kDroppingRounds = 4;
    for (int round = 0;; ++round) {
        if (round < kDroppingRounds) {
            s.dropped_vertices =
                simplify_outlines(welded.positions, sets, pinned, tolerance, outlines);
        } else {
            s.dropped_vertices = 0;
            outlines.assign(sets.size(), {});
            for (size_t i = 0; i < sets.size(); ++i) {
                outlines[i] = sets[i].outline;
            }
        }
        // One byte per set: the tasks below write their own flags at once, and std::vector<bool>
        // packs 64 flags in a word, so two tasks' writes to one word raced and one was lost (a
        // refused triangulation then read as merged: an empty optional, a crash).
        std::vector<uint8_t> refused(sets.size(), 0);
        tbb::parallel_for(size_t(0), sets.size(), [&](size_t i) {
            if (sets[i].fanned || (merged[i] && triangulated[i] == outlines[i])) {
                return;  // kept as they are, or the same outline as the last round
            }
            merged[i] = triangulate_outline(welded.positions, outlines[i], sets[i].normal);
            triangulated[i] = outlines[i];
            refused[i] = merged[i] ? 0 : 1;
        });
        bool any = false;
        for (size_t i = 0; i < sets.size(); ++i) {
            if (refused[i]) {
                sets[i].fanned = true;
                pin(sets[i]);
                any = true;
            }
        }
        s.rounds = round + 1;
        if (!any) {
            return merged;
        }
    }
}

}  // namespace

RegionMesh maximal_polygon_mesh(const std::vector<PlanarFace>& faces, double tolerance,
                                MergeStats& s) {
    const WeldedFaces welded = weld(faces);
    std::vector<FaceSet> sets = sets_by_plane(faces, welded);
    const std::vector<std::optional<MaximalTriangulation>> merged =
        triangulate_sets(welded, sets, tolerance, s);
    RegionMesh mesh;
    for (size_t i = 0; i < sets.size(); ++i) {
        const FaceSet& set = sets[i];
        if (set.fanned) {
            s.unmerged_planes += faces[set.faces.front()].plane >= 0 && !set.flat ? 1 : 0;
            s.flat_planes += set.flat ? 1 : 0;
            for (const uint32_t f : set.faces) {
                mesh.add_fanned(*faces[f].polygon, faces[f].beam);
            }
            continue;
        }
        ++s.merged_planes;
        const auto base = uint32_t(mesh.positions.size());
        for (const dvec3& p : merged[i]->vertices) {
            mesh.positions.emplace_back(p);
        }
        for (const glm::uvec3& t : merged[i]->triangles) {
            mesh.triangles.push_back(t + base);
            mesh.beams.push_back(faces[set.faces.front()].beam);
        }
    }
    return mesh;
}

}  // namespace sl::bt
