#include "beamtree/boundary.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <deque>
#include <map>
#include <optional>

#include <glm/geometric.hpp>

#include "beamtree/conforming.h"

namespace sl::bt {

namespace {

struct Box3 {
    dvec3 lo{std::numeric_limits<double>::max()}, hi{std::numeric_limits<double>::lowest()};
    explicit Box3(const Polygon& polygon) {
        for (const dvec3& v : polygon.vertices) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
    }
    bool overlaps(const Box3& other, double margin) const {
        return !(glm::any(glm::greaterThan(lo, other.hi + margin)) ||
                 glm::any(glm::greaterThan(other.lo, hi + margin)));
    }
};

// The parts of convex `a` outside convex `b`, both on one plane: `a` cut by each edge line of
// `b` (as a plane through the edge along the plane's normal), the part outside an edge kept,
// the part inside going on to the next edge; what is inside every edge is a ∩ b, returned.
// The edges of the parts that `b` made are `b`'s own edges, so they meet `b`'s neighbouring
// faces exactly.
Polygon subtract(const Polygon& a, const Polygon& b, const dvec3& b_normal, double epsilon,
                 std::vector<Polygon>& out) {
    // b winds counter-clockwise around its normal (the plane's, not its own area vector's: a
    // sliver's is round-off): (q - p) x n points out of it.
    Polygon remaining = a;
    for (size_t i = 0; i < b.size() && !remaining.empty(); ++i) {
        const dvec3& p = b.vertices[i];
        const dvec3& q = b.vertices[(i + 1) % b.size()];
        const dvec3 outward = glm::cross(q - p, b_normal);
        const double length = glm::length(outward);
        if (!(length > epsilon)) {
            continue;  // a (near-)zero-length edge: its direction is round-off
        }
        const Plane edge{outward / length, -glm::dot(outward / length, p)};
        Split parts = split(remaining, edge, epsilon);
        if (parts.coplanar) {
            continue;
        }
        if (!parts.front.empty()) {
            out.push_back(std::move(parts.front));
        }
        remaining = std::move(parts.back);
    }
    return remaining;
}

struct Fragment {
    Polygon polygon;
    uint32_t beam;
    uint32_t origin;  // the piece face it is part of
};

// Signed multiplicity on one plane: a point covered by m faces from the front side and n from
// the back is on the boundary m - n times, outward the way the majority points. (The pieces are
// disjoint, so m, n <= 1 except where a sliver thinner than the plane tolerance lies on the
// plane, whose two faces both fall in one group: the covering face in front of it and its own
// front face then overlap, and only one of them may cancel its back face.) Each overlap of a
// front and a back fragment is cancelled once, from both, and what is left of each goes on to
// the faces it has not met: the back fragments as a work list against every front fragment.
// Both inputs are convex polygons on the plane of `normal` (the back side's faces wind around
// it, the front side's against it); the outputs are convex parts of them.
void cancel(std::vector<Fragment>& front, std::vector<Fragment>& back, const dvec3& normal,
            double epsilon) {
    std::vector<Fragment> work = std::move(back);
    back.clear();
    std::vector<Box3> front_boxes;
    for (const Fragment& f : front) {
        front_boxes.emplace_back(f.polygon);
    }
    const double min_area = epsilon * epsilon;
    while (!work.empty()) {
        Fragment b = std::move(work.back());
        work.pop_back();
        const Box3 b_box(b.polygon);
        bool met = false;
        for (size_t j = 0; j < front.size() && !met; ++j) {
            if (front[j].polygon.empty() || !b_box.overlaps(front_boxes[j], epsilon)) {
                continue;
            }
            std::vector<Polygon> b_parts;
            const Polygon common = subtract(b.polygon, front[j].polygon, -normal, epsilon, b_parts);
            if (common.size() < 3 || !(area(common) > min_area)) {
                continue;
            }
            met = true;
            std::vector<Polygon> f_parts;
            subtract(front[j].polygon, b.polygon, normal, epsilon, f_parts);
            const Fragment f = std::move(front[j]);
            front[j].polygon = Polygon();
            for (size_t k = 0; k < f_parts.size(); ++k) {
                Fragment part{std::move(f_parts[k]), f.beam, f.origin};
                if (k == 0) {
                    front_boxes[j] = Box3(part.polygon);
                    front[j] = std::move(part);
                } else {
                    front_boxes.emplace_back(part.polygon);
                    front.push_back(std::move(part));
                }
            }
            for (Polygon& part : b_parts) {
                work.push_back({std::move(part), b.beam, b.origin});
            }
        }
        if (!met) {
            back.push_back(std::move(b));
        }
    }
    std::erase_if(front, [](const Fragment& f) { return f.polygon.empty(); });
}

struct Face {
    const Polygon* polygon;
    uint32_t beam;
};

// Closes what the conforming step leaves open. The two sides of a shared plane are cut from
// the tree independently, and where they disagree by less than the tree's ε (a corner computed
// from two near-coincident planes) a crack of that width remains: a chain of edges met from one
// side only. In a set of closed polygons such edges always form cycles (every vertex has as many
// unmatched edges in as out), so each cycle becomes a polygon of the opposite winding: the cracks
// are ε wide, the fill's area next to nothing, and every directed edge is then met by its
// opposite. Positions are compared exactly: the conforming step welded the shared ones. Returns
// the cycles filled.
size_t close_cracks(std::vector<BoundaryFace>& faces) {
    // Vertex ids by exact position (lexicographic order, so the result does not depend on the
    // faces' order beyond which cycle starts where).
    std::vector<dvec3> positions;
    for (const BoundaryFace& face : faces) {
        positions.insert(positions.end(), face.polygon.vertices.begin(),
                         face.polygon.vertices.end());
    }
    std::sort(positions.begin(), positions.end(), lexicographic_less);
    positions.erase(std::unique(positions.begin(), positions.end()), positions.end());
    const auto id_of = [&](const dvec3& p) {
        return uint32_t(
            std::lower_bound(positions.begin(), positions.end(), p, lexicographic_less) -
            positions.begin());
    };
    std::vector<Edge> edges;
    for (const BoundaryFace& face : faces) {
        const std::vector<dvec3>& v = face.polygon.vertices;
        for (size_t k = 0; k < v.size(); ++k) {
            edges.emplace_back(id_of(v[k]), id_of(v[(k + 1) % v.size()]));
        }
    }
    const std::vector<Edge> unmatched = unmatched_edges(edges);
    // Follow the unmatched ones from edge to edge (sorted by where they start; each used once).
    std::vector<bool> used(unmatched.size(), false);
    auto next_from = [&](uint32_t vertex) -> std::optional<size_t> {
        auto at = std::lower_bound(unmatched.begin(), unmatched.end(),
                                   std::pair<uint32_t, uint32_t>(vertex, 0));
        for (; at != unmatched.end() && at->first == vertex; ++at) {
            const auto k = size_t(at - unmatched.begin());
            if (!used[k]) {
                return k;
            }
        }
        return std::nullopt;
    };
    size_t cycles = 0;
    for (size_t start = 0; start < unmatched.size(); ++start) {
        if (used[start]) {
            continue;
        }
        used[start] = true;
        std::vector<uint32_t> cycle = {unmatched[start].first};
        uint32_t at = unmatched[start].second;
        while (at != cycle.front()) {
            const std::optional<size_t> next = next_from(at);
            if (!next) {
                break;  // not a cycle (cannot happen for closed polygons): left open
            }
            cycle.push_back(at);
            used[*next] = true;
            at = unmatched[*next].second;
        }
        if (at != cycle.front() || cycle.size() < 3) {
            continue;
        }
        // The cycle runs the way its faces do; the fill runs against it.
        BoundaryFace fill;
        for (auto p = cycle.rbegin(); p != cycle.rend(); ++p) {
            fill.polygon.vertices.push_back(positions[*p]);
        }
        faces.push_back(std::move(fill));
        ++cycles;
    }
    return cycles;
}

// Each piece face's plane: a split node on the piece's path (and on which side of it the piece
// lies), or none (a range, the occluder, the stopper: another type beyond).
std::vector<std::vector<BeamTree::FacePlane>> piece_face_planes(
    const BeamTree& tree, const std::vector<RegionPiece>& pieces, double tolerance) {
    std::vector<std::vector<BeamTree::FacePlane>> planes(pieces.size());
    tbb::parallel_for(size_t(0), pieces.size(), [&](size_t i) {
        dvec3 interior(0.0);
        size_t corners = 0;
        for (const Polygon& face : pieces[i].polyhedron.faces) {
            for (const dvec3& v : face.vertices) {
                interior += v;
                ++corners;
            }
        }
        interior /= double(corners);
        for (const Polygon& face : pieces[i].polyhedron.faces) {
            planes[i].push_back(tree.face_plane(interior, face, tolerance));
        }
    });
    return planes;
}

// Faces on one plane from its front side and its back side: the boundary there is the parts
// covered from one side only.
struct Group {
    dvec3 normal{0.0};  // the split plane's
    Plane plane;        // for a group of one face on its own plane
    std::vector<Face> front, back;
};

// The piece faces by plane: on a split plane, grouped by its node; on any other plane, one group
// each; faces of no area are kept whole at once (into `kept`).
struct FaceGroups {
    std::map<int32_t, Group> by_split;
    std::deque<Group> own_plane;
};

FaceGroups group_faces(const BeamTree& tree, const std::vector<RegionPiece>& pieces,
                       double tolerance, std::vector<BoundaryFace>& kept, BoundaryStats& s) {
    const std::vector<std::vector<BeamTree::FacePlane>> planes =
        piece_face_planes(tree, pieces, tolerance);
    FaceGroups groups;
    for (size_t i = 0; i < pieces.size(); ++i) {
        const std::vector<Polygon>& piece_faces = pieces[i].polyhedron.faces;
        s.piece_faces += piece_faces.size();
        for (size_t f = 0; f < piece_faces.size(); ++f) {
            const BeamTree::FacePlane& plane = planes[i][f];
            if (plane.split < 0) {
                // On a range, occluder or stopper plane: another type is beyond, except where
                // an occluder occludes nothing (edge-on to the light, or behind another's
                // outer volume that already made the space beyond uncertain) — then the same
                // type lies beyond and its face there must cancel too. Such faces form groups
                // of their own plane, merged with any other group on the same plane below.
                const dvec3 area = area_vector(piece_faces[f]);
                const double a = glm::length(area);
                if (!(a > tolerance * tolerance)) {
                    kept.push_back({pieces[i].beam, piece_faces[f]});
                    ++s.kept_whole;
                    continue;
                }
                Group& group = groups.own_plane.emplace_back();
                group.plane = Plane{area / a, -glm::dot(area / a, centroid(piece_faces[f]))};
                group.back.push_back({&piece_faces[f], pieces[i].beam});  // piece behind it
                continue;
            }
            // The side of the piece: by the face's own outward direction where it has one
            // (a sliver piece's interior point lies on the plane to round-off), else as the
            // tree found it.
            Group& group = groups.by_split[plane.split];
            const double along =
                glm::dot(area_vector(piece_faces[f]), tree.node_plane(plane.split).normal);
            const bool in_front =
                std::abs(along) > tolerance * tolerance ? along < 0.0 : plane.piece_in_front;
            (in_front ? group.front : group.back).push_back({&piece_faces[f], pieces[i].beam});
        }
    }
    return groups;
}

// The same plane can be split by several nodes (polygons sharing an edge insert it once each, a
// flat polygon twice): their faces meet across one geometric plane, so groups whose planes lie
// within the tolerance of each other over the influence volume (every split plane passes through
// the light: directions within tolerance / range, distances from the light within the
// tolerance) are merged, the front and back of a flipped copy swapped.
std::vector<Group> merge_coincident(const BeamTree& tree, FaceGroups& groups) {
    const double range = tree.epsilon() / BeamTree::kRelativeEpsilon;
    const double coincide = 3e-2 * tree.epsilon();
    const double angle = coincide / range;
    struct Keyed {
        dvec3 normal;
        double offset;  // signed distance of the light
        Group* group;
        bool flipped;
    };
    std::vector<Keyed> keyed;
    auto add_keyed = [&](const Plane& plane, Group& group) {
        // A canonical direction: the largest component positive.
        const dvec3& n = plane.normal;
        const int axis = std::abs(n.x) >= std::abs(n.y) && std::abs(n.x) >= std::abs(n.z) ? 0
                         : std::abs(n.y) >= std::abs(n.z)                                 ? 1
                                                                                          : 2;
        const bool flip = n[axis] < 0.0;
        const double at_light = plane.distance(tree.apex());
        keyed.push_back({flip ? -n : n, flip ? -at_light : at_light, &group, flip});
    };
    for (auto& [node, group] : groups.by_split) {
        add_keyed(tree.node_plane(node), group);
    }
    for (Group& group : groups.own_plane) {
        add_keyed(group.plane, group);
    }
    std::sort(keyed.begin(), keyed.end(), [](const Keyed& a, const Keyed& b) {
        return a.normal.x != b.normal.x ? a.normal.x < b.normal.x : a.offset < b.offset;
    });
    std::vector<Group> merged;
    std::vector<bool> used(keyed.size(), false);
    for (size_t i = 0; i < keyed.size(); ++i) {
        if (used[i]) {
            continue;
        }
        Group g;
        g.normal = keyed[i].normal;
        for (size_t j = i; j < keyed.size() && keyed[j].normal.x - keyed[i].normal.x <= angle;
             ++j) {
            if (used[j] || glm::length(keyed[j].normal - keyed[i].normal) > angle ||
                std::abs(keyed[j].offset - keyed[i].offset) > coincide) {
                continue;
            }
            used[j] = true;
            Group& source = *keyed[j].group;
            std::vector<Face>& front = keyed[j].flipped ? g.back : g.front;
            std::vector<Face>& back = keyed[j].flipped ? g.front : g.back;
            front.insert(front.end(), source.front.begin(), source.front.end());
            back.insert(back.end(), source.back.begin(), source.back.end());
        }
        merged.push_back(std::move(g));
    }
    return merged;
}

// What the two sides of one group do not cancel, with what became of each piece face.
struct Uncovered {
    std::vector<BoundaryFace> faces;
    size_t kept_whole = 0, split = 0, dropped = 0;
};

Uncovered uncovered_faces(const Group& group, size_t index, double epsilon) {
    Uncovered result;
    std::vector<Fragment> front, back;
    std::vector<const Polygon*> origins;
    for (const bool is_front : {true, false}) {
        for (const Face& face : is_front ? group.front : group.back) {
            (is_front ? front : back)
                .push_back({*face.polygon, face.beam, uint32_t(origins.size())});
            origins.push_back(face.polygon);
        }
    }
    // A face behind the plane points along its normal.
    cancel(front, back, group.normal, epsilon);
    std::vector<uint32_t> parts(origins.size(), 0);
    std::vector<bool> whole(origins.size(), false);
    for (const std::vector<Fragment>* side : {&front, &back}) {
        for (const Fragment& f : *side) {
            ++parts[f.origin];
            whole[f.origin] = f.polygon.vertices == origins[f.origin]->vertices;
        }
    }
    for (size_t o = 0; o < origins.size(); ++o) {
        if (parts[o] == 0) {
            ++result.dropped;
        } else if (parts[o] == 1 && whole[o]) {
            ++result.kept_whole;
        } else {
            ++result.split;
        }
    }
    for (std::vector<Fragment>* side : {&front, &back}) {
        const auto plane = int32_t(2 * index + (side == &front ? 1 : 0));
        for (Fragment& f : *side) {
            result.faces.push_back({f.beam, std::move(f.polygon), plane});
        }
    }
    return result;
}

}  // namespace

std::vector<BoundaryFace> boundary_faces(const BeamTree& tree, const Regions& regions,
                                         Region region, BoundaryStats* stats) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<BoundaryFace> faces;
    BoundaryStats s;
    FaceGroups groups =
        group_faces(tree, regions.pieces[size_t(region)], 1e-2 * tree.epsilon(), faces, s);
    const std::vector<Group> merged = merge_coincident(tree, groups);
    // Per group in parallel.
    const double epsilon = Regions::kCutEpsilon * tree.epsilon();
    std::vector<Uncovered> results(merged.size());
    tbb::parallel_for(size_t(0), merged.size(),
                      [&](size_t g) { results[g] = uncovered_faces(merged[g], g, epsilon); });
    for (Uncovered& result : results) {
        s.kept_whole += result.kept_whole;
        s.split += result.split;
        s.dropped += result.dropped;
        std::move(result.faces.begin(), result.faces.end(), std::back_inserter(faces));
    }
    s.faces = faces.size();
    s.ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (stats) {
        *stats = s;
    }
    return faces;
}

