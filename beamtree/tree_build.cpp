// How the beam tree is built: what it is offered (each object's light-facing outer and inner
// faces, or its exact triangles as coplanar faces), in what order (nearest to the light first),
// what it leaves out (objects and clusters of faces outside the influence pyramid, and the rest of
// an object or a cluster once its box is hidden behind what is in), and the grid of sub-beams cut
// at the top of the tree of a large offer (TreeBuild). An object cut into clusters is offered
// cluster by cluster, each opened (its faces' distances found, its faces ordered among the rest)
// only when the order reaches its box. The tree itself, its insertion and queries: beam_tree.cpp.

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

#include <glm/geometric.hpp>

#include "beamtree/beam_tree.h"
#include "core/error.h"
#include "core/sort_by_key.h"

namespace sl::bt {

// A polygon as the tree takes it, nearest to the light first: the result does not depend on the
// order, but a farther polygon then mostly lands in leaves a nearer one already closed, and is
// dropped there without splitting them.
struct Inserting {
    double distance;         // an exact triangle's closest point; a volume's faces: its box
    const Polygon* polygon;  // the caller's, not copied
    Plane plane;             // facing the light
    BeamTree::Role role;
    bool reversed = false;  // a triangle wound the other way about `plane`: turned when inserted
    // An exact face's boxes (indices into Offer::boxes): its object's, and its cluster's where
    // the object has clusters (ObjectVolumes::clusters); else -1.
    int32_t object = -1;
    int32_t cluster = -1;
    // Ties in distance go in this order: the object's place in the volumes, then the polygon's
    // in the object (its faces, or a volume's outer faces and then its inner ones).
    uint64_t rank = 0;
    const Ball* ball = nullptr;  // around `polygon`, where found with it (ObjectVolumes)
};

// The faces of one cluster of an object's exact faces (ObjectVolumes::clusters), offered as one
// entry at the depth of the cluster's box, which no face of it is nearer than: its faces' own
// distances are found, and the faces ordered among the rest, only when the order reaches it and
// the box is not hidden. Most of a building's clusters under the sun never are.
struct OfferedCluster {
    double depth;
    uint32_t object;          // index into the volumes
    uint32_t cluster;         // index into the object's clusters
    int32_t object_box, box;  // indices into Offer::boxes
    uint32_t facing;          // its faces the tree takes (takes_face)
    bool outward_only;
};

struct BeamTree::Offer {
    std::vector<Inserting> polygons;
    // Nearest first, ties in the order of `polygons`: (distance, index) keys, a quarter of the
    // bytes of the entries themselves.
    std::vector<std::pair<double, uint32_t>> order;
    // The clusters, and their order by (depth, index): (depth, index) keys.
    std::vector<OfferedCluster> clusters;
    std::vector<std::pair<double, uint32_t>> cluster_order;
    // The boxes asked about (BeamTree::hidden_beyond): per object of kHidingFaces or more exact
    // faces, its box, then its clusters'. Their light-facing faces are found at each question:
    // most clusters are never asked about.
    std::vector<std::pair<dvec3, dvec3>> boxes;
    // Every polygon offered: `polygons` and the clusters' faces that the tree takes; and of
    // those, the faces of clusters whose box lies outside the influence, left out unopened.
    size_t count = 0;
    size_t left_out = 0;
};

namespace {

// The box around the polygons' vertices: its least and greatest corners.
std::pair<dvec3, dvec3> bounds_of(const std::vector<Polygon>& polygons) {
    dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
    for (const Polygon& polygon : polygons) {
        for (const dvec3& v : polygon.vertices) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
    }
    return {lo, hi};
}

// From p to the box around the polygons (an object's outer volume).
double distance_to_box(const dvec3& p, const std::vector<Polygon>& polygons) {
    const auto [lo, hi] = bounds_of(polygons);
    return glm::length(glm::max(dvec3(0.0), glm::max(lo - p, p - hi)));
}

// The tree needs the light outside every outer volume; an error that says what to do otherwise.
void require_light_outside(const std::vector<ObjectVolumes>& volumes, const dvec3& light,
                           double epsilon) {
    for (const ObjectVolumes& object : volumes) {
        // Triangles need the light outside no volume: one through the light is edge-on to it.
        if (object.triangles.empty() && object.outer.contains(light, -epsilon)) {
            fail(
                "the light at ({}, {}, {}) is inside the outer bounding volume of object {}{}: "
                "the beam tree needs the light outside every outer volume (move the light out of "
                "it; or make the objects exact occluders, [beamtree] occluders = \"triangles\"; "
                "or cut the object into convex pieces, [beamtree] "
                "pieces = true, when the light is outside each piece; or use a method without "
                "regions: planes, march, froxel, lightvolume, epipolar)",
                light.x, light.y, light.z,
                object.name.empty() ? std::to_string(object.object) : "'" + object.name + "'",
                object.pieces > 1
                    ? fmt::format(" (its convex piece {} of {})", object.piece + 1, object.pieces)
                    : "");
        }
    }
}

// Into `faces`: the faces of the box `bounds` whose outward side faces the light by more than ε
// (`side(plane)`: BeamTree::light_side); every ray into the box enters through one of them. For
// a light at a point: none where the light lies within ε of a face's plane (the light inside, or
// on the edge of, what the faces bound). For `parallel` beams a face within ε of edge-on is left
// out instead: no ray enters the box through it (a sun whose direction has a zero component has
// two such faces on every box).
template <typename Side>
void facing_box_faces(const std::pair<dvec3, dvec3>& bounds, const Side& side, double epsilon,
                      bool parallel, std::vector<Polygon>& faces) {
    // Named copies, not a structured binding: clang 14 (the fuzz build's) lets no lambda
    // capture one.
    const dvec3 lo = bounds.first;
    const dvec3 hi = bounds.second;
    auto corner = [&](int i) {
        return dvec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    };
    // -x, +x, -y, +y, -z, +z: each face's corners counter-clockwise about its outward normal.
    constexpr int kCorners[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                    {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    const Plane planes[6] = {{{-1, 0, 0}, lo.x}, {{1, 0, 0}, -hi.x}, {{0, -1, 0}, lo.y},
                             {{0, 1, 0}, -hi.y}, {{0, 0, -1}, lo.z}, {{0, 0, 1}, -hi.z}};
    // The faces are written over the last question's, in their storage: a sun faces the same
    // three faces of every box.
    size_t count = 0;
    for (int f = 0; f < 6; ++f) {
        const double s = side(planes[f]);
        if (std::abs(s) <= epsilon) {
            if (parallel) {
                continue;
            }
            faces.clear();
            return;
        }
        if (s > epsilon) {
            if (faces.size() == count) {
                faces.emplace_back();
            }
            Polygon& face = faces[count++];
            const int* c = kCorners[f];
            face.clear();
            for (int k = 0; k < 4; ++k) {
                face.vertices.push_back(corner(c[k]));
            }
        }
    }
    faces.resize(count);
}

// An opaque triangle stops the light whatever its winding: it goes in facing the light, as an
// occluder and a stopper on the same plane at once, so that behind it the leaf is a blocker
// whose uncertain layer (between occluder and stopper) is empty: unlit, exactly. Each triangle
// is placed by its own distance, so that the triangles of neighbouring objects interleave.
// Degenerate triangles cover nothing and are left out. With `closed` (the light outside the
// object's bounds, and some of its faces on closed components), a triangle that lies on a closed
// component wound outward (ObjectVolumes::closed_faces) and faces away from the light is left out
// too: it blocks nothing the others do not (closed_surface.h).
// True when the tree takes face f; then, where asked for, `plane` facing the light and
// `reversed` where the face is wound the other way about it (counting the faces asks for
// neither: no plane is copied). `side(plane)`: the light's signed distance from a plane
// (BeamTree::light_side).
template <typename Side>
bool takes_face(const ObjectVolumes& object, size_t f, const Side& side, bool closed,
                Plane* plane = nullptr, bool* reversed = nullptr) {
    Plane through;
    const Plane* wound = &through;  // the face's plane as wound
    if (!object.face_planes.empty()) {
        wound = &object.face_planes[f];
        if (wound->normal == dvec3(0.0)) {
            return false;
        }
    } else {
        const std::vector<dvec3>& v = object.triangles[f].vertices;
        if (!Plane::through(v[0], v[1], v[2], through)) {
            return false;
        }
    }
    const bool away = side(*wound) < 0.0;
    if (away && closed && object.closed_faces[f]) {
        return false;
    }
    if (plane) {
        *plane = away ? wound->flipped() : *wound;
    }
    if (reversed) {
        *reversed = away;
    }
    return true;
}

// The ball around face f where it was found with the faces, else null.
const Ball* face_ball(const ObjectVolumes& object, size_t f) {
    return object.face_balls.empty() ? nullptr : &object.face_balls[f];
}

// Every face of the object that the tree takes (takes_face), as entries; `nearest(p)`: a
// polygon's distance from the light (BeamTree::nearest_to_light); `rank`: the object's place in
// the volumes, shifted for Inserting::rank.
template <typename Side, typename Nearest>
void add_facing_triangles(const ObjectVolumes& object, const Side& side, const Nearest& nearest,
                          bool outward_only, int32_t object_box, uint64_t rank,
                          std::vector<Inserting>& out) {
    const std::vector<Polygon>& triangles = object.triangles;
    const bool closed = outward_only && !object.closed_faces.empty();
    SL_CHECK(object.closed_faces.empty() || object.closed_faces.size() == triangles.size());
    SL_CHECK(object.face_planes.empty() || object.face_planes.size() == triangles.size());
    SL_CHECK(object.face_balls.empty() || object.face_balls.size() == triangles.size());
    for (size_t f = 0; f < triangles.size(); ++f) {
        Plane plane;
        bool reversed = false;
        if (takes_face(object, f, side, closed, &plane, &reversed)) {
            out.push_back({nearest(triangles[f]), &triangles[f], plane, BeamTree::Role::opaque,
                           reversed, object_box, -1, rank | f, face_ball(object, f)});
        }
    }
}

// The entries' (key, index) pairs, by key and then index: as std::sort orders them, in about
// linear time (sort_by_key).
template <typename T>
std::vector<std::pair<double, uint32_t>> nearest_first(const std::vector<T>& entries,
                                                       double T::*key) {
    SL_CHECK(entries.size() < size_t(std::numeric_limits<uint32_t>::max()));
    std::vector<std::pair<double, uint32_t>> order(entries.size());
    for (size_t i = 0; i < entries.size(); ++i) {
        order[i] = {entries[i].*key, uint32_t(i)};
    }
    sort_by_key(order);
    return order;
}

// True when p lies within `margin` of the box.
bool near_bounds(const std::pair<dvec3, dvec3>& bounds, const dvec3& p, double margin) {
    const auto& [lo, hi] = bounds;
    return glm::all(glm::greaterThanEqual(p, lo - margin)) &&
           glm::all(glm::lessThanEqual(p, hi + margin));
}

}  // namespace

int TreeBuild::grid(size_t polygons) const {
    if (polygons < grid_from || polygons_per_cell == 0) {
        return 1;
    }
    const auto side = int(std::sqrt(double(polygons) / double(polygons_per_cell)));
    return std::clamp(side, 1, max_grid);
}

BeamTree::BeamTree(const SpotLight& light, const std::vector<ObjectVolumes>& volumes,
                   const TreeBuild& build, const std::optional<ViewWindow>& window)
    : apex_(light.position),
      parallel_(light.parallel()),
      axis_(glm::normalize(dvec3(light.direction()))),
      scale_(double(light.far)),
      epsilon_(kRelativeEpsilon * double(light.far)) {
    influence_ = bt::influence_planes(light, window);
    // Root: a chain through the four side planes and the window's cuts (nodes 0 to chain() - 1;
    // the influence planes less the near and far ranges), the inside an open leaf.
    const int32_t chain = this->chain();
    for (int32_t i = 0; i < chain; ++i) {
        Node node;
        node.kind = Kind::split;
        node.plane = influence_[size_t(i < 4 ? i : i + 2)];
        nodes_.push_back(node);
        parents_.push_back(i - 1);
    }
    for (int32_t i = 0; i < chain; ++i) {
        const int32_t out = add_leaf({Kind::out, {}, -1}, i);
        at(i).front = out;
        at(i).back = i + 1 < chain ? i + 1 : add_leaf({Kind::open, {}, -1}, i);
    }
    if (!parallel_) {
        require_light_outside(volumes, apex_, epsilon_);  // a sun is outside every volume
    }
    // One pass, nearest first. A volume's inner faces (its stoppers, Nilsson §5.2.1) follow its
    // outer faces at once: what lies behind the volume then finds the leaf's stopper already
    // there and is dropped, instead of splitting the leaf first. (Nilsson inserts every stopper
    // after every occluder; the regions are the same, and on multiple:1650 the tree is as big
    // and 20 % faster to build this way.)
    Offer offer;
    auto side = [&](const Plane& plane) { return light_side(plane); };
    for (size_t k = 0; k < volumes.size(); ++k) {
        const ObjectVolumes& object = volumes[k];
        const uint64_t rank = uint64_t(k) << 32;
        if (!object.triangles.empty()) {
            // The box around the faces, found with them where it is known. Beyond a plane of the
            // influence, so is every corner of every face (and the box tells in one corner for
            // most objects the window leaves out); else the corners themselves may still be.
            const bool box_known = object.face_bounds.first.x <= object.face_bounds.second.x;
            if ((box_known && box_outside_influence(object.face_bounds)) ||
                outside_influence(object.triangles)) {
                continue;
            }
            const std::pair<dvec3, dvec3> box =
                box_known ? object.face_bounds : bounds_of(object.triangles);
            // An object cut into clusters is offered cluster by cluster (each left out where its
            // box lies outside the influence), any other face by face.
            const bool clustered =
                object.triangles.size() >= kHidingFaces && object.clusters.bounds.size() > 1;
            // Outside the box the light is outside every closed component's solid; inside it (a
            // torus's hole, or the solid itself) every triangle goes in.
            const bool outward_only =
                !object.closed_faces.empty() && (parallel_ || !near_bounds(box, apex_, epsilon_));
            int32_t object_box = -1;
            if (object.triangles.size() >= kHidingFaces) {
                object_box = int32_t(offer.boxes.size());
                offer.boxes.push_back(box);
            }
            if (clustered) {
                offer_clusters(object, uint32_t(k), object_box, outward_only, offer);
                continue;
            }
            add_facing_triangles(
                object, side, [&](const Polygon& triangle) { return nearest_to_light(triangle); },
                outward_only, object_box, rank, offer.polygons);
            continue;
        }
        if (outside_influence(object.outer.faces)) {
            continue;
        }
        // A volume's faces go in together, at the distance of the box around it.
        const double distance = parallel_ ? depth_of_box(object.outer.faces)
                                          : distance_to_box(apex_, object.outer.faces);
        uint64_t place = rank;
        for (size_t f = 0; f < object.outer.faces.size(); ++f) {
            offer.polygons.push_back({distance, &object.outer.faces[f], object.outer.planes[f],
                                      Role::occluder, false, -1, -1, place++});
        }
        for (const ConvexVolume& inner : object.inner) {
            for (size_t f = 0; f < inner.faces.size(); ++f) {
                offer.polygons.push_back({distance, &inner.faces[f], inner.planes[f], Role::stopper,
                                          false, -1, -1, place++});
            }
        }
    }
    offer.order = nearest_first(offer.polygons, &Inserting::distance);
    offer.cluster_order = nearest_first(offer.clusters, &OfferedCluster::depth);
    offer.count += offer.polygons.size();
    add_grid(light, build.grid(offer.count), window.value_or(ViewWindow{}));
    insert_offer(offer, volumes, build.ask_faces);
}

void BeamTree::add_grid(const SpotLight& light, int grid, const ViewWindow& window) {
    // Line k of the grid's grid - 1 lines per axis sits at m = lo + (hi - lo) (k + 1) / grid,
    // across the window (the whole pyramid: lo = -1, hi = 1).
    std::array<std::vector<Plane>, 2> lines;
    for (int axis = 0; axis < 2; ++axis) {
        const double lo = window.lo[axis], hi = window.hi[axis];
        for (int k = 0; k + 1 < grid; ++k) {
            lines[size_t(axis)].push_back(
                bt::beam_plane(light, axis, lo + (hi - lo) * double(k + 1) / grid));
        }
    }
    // The columns' planes, the middle one first (balanced), then each column's rows likewise.
    std::vector<int32_t> columns;
    auto cut = [&](auto&& self, int32_t leaf, int axis, int lo, int hi) -> void {
        if (lo == hi) {
            if (axis == 0) {
                columns.push_back(leaf);
            }
            return;
        }
        const int middle = lo + (hi - lo) / 2;
        const int32_t front = add_leaf({Kind::open, {}, -1}, leaf);
        const int32_t back = add_leaf({Kind::open, {}, -1}, leaf);
        Node& node = at(leaf);
        node.kind = Kind::split;
        node.plane = lines[size_t(axis)][size_t(middle)];
        node.front = front;
        node.back = back;
        self(self, back, axis, lo, middle);
        self(self, front, axis, middle + 1, hi);
    };
    cut(cut, at(chain() - 1).back, 0, 0, grid - 1);
    for (const int32_t column : columns) {
        cut(cut, column, 1, 0, grid - 1);
    }
}

void BeamTree::offer_clusters(const ObjectVolumes& object, uint32_t index, int32_t object_box,
                              bool outward_only, Offer& offer) const {
    const FaceClusters& clusters = object.clusters;
    SL_CHECK(clusters.first.size() == clusters.bounds.size() + 1);
    SL_CHECK(clusters.faces.size() == object.triangles.size());
    SL_CHECK(object.closed_faces.empty() || object.closed_faces.size() == object.triangles.size());
    SL_CHECK(object.face_planes.empty() || object.face_planes.size() == object.triangles.size());
    SL_CHECK(object.face_balls.empty() || object.face_balls.size() == object.triangles.size());
    const bool closed = outward_only && !object.closed_faces.empty();
    const auto first_box = int32_t(offer.boxes.size());
    offer.boxes.insert(offer.boxes.end(), clusters.bounds.begin(), clusters.bounds.end());
    auto side = [&](const Plane& plane) { return light_side(plane); };
    for (size_t c = 0; c < clusters.bounds.size(); ++c) {
        // The faces it takes are counted now (the grid's size and the faces left out count
        // them); their distances wait.
        uint32_t facing = 0;
        for (uint32_t i = clusters.first[c]; i < clusters.first[c + 1]; ++i) {
            facing += takes_face(object, clusters.faces[i], side, closed);
        }
        offer.count += facing;
        if (box_outside_influence(clusters.bounds[c])) {
            offer.left_out += facing;  // as the box's question would have answered
            continue;
        }
        if (facing == 0) {
            continue;
        }
        // ε nearer than the box: no face of it is due before the cluster is opened, whatever
        // the round-off of the two distances.
        offer.clusters.push_back({depth_of_box(clusters.bounds[c]) - epsilon_, index, uint32_t(c),
                                  object_box, first_box + int32_t(c), facing, outward_only});
    }
}

void BeamTree::insert_offer(const Offer& offer, const std::vector<ObjectVolumes>& volumes,
                            bool ask_faces) {
    // Per box of exact faces (an object's, a cluster's): whether the rest of its faces is
    // hidden, and whether that was asked.
    struct Hiding {
        bool hidden = false;
        bool asked = false;
        int32_t start = 0;  // where the box's faces start their descent (deepest_holding)
        bool grew = false;  // the box's last face sent down the tree added nodes to it
    };
    std::vector<Hiding> hiding(offer.boxes.size());
    bool loose_grew = false;  // as Hiding::grew, for the faces of no box
    auto side = [&](const Plane& plane) { return light_side(plane); };
    thread_local std::vector<Polygon> facing;  // a box's light-facing faces, for one question
    // An object whose box lies wholly behind what is in already, from this face's depth on, has
    // nothing left that the tree would keep: each of its faces would descend to nodes that all
    // lie beyond their reach, and be dropped there. Likewise a cluster of its faces. Asked once,
    // at the box's first face (a cluster's: when it is opened, at its box's depth): asked again
    // after 8, 24, 56, ... of them, the answers left out fewer faces than the questions cost
    // (results/beamtree.md).
    auto hidden = [&](int32_t box, double distance) {
        if (box < 0) {
            return false;
        }
        Hiding& h = hiding[size_t(box)];
        if (!h.asked) {
            h.asked = true;
            facing_box_faces(offer.boxes[size_t(box)], side, epsilon_, parallel_, facing);
            h.hidden = !facing.empty() && hidden_beyond(facing, distance);
        }
        return h.hidden;
    };
    hidden_polygons_ += offer.left_out;
    nodes_.reserve(nodes_.size() + 16 * offer.count);
    parents_.reserve(nodes_.capacity());
    // The faces of the clusters opened so far, and those still to go in, nearest first (a heap
    // of (distance, rank, entry)).
    struct Due {
        double distance;
        uint64_t rank;
        uint32_t entry;
        bool operator>(const Due& other) const {
            return distance != other.distance ? distance > other.distance : rank > other.rank;
        }
    };
    thread_local std::vector<Inserting> opened;
    thread_local std::vector<Due> due;
    opened.clear();
    due.clear();
    // Whether a listed entry goes in before the nearest opened face (ranks never tie).
    auto listed_first = [&](const Inserting& o) {
        return due.empty() || due.front() > Due{o.distance, o.rank, 0};
    };
    auto open = [&](const OfferedCluster& group) {
        if (hidden(group.object_box, group.depth) || hidden(group.box, group.depth)) {
            hidden_polygons_ += group.facing;
            return;
        }
        const ObjectVolumes& object = volumes[group.object];
        const FaceClusters& clusters = object.clusters;
        const bool closed = group.outward_only && !object.closed_faces.empty();
        for (uint32_t i = clusters.first[group.cluster]; i < clusters.first[group.cluster + 1];
             ++i) {
            const uint32_t f = clusters.faces[i];
            Plane plane;
            bool reversed = false;
            if (!takes_face(object, f, side, closed, &plane, &reversed)) {
                continue;
            }
            const Polygon& triangle = object.triangles[f];
            const uint64_t rank = uint64_t(group.object) << 32 | f;
            const double distance = nearest_to_light(triangle);
            due.push_back({distance, rank, uint32_t(opened.size())});
            std::push_heap(due.begin(), due.end(), std::greater<>());
            opened.push_back({distance, &triangle, plane, Role::opaque, reversed, group.object_box,
                              group.box, rank, face_ball(object, f)});
        }
    };
    // The order visits the entries, their polygons and their vertices in no order of memory;
    // each first read was a cache miss that the descent waited on. Asked for ahead: an entry
    // and its polygon kLead entries ahead, that polygon's vertices half as far.
    constexpr size_t kLead = 16;
    const size_t count = offer.order.size();
    size_t next = 0, next_cluster = 0;
    for (;;) {
        const Inserting* listed =
            next < count ? &offer.polygons[offer.order[next].second] : nullptr;
        const bool any_due = !due.empty();
        // A cluster opens before any face at its depth or beyond.
        if (next_cluster < offer.cluster_order.size()) {
            const double depth = offer.cluster_order[next_cluster].first;
            if ((!listed || depth <= listed->distance) &&
                (!any_due || depth <= due.front().distance)) {
                open(offer.clusters[offer.cluster_order[next_cluster++].second]);
                continue;
            }
        }
        if (!listed && !any_due) {
            break;
        }
        const Inserting* taken = nullptr;
        if (listed && listed_first(*listed)) {
            taken = listed;
            if (next + kLead < count) {
                const Inserting& ahead = offer.polygons[offer.order[next + kLead].second];
                __builtin_prefetch(&ahead);
                __builtin_prefetch(ahead.polygon);
            }
            if (next + kLead / 2 < count) {
                __builtin_prefetch(
                    offer.polygons[offer.order[next + kLead / 2].second].polygon->vertices.data());
            }
            ++next;
        } else {
            std::pop_heap(due.begin(), due.end(), std::greater<>());
            taken = &opened[due.back().entry];
            due.pop_back();
        }
        const Inserting& o = *taken;
        if (hidden(o.object, o.distance) || hidden(o.cluster, o.distance)) {
            ++hidden_polygons_;
            continue;
        }
        // The face's descent starts below the planes its cluster's (or its object's) box lies
        // wholly on one side of: the same descent, without the top of it.
        int32_t start = 0;
        bool* grew = &loose_grew;
        if (const int32_t box = o.cluster >= 0 ? o.cluster : o.object; box >= 0) {
            Hiding& h = hiding[size_t(box)];
            h.start = deepest_holding(offer.boxes[size_t(box)], h.start);
            start = h.start;
            grew = &h.grew;
        }
        // An exact face is asked about on its own (hidden_beyond) before its descent, unless the
        // last face of its box that went down grew the tree: a box's faces come nearest first,
        // and after one that grew the tree the next is seldom hidden, where asking costs about a
        // third of a descent (results/beamtree.md).
        const bool ask = ask_faces && o.role == Role::opaque && !*grew;
        // An exact face's distance is its own nearest_to_light (add_facing_triangles); a
        // volume's faces share the box's.
        const double known_nearest = o.role == Role::opaque ? o.distance : -1.0;
        const size_t nodes_before = nodes_.size();
        Outcome outcome = Outcome::left_out;
        if (o.reversed) {
            thread_local Polygon flipped;  // its storage kept from face to face
            const std::vector<dvec3>& v = o.polygon->vertices;
            flipped.vertices.assign(v.rbegin(), v.rend());
            outcome = insert(flipped, o.plane, o.role, start, known_nearest, ask, o.ball);
        } else {
            outcome = insert(*o.polygon, o.plane, o.role, start, known_nearest, ask, o.ball);
        }
        if (outcome == Outcome::hidden) {
            ++hidden_polygons_;
        } else if (outcome == Outcome::inserted) {
            *grew = nodes_.size() != nodes_before;
            ++(o.role == Role::occluder  ? outer_polygons_
               : o.role == Role::stopper ? stopper_polygons_
                                         : exact_polygons_);
        }
    }
}

bool BeamTree::box_outside_influence(const std::pair<dvec3, dvec3>& box) const {
    // As outside_influence, of the box's corners: beyond one plane at the corner its normal
    // picks least.
    for (size_t i = 0; i < influence_.size(); ++i) {
        if (i == 4) {
            continue;
        }
        if (influence_[i].distance(least_corner(box, influence_[i].normal)) > epsilon_) {
            return true;
        }
    }
    return false;
}

bool BeamTree::outside_influence(const std::vector<Polygon>& polygons) const {
    // Beyond a side of the influence pyramid or its far range, wholly (not the near range: an
    // object between the light and it still shadows). Such an object casts no shadow inside the
    // pyramid: the root chain would drop each of its polygons, one descent each. A point light's
    // faces each see a part of the scene, so each skips most of it here.
    for (size_t i = 0; i < influence_.size(); ++i) {
        if (i == 4) {
            continue;
        }
        const Plane& plane = influence_[i];
        bool all_outside = true;
        for (const Polygon& polygon : polygons) {
            for (const dvec3& v : polygon.vertices) {
                all_outside &= plane.distance(v) > epsilon_;
            }
            if (!all_outside) {
                break;
            }
        }
        if (all_outside && !polygons.empty()) {
            return true;
        }
    }
    return false;
}

bool BeamTree::wholly_behind(const Polygon& polygon, const Ball& ball, const Plane& plane) const {
    switch (ball.side(plane, epsilon_)) {  // decides only where every vertex would
        case Side::back:
            return true;
        case Side::front:
            return false;
        default:
            break;
    }
    for (const dvec3& v : polygon.vertices) {
        if (!(plane.distance(v) < -epsilon_)) {
            return false;
        }
    }
    return true;
}

int32_t BeamTree::deepest_holding(const std::pair<dvec3, dvec3>& box, int32_t start) const {
    const double margin = 2.0 * epsilon_;
    for (;;) {
        const Node& node = at(start);
        if (node.kind != Kind::split) {
            return start;
        }
        // The plane's least and greatest distance over the box: at the corners its normal picks.
        const dvec3& n = node.plane.normal;
        if (node.plane.distance(least_corner(box, n)) > margin) {
            start = node.front;
        } else if (node.plane.distance(greatest_corner(box, n)) < -margin) {
            start = node.back;
        } else {
            return start;
        }
    }
}

bool BeamTree::hidden_beyond(const std::vector<Polygon>& polygons, double nearest) const {
    for (const Polygon& polygon : polygons) {
        if (!hidden_beyond(polygon, bounding_ball(polygon), nearest, 0)) {
            return false;
        }
    }
    return true;
}

bool BeamTree::hidden_beyond(const Polygon& polygon, const Ball& ball, double nearest,
                             int32_t start) const {
    // Every ray through the polygon, followed down the tree: a polygon that comes within ε of a
    // plane goes down both sides whole (a superset of the rays a fragment of it could take there,
    // whatever ε decides for it), so that the answer never depends on round-off. A ray is done
    // where the node's reach lies nearer than `nearest`, or at a blocker leaf where the polygon
    // lies wholly behind the stopper by more than ε: a ray that crosses a plane facing the light
    // never comes back, so from the polygon on it is unlit there, and a fragment sent down the
    // tree would find itself behind that stopper (or behind a nearer one that took over since)
    // and change nothing. (The reach alone misses the second case wherever the stopper slopes
    // away from the light: its far corner lies beyond the polygon.) The ball decides most planes
    // without a vertex, and only where the vertices would.
    thread_local std::vector<int32_t> stack;
    stack.clear();
    stack.push_back(start);
    while (!stack.empty()) {
        int32_t index = stack.back();
        stack.pop_back();
        for (;;) {
            const Node& node = at(index);
            if (nearest > double(node.reach) || node.kind == Kind::out ||
                (node.kind == Kind::blocker && wholly_behind(polygon, ball, stopper_of(node)))) {
                break;  // unlit beyond its reach or its stopper, or outside the influence
            }
            if (node.kind != Kind::split) {
                return false;  // a leaf that something beyond `nearest` would still change
            }
            const Side passed = ball.side(node.plane, epsilon_);
            if (passed != Side::straddling) {
                index = passed == Side::front ? node.front : node.back;
                continue;
            }
            bool front = false, back = false;
            for (const dvec3& v : polygon.vertices) {
                const double d = node.plane.distance(v);
                front |= d > -epsilon_;
                back |= d < epsilon_;
            }
            if (front && back) {
                stack.push_back(node.back);
            }
            index = front ? node.front : node.back;
        }
    }
    return true;
}
}  // namespace sl::bt