std::vector<BoundaryFace> closed_boundary(const BeamTree& tree, const Regions& regions,
                                          Region region, BoundaryStats* stats) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<BoundaryFace> faces = boundary_faces(tree, regions, region, stats);
    std::vector<Polygon*> pointers;
    for (BoundaryFace& face : faces) {
        pointers.push_back(&face.polygon);
    }
    make_conforming(pointers, Regions::kConformingTolerance * std::cbrt(regions.influence_volume));
    std::erase_if(faces, [](const BoundaryFace& face) { return face.polygon.size() < 3; });
    const size_t cracks = close_cracks(faces);
    if (stats) {
        stats->cracks = cracks;
        stats->ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
    }
    return faces;
}

RegionMesh boundary_mesh(const BeamTree& tree, const Regions& regions, Region region,
                         BoundaryStats* stats, BoundaryShape shape) {
    const auto start = std::chrono::steady_clock::now();
    BoundaryStats s;
    const std::vector<BoundaryFace> faces = closed_boundary(tree, regions, region, &s);
    RegionMesh mesh;
    if (shape == BoundaryShape::fragments) {
        for (const BoundaryFace& face : faces) {
            mesh.add_fanned(face.polygon, face.beam);
        }
    } else {
        std::vector<PlanarFace> planar;
        planar.reserve(faces.size());
        for (const BoundaryFace& face : faces) {
            planar.push_back({&face.polygon, face.beam, face.plane});
        }
        mesh = maximal_polygon_mesh(
            planar, Regions::kConformingTolerance * std::cbrt(regions.influence_volume), s.merge);
    }
    s.triangles = mesh.triangles.size();
    s.ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (stats) {
        *stats = s;
    }
    return mesh;
}

}  // namespace sl::bt
