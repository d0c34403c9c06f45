#include "beamtree/beam_tree.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "core/error.h"

namespace sl::bt {

const char* to_string(Region region) {
    switch (region) {
        case Region::lit:
            return "lit";
        case Region::uncertain:
            return "uncertain";
        case Region::unlit:
            return "unlit";
    }
    return "?";
}

namespace {

// The point of triangle abc closest to p (Ericson, Real-Time Collision Detection §5.1.5).
dvec3 closest_on_triangle(const dvec3& p, const dvec3& a, const dvec3& b, const dvec3& c) {
    const dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) {
        return a;
    }
    const dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) {
        return b;
    }
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        return a + d1 / (d1 - d3) * ab;
    }
    const dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) {
        return c;
    }
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        return a + d2 / (d2 - d6) * ac;
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
        return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
    }
    const double denominator = 1.0 / (va + vb + vc);
    return a + ab * (vb * denominator) + ac * (vc * denominator);
}

// From p to a convex polygon: to the nearest of its fan's triangles.
double distance_to_polygon(const dvec3& p, const Polygon& polygon) {
    const std::vector<dvec3>& v = polygon.vertices;
    double distance = std::numeric_limits<double>::max();
    for (size_t i = 1; i + 1 < v.size(); ++i) {
        distance =
            std::min(distance, glm::length(closest_on_triangle(p, v[0], v[i], v[i + 1]) - p));
    }
    return distance;
}

// The light's up vector made perpendicular to its axis d (glm::lookAt's).
dvec3 up_across(const SpotLight& light, const dvec3& d) {
    return glm::normalize(dvec3(light.up()) - glm::dot(dvec3(light.up()), d) * d);
}

// For parallel beams, the outward plane a x + b y = c across them, x and y the light's right and
// up coordinates in half-widths from the axis, (a, b) a unit vector: its normal a right + b up.
Plane across_beams(const SpotLight& light, double a, double b, double c) {
    const dvec3 d = glm::normalize(dvec3(light.direction()));
    const dvec3 u = up_across(light, d);
    const dvec3 n = a * glm::cross(d, u) + b * u;
    return {n, -glm::dot(n, dvec3(light.position)) - c * double(light.half_width)};
}

}  // namespace

Plane beam_plane(const SpotLight& light, int axis, double m) {
    if (light.parallel()) {
        return across_beams(light, axis == 0 ? 1.0 : 0.0, axis == 0 ? 0.0 : 1.0, m);
    }
    const dvec3 apex(light.position);
    const dvec3 d = glm::normalize(dvec3(light.direction()));
    const dvec3 u = up_across(light, d);
    const dvec3 side = axis == 0 ? glm::cross(d, u) : u;
    const double t = std::tan(glm::radians(double(light.cone_half_angle_degrees)));
    const dvec3 n = glm::normalize(side - m * t * d);
    return {n, -glm::dot(n, apex)};
}

std::vector<Plane> influence_planes(const SpotLight& light,
                                    const std::optional<ViewWindow>& window) {
    SL_CHECK(!window || light.parallel());
    const ViewWindow w = window.value_or(ViewWindow{});
    const dvec3 apex(light.position);
    const dvec3 d = glm::normalize(dvec3(light.direction()));
    // The window's far side in the box's clip space (glm::ortho's z) as a depth along the beams.
    const double near = double(light.near), far = double(light.far);
    const double depth = window ? near + 0.5 * (w.hi.z + 1.0) * (far - near) : far;
    std::vector<Plane> planes = {
        beam_plane(light, 0, w.hi.x),   beam_plane(light, 0, w.lo.x).flipped(),
        beam_plane(light, 1, w.hi.y),   beam_plane(light, 1, w.lo.y).flipped(),
        {-d, glm::dot(d, apex) + near}, {d, -glm::dot(d, apex) - depth}};
    for (const glm::dvec3& cut : w.cuts) {  // a x + b y <= c inside
        planes.push_back(across_beams(light, cut.x, cut.y, cut.z));
    }
    return planes;
}

double BeamTree::depth(const dvec3& p) const {
    return parallel_ ? glm::dot(p - apex_, axis_) : glm::length(p - apex_);
}

double BeamTree::nearest_to_light(const Polygon& polygon) const {
    if (!parallel_) {
        return distance_to_polygon(apex_, polygon);
    }
    double nearest = std::numeric_limits<double>::max();  // a linear depth: least at a corner
    for (const dvec3& v : polygon.vertices) {
        nearest = std::min(nearest, depth(v));
    }
    return nearest;
}

double BeamTree::depth_of_box(const std::vector<Polygon>& polygons) const {
    double nearest = std::numeric_limits<double>::max();
    for (const Polygon& polygon : polygons) {
        nearest = std::min(nearest, nearest_to_light(polygon));
    }
    return nearest;
}

double BeamTree::depth_of_box(const std::pair<dvec3, dvec3>& box) const {
    if (!parallel_) {
        return glm::length(glm::max(dvec3(0.0), glm::max(box.first - apex_, apex_ - box.second)));
    }
    return depth(least_corner(box, axis_));  // a linear depth: least at a corner
}

bool BeamTree::edge_plane(const dvec3& a, const dvec3& b, Plane& plane) const {
    if (!parallel_) {
        return Plane::through(apex_, a, b, plane);
    }
    // The limit of the plane through L, a and b as L recedes against the beams (L = a - R·axis,
    // R -> ∞): its normal is (a - L) × (b - L) / R -> (a - b) × axis.
    const dvec3 n = glm::cross(a - b, axis_);
    const double length = glm::length(n);
    if (!(length > 1e-12 * glm::length(a - b))) {
        return false;
    }
    plane.normal = n / length;
    plane.offset = -glm::dot(plane.normal, a);
    return true;
}

void BeamTree::set_leaf(int32_t index, const Leaf& leaf) {
    Node& node = at(index);
    node.kind = leaf.kind;
    node.plane = leaf.occluder;
    node.front = -1;
    node.back = leaf.stopper;
    node.reach = leaf.kind == Kind::blocker ? leaf.reach : kUnbounded;
}

int32_t BeamTree::add_leaf(const Leaf& leaf, int32_t parent) {
    nodes_.emplace_back();
    parents_.push_back(parent);
    set_leaf(int32_t(nodes_.size() - 1), leaf);
    return int32_t(nodes_.size() - 1);
}

void BeamTree::lower_reach_above(int32_t index) {
    for (int32_t p = parents_[size_t(index)]; p >= 0; p = parents_[size_t(p)]) {
        Node& node = at(p);
        const float reach = std::max(at(node.front).reach, at(node.back).reach);
        if (reach == node.reach) {
            return;  // unchanged here, so above too
        }
        node.reach = reach;
    }
}

namespace {

// Vertex storage of fragments that are done, for the next splits: without it each split of a
// descending fragment allocates two polygons and frees one (a tenth of the instructions of the
// room's point-light trees).
std::vector<std::vector<dvec3>>& spare_vertices() {
    thread_local std::vector<std::vector<dvec3>> spare;
    return spare;
}

// An empty polygon, with storage from a finished fragment where there is one.
Polygon reused_polygon() {
    Polygon polygon;
    std::vector<std::vector<dvec3>>& spare = spare_vertices();
    if (!spare.empty()) {
        polygon.vertices = std::move(spare.back());
        spare.pop_back();
    }
    return polygon;
}

// Gives a finished fragment's storage back for reuse.
void recycle(Polygon&& fragment) {
    constexpr size_t kKept = 64;  // what one descent has in flight, with room to spare
    std::vector<std::vector<dvec3>>& spare = spare_vertices();
    if (spare.size() < kKept && fragment.vertices.capacity() > 0) {
        fragment.vertices.clear();
        spare.push_back(std::move(fragment.vertices));
    }
}

}  // namespace

BeamTree::Outcome BeamTree::insert(const Polygon& polygon, const Plane& plane, Role role,
                                   int32_t start, double nearest, bool ask_hidden,
                                   const Ball* known_ball) {
    // Only light-facing polygons occlude; edge-on ones (L within ε of their plane) add nothing.
    if (light_side(plane) <= epsilon_ || !area_exceeds(polygon, epsilon_ * epsilon_)) {
        return Outcome::left_out;
    }
    // Nothing beyond the far range matters (Nilsson §4.2): clip to the backplate first.
    // (as split(...).back, into a finished fragment's storage instead of a new one)
    Polygon clipped = reused_polygon();
    // One ball for all of its fragments: what bounds the polygon bounds its fragments. Most
    // polygons lie wholly inside the far range, which the ball tells without a vertex's distance.
    Ball ball = known_ball ? *known_ball : bounding_ball(polygon);
    Side far_side = ball.side(influence_[5], epsilon_);
    if (far_side == Side::straddling) {
        thread_local Polygon beyond;  // the part past the far range: dropped
        beyond.clear();
        far_side = split_straddling(polygon, influence_[5], epsilon_, false, beyond, clipped);
        if (far_side == Side::straddling) {
            ball = bounding_ball(clipped);
        }
    }
    switch (far_side) {
        case Side::back:
            clipped.vertices.assign(polygon.vertices.begin(), polygon.vertices.end());
            clipped.on_split_plane = polygon.on_split_plane;
            break;
        case Side::straddling:
            break;
        case Side::front:
        case Side::coplanar:
            clipped.clear();
            break;
    }
    if (clipped.empty()) {
        recycle(std::move(clipped));
        return Outcome::left_out;
    }
    const bool stops = role != Role::occluder;
    const bool whole = far_side == Side::back;
    Inserted inserted{role, plane, -1,
                      whole && nearest >= 0.0 ? nearest : nearest_to_light(clipped)};
    if (ask_hidden && hidden_beyond(clipped, ball, inserted.nearest, start)) {
        recycle(std::move(clipped));
        return Outcome::hidden;
    }
    if (stops) {
        inserted.stopper = int32_t(stoppers_.size());
        stoppers_.push_back(plane);
    }

    // Fragments waiting for their descent; kept between calls so that it allocates once.
    thread_local std::vector<Pending> stack;
    stack.clear();
    stack.push_back({start, std::move(clipped), ball});
    while (!stack.empty()) {
        Pending next = std::move(stack.back());
        stack.pop_back();
        const int32_t leaf = descend(next.node, inserted.nearest, next.fragment, next.ball, stack);
        if (leaf >= 0) {
            insert_at_leaf(leaf, next.fragment, next.ball, inserted, stack);
        }
        recycle(std::move(next.fragment));
    }
    return Outcome::inserted;
}

int32_t BeamTree::descend(int32_t index, double nearest, Polygon& fragment, const Ball& ball,
                          std::vector<Pending>& stack) const {
    // Descend while the fragment lies on one side: no copies on the way down, and the parts of
    // a split reuse storage (the far part, going onto the stack, takes a finished fragment's).
    thread_local Polygon front, back;  // empty between splits
    front.clear();
    int32_t found = -1;
    for (;;) {
        const Node& node = at(index);
        if (nearest > double(node.reach)) {
            break;  // behind every stopper below: hidden wherever it would land
        }
        if (node.kind != Kind::split) {
            found = index;
            break;
        }
        const Side passed = ball.side(node.plane, epsilon_);  // most planes pass it by
        if (passed != Side::straddling) {
            index = passed == Side::front ? node.front : node.back;
            continue;
        }
        // A part that would land behind its child's reach is dropped there: not made at all.
        const bool front_hidden = nearest > double(at(node.front).reach);
        const bool back_hidden = nearest > double(at(node.back).reach);
        const Parts parts = back_hidden ? Parts::front : front_hidden ? Parts::back : Parts::both;
        uint64_t touching = 0;
        const Side where = split_straddling(fragment, node.plane, epsilon_, true, front, back,
                                            &touching, kCoincident * epsilon_, parts);
        if (where == Side::coplanar) {
            break;  // on a plane through L: edge-on to the light, occludes nothing
        }
        if (where != Side::straddling) {
            // An edge on the plane (shared with the polygon whose edge made it) already has
            // its plane on the path: attach() adds none for it.
            fragment.on_split_plane |= touching;
            index = where == Side::front ? node.front : node.back;
            continue;
        }
        // Slivers thinner than the planes' thickness add nothing but nodes.
        if (area_exceeds(back, epsilon_ * epsilon_)) {
            stack.push_back({node.back, std::move(back), ball});
            back = reused_polygon();
        } else {
            back.clear();
        }
        if (!area_exceeds(front, epsilon_ * epsilon_)) {
            break;
        }
        std::swap(fragment, front);  // the old fragment's storage takes the next front part
        front.clear();
        index = node.front;
    }
    return found;
}

void BeamTree::insert_at_leaf(int32_t index, const Polygon& fragment, const Ball& ball,
                              const Inserted& inserted, std::vector<Pending>& stack) {
    // Each leaf keeps the nearest occluder and the nearest stopper over its beam (the stopper
    // never nearer than the occluder): a fragment takes over the part of the leaf where it is
    // nearer than what the leaf has, whatever the order of insertion.
    const Node node = at(index);
    if (node.kind == Kind::split || node.kind == Kind::out) {
        return;
    }
    const Leaf here{node.kind, node.plane, node.kind == Kind::blocker ? node.back : -1, node.reach};
    switch (inserted.role) {
        case Role::occluder:
            switch (node.kind) {
                case Kind::open:  // appendix B attachPolygon
                    attach(index, fragment, {Kind::solid, inserted.plane, -1}, here);
                    break;
                case Kind::solid:
                case Kind::blocker:
                    // Fix-up: the part nearer to L than the current occluder takes over; a
                    // blocker keeps its stopper, which lies behind both.
                    attach_nearer(index, fragment, node.plane,
                                  {node.kind, inserted.plane, here.stopper, here.reach}, here);
                    break;
                default:
                    break;
            }
            break;
        case Role::stopper:
            switch (node.kind) {
                case Kind::solid:
                    attach(index, fragment,
                           {Kind::blocker, node.plane, inserted.stopper, here.reach, true}, here);
                    break;
                case Kind::blocker:  // keep the nearest stopper, as for occluders
                    attach_nearer(index, fragment, stopper_of(node),
                                  {Kind::blocker, node.plane, inserted.stopper, here.reach, true},
                                  here);
                    break;
                default:
                    break;  // an inner face where no occluder is: outside its own outer volume
            }
            break;
        case Role::opaque: {
            // Occluder and stopper at once: where it is nearer than the leaf's occluder it is
            // both (unlit right behind it); behind the occluder it is the nearer stopper.
            const Leaf opaque{Kind::blocker, inserted.plane, inserted.stopper, here.reach, true};
            if (node.kind == Kind::open) {
                attach(index, fragment, opaque, here);
                break;
            }
            switch (side(fragment, node.plane, epsilon_)) {
                case Side::front:
                    attach(index, fragment, opaque, here);
                    return;
                case Side::straddling: {
                    Split parts = split(fragment, node.plane, epsilon_);
                    if (area_exceeds(parts.front, epsilon_ * epsilon_)) {
                        attach(index, parts.front, opaque, here);
                    }
                    // The leaf is now a subtree: the part behind goes down it again, to the
                    // leaves outside the front part's beam, which are this leaf as it was.
                    if (area_exceeds(parts.back, epsilon_ * epsilon_)) {
                        stack.push_back({index, std::move(parts.back), ball});
                    }
                    return;
                }
                case Side::back:
                case Side::coplanar:
                    break;
            }
            const Leaf stopped{Kind::blocker, node.plane, inserted.stopper, here.reach, true};
            if (node.kind == Kind::solid) {
                attach(index, fragment, stopped, here);
            } else {
                attach_nearer(index, fragment, stopper_of(node), stopped, here);
            }
            break;
        }
    }
}

void BeamTree::attach_nearer(int32_t index, const Polygon& fragment, const Plane& current,
                             const Leaf& inside, const Leaf& outside) {
    switch (side(fragment, current, epsilon_)) {
        case Side::front:
            attach(index, fragment, inside, outside);
            break;
        case Side::straddling: {
            // The part nearer than the current plane. A sliver of it is left out, as insert()
            // leaves slivers out: its edges are shorter than ε, and attach() skips those, so its
            // beam would stay open across the whole leaf.
            const Polygon front = split(fragment, current, epsilon_).front;
            if (area_exceeds(front, epsilon_ * epsilon_)) {
                attach(index, front, inside, outside);
            }
            break;
        }
        case Side::back:
        case Side::coplanar:
            break;  // hidden behind, or on, what the leaf already has
    }
}

namespace {

// The fragment's corners with those closer than `coincident` merged into one, and per corner
// whether the edge leaving it lies on a plane of the path.
void merge_corners(const Polygon& fragment, double coincident, std::vector<dvec3>& corners,
                   std::vector<char>& on_split) {
    corners.clear();
    on_split.clear();
    for (size_t i = 0; i < fragment.size(); ++i) {
        const dvec3& v = fragment.vertices[i];
        if (corners.empty() || glm::length(v - corners.back()) > coincident) {
            corners.push_back(v);
            on_split.push_back(fragment.edge_on_split_plane(i));
        } else {
            on_split.back() = fragment.edge_on_split_plane(i);  // the merged edge leaves from v
        }
    }
    while (corners.size() > 1 && glm::length(corners.front() - corners.back()) <= coincident) {
        corners.pop_back();  // merged into the first corner; the closing edge leaves from it
        on_split.pop_back();
    }
}

// Whether the planes of the neighbours of edge i (corners[i] to corners[i + 1]) meet within
// 4 `epsilon` beyond it, `normal` being the corners' area vector.
bool closes_near(const std::vector<dvec3>& corners, size_t i, const dvec3& normal, double epsilon) {
    const size_t n = corners.size();
    const dvec3& a = corners[i];
    const dvec3& b = corners[(i + 1) % n];
    const dvec3 before = a - corners[(i + n - 1) % n];  // runs on past a
    const dvec3 after = b - corners[(i + 2) % n];       // runs on past b
    const double length = glm::length(b - a);
    if (!(glm::length(normal) > 0.0)) {
        return true;  // no area: nothing for a plane to bound
    }
    const dvec3 along = (b - a) / length;
    const dvec3 out = glm::normalize(glm::cross(along, normal));  // away from the fragment
    const double rise_a = glm::dot(before, out), rise_b = glm::dot(after, out);
    if (!(rise_a > 0.0) || !(rise_b > 0.0)) {
        return false;
    }
    // Beyond the edge at height h, the neighbours are at a + h·cot_a and b + h·cot_b
    // along it: they meet where h (cot_a - cot_b) = length.
    const double closing = glm::dot(before, along) / rise_a - glm::dot(after, along) / rise_b;
    return closing > 0.0 && length <= 4.0 * epsilon * closing;
}

}  // namespace

bool BeamTree::edge_planes(const std::vector<dvec3>& corners, const std::vector<char>& on_split,
                           std::vector<Plane>& edges) const {
    // An edge shorter than ε gets no plane of its own (Nilsson §4.3: the planes are ε thick)
    // only where its neighbours' planes meet within 4ε beyond it, so that the beam grows by no
    // more than that. Where they part (a sliver's tip cut off by a nearer occluder), the edge gets
    // its plane, or the beam would run on across the rest of the leaf, which would then take the
    // new occluder where the fragment is not.
    const size_t n = corners.size();
    dvec3 normal(0.0), center(0.0);  // Newell's area vector, and the corners' centroid
    for (size_t i = 0; i < n; ++i) {
        normal += glm::cross(corners[i] - corners[0], corners[(i + 1) % n] - corners[0]);
        center += corners[i] / double(n);
    }
    edges.clear();
    for (size_t i = 0; i < n; ++i) {
        if (on_split[i]) {
            continue;
        }
        const dvec3& a = corners[i];
        const dvec3& b = corners[(i + 1) % n];
        if (glm::length(b - a) <= epsilon_ && closes_near(corners, i, normal, epsilon_)) {
            continue;
        }
        Plane plane;
        if (!edge_plane(a, b, plane)) {
            continue;  // the edge points at the light
        }
        const double side = plane.distance(center);
        if (std::abs(side) <= 0.01 * epsilon_) {
            return false;  // the whole fragment is edge-on to the light
        }
        edges.push_back(side > 0.0 ? plane.flipped() : plane);
    }
    return true;
}

void BeamTree::attach(int32_t index, const Polygon& fragment, const Leaf& inside,
                      const Leaf& outside) {
    // Planes through L and each edge of the fragment that does not already lie on a plane of
    // the path, oriented with the fragment behind (appendix B attachPolygon). The leaf becomes
    // the fragment's beam, so the planes must bound it.
    // Corners closer than 1e-3 ε (clipping's near-duplicates) are one corner: the plane through
    // L and an edge of length l at distance D from L is good to about 1e-16 D / l radians, which
    // such an edge would not be.
    thread_local std::vector<dvec3> corners;  // allocated once per thread
    thread_local std::vector<char> on_split;  // the edge leaving corners[i] lies on a path plane
    thread_local std::vector<Plane> edges;
    merge_corners(fragment, 1e-3 * epsilon_, corners, on_split);
    if (corners.size() < 3 || !edge_planes(corners, on_split, edges)) {
        return;  // no area, or edge-on to the light
    }
    // Rewrite the leaf in place as a chain: each edge plane's front is outside the fragment's
    // beam; the last back is the fragment's beam.
    int32_t current = index;
    for (const Plane& plane : edges) {
        const int32_t front = add_leaf(outside, current);
        const int32_t back = add_leaf(outside, current);
        Node& node = at(current);
        node.kind = Kind::split;
        node.plane = plane;
        node.front = front;
        node.back = back;
        current = back;
    }
    Leaf beam = inside;
    if (beam.stopped_here) {
        // Every ray of the beam crosses the fragment, no farther than its farthest corner.
        double farthest = 0.0;
        for (const dvec3& v : fragment.vertices) {
            farthest = std::max(farthest, depth(v));
        }
        float up = float(farthest);
        if (double(up) < farthest) {
            up = std::nextafter(up, kUnbounded);
        }
        beam.reach = std::min(beam.reach, up);
    }
    set_leaf(current, beam);
    // The chain's reach, from the beam up; above it, as far as it falls.
    while (current != index) {
        current = parents_[size_t(current)];
        Node& node = at(current);
        node.reach = std::max(at(node.front).reach, at(node.back).reach);
    }
    lower_reach_above(index);
}

Region BeamTree::classify(const dvec3& p, double* margin) const {
    double closest = std::numeric_limits<double>::max();
    auto record = [&](double distance) { closest = std::min(closest, std::abs(distance)); };
    Region region = Region::unlit;
    bool inside = true;
    for (size_t i = 4; i < 6; ++i) {  // near and far ranges; the sides are the tree's root chain
        const double distance = influence_[i].distance(p);
        record(distance);
        inside &= distance < 0.0;
    }
    if (inside) {
        int32_t index = 0;
        while (at(index).kind == Kind::split) {
            const Node& node = at(index);
            const double distance = node.plane.distance(p);
            record(distance);
            index = distance >= 0.0 ? node.front : node.back;  // Nilsson Program 2
        }
        const Node& leaf = at(index);
        region = leaf_region(leaf, p);
        if (leaf.kind == Kind::solid) {
            record(leaf.plane.distance(p));
        } else if (leaf.kind == Kind::blocker) {
            record(leaf.plane.distance(p));
            record(stopper_of(leaf).distance(p));
        }
    }
    if (margin) {
        *margin = closest;
    }
    return region;
}

Region BeamTree::leaf_region(const Node& leaf, const dvec3& p) const {
    switch (leaf.kind) {
        case Kind::open:
            return Region::lit;
        case Kind::solid:
            return leaf.plane.distance(p) > 0.0 ? Region::lit : Region::uncertain;
        case Kind::blocker:
            return leaf.plane.distance(p) > 0.0         ? Region::lit
                   : stopper_of(leaf).distance(p) > 0.0 ? Region::uncertain
                                                        : Region::unlit;
        case Kind::out:
        case Kind::split:
            break;
    }
    return Region::unlit;
}

namespace {

// Appends intervals to a trace's answer, joining neighbours of one region and dropping empty ones.
struct IntervalWriter {
    std::vector<RegionInterval>& out;
    void emit(Region region, double begin, double end) {
        if (!(end > begin)) {
            return;
        }
        if (!out.empty() && out.back().region == region) {
            out.back().end = end;
        } else {
            out.push_back({region, begin, end});
        }
    }
};

// The plane's signed distance along the ray, a + b t.
struct Crossing {
    double a, b;
    Crossing(const Plane& plane, const dvec3& origin, const dvec3& direction)
        : a(plane.distance(origin)), b(glm::dot(plane.normal, direction)) {}
};

}  // namespace

void BeamTree::trace(const dvec3& origin, const dvec3& direction, double t0, double t1,
                     std::vector<RegionInterval>& out) const {
    out.clear();
    IntervalWriter writer{out};
    // Inside the near and far ranges: both distances negative (classify's test).
    double inside0 = t0, inside1 = t1;
    for (size_t i = 4; i < 6; ++i) {
        const Crossing c(influence_[i], origin, direction);
        if (c.b == 0.0) {
            if (!(c.a < 0.0)) {
                inside1 = inside0;
            }
        } else if (c.b > 0.0) {
            inside1 = std::min(inside1, -c.a / c.b);
        } else {
            inside0 = std::max(inside0, -c.a / c.b);
        }
    }
    if (!(inside1 > inside0)) {
        writer.emit(Region::unlit, t0, t1);
        return;
    }
    writer.emit(Region::unlit, t0, inside0);
    // Depth-first down the tree, nearer pieces first: the current piece descends without the
    // stack (a push and pop per node stalls on store forwarding); the farther part of a split
    // waits on it.
    thread_local std::vector<TracePiece> stack;
    stack.clear();
    TracePiece piece{0, inside0, inside1};
    for (;;) {
        const Node& node = at(piece.node);
        if (node.kind == Kind::split) {
            const Crossing c(node.plane, origin, direction);
            const bool front_begin = c.a + c.b * piece.begin >= 0.0;
            const bool front_end = c.a + c.b * piece.end >= 0.0;
            if (front_begin == front_end) {
                piece.node = front_begin ? node.front : node.back;
                continue;
            }
            const double t = c.b != 0.0 ? std::clamp(-c.a / c.b, piece.begin, piece.end)
                                        : 0.5 * (piece.begin + piece.end);
            stack.push_back({front_end ? node.front : node.back, t, piece.end});
            piece = {front_begin ? node.front : node.back, piece.begin, t};
            continue;
        }
        trace_leaf(node, origin, direction, piece, writer.out);
        if (stack.empty()) {
            break;
        }
        piece = stack.back();
        stack.pop_back();
    }
    writer.emit(Region::unlit, inside1, t1);
}

void BeamTree::trace_leaf(const Node& node, const dvec3& origin, const dvec3& direction,
                          const TracePiece& piece, std::vector<RegionInterval>& out) const {
    // The leaf's occluder and stopper cut the piece into at most three parts.
    std::array<double, 4> cuts = {piece.begin, piece.end, piece.end, piece.end};
    size_t count = 1;
    const Plane* planes[2] = {nullptr, nullptr};
    if (node.kind == Kind::solid || node.kind == Kind::blocker) {
        planes[0] = &node.plane;
    }
    if (node.kind == Kind::blocker) {
        planes[1] = &stopper_of(node);
    }
    for (const Plane* plane : planes) {
        if (!plane) {
            continue;
        }
        const Crossing c(*plane, origin, direction);
        if (c.b != 0.0 && -c.a / c.b > piece.begin && -c.a / c.b < piece.end) {
            cuts[count++] = -c.a / c.b;
        }
    }
    if (count == 3 && cuts[2] < cuts[1]) {
        std::swap(cuts[1], cuts[2]);
    }
    cuts[count++] = piece.end;
    IntervalWriter writer{out};
    for (size_t i = 0; i + 1 < count; ++i) {
        const double middle = 0.5 * (cuts[i] + cuts[i + 1]);
        writer.emit(leaf_region(node, origin + middle * direction), cuts[i], cuts[i + 1]);
    }
}

BeamTree::FacePlane BeamTree::face_plane(const dvec3& interior, const Polygon& face,
                                         double tolerance) const {
    // Near the light every plane through it passes within any tolerance of a small face: a face
    // whose normal is well defined must also share the plane's direction.
    const dvec3 area = area_vector(face);
    const double length = glm::length(area);
    const bool oriented = length > tolerance * tolerance;
    const dvec3 normal = oriented ? area / length : dvec3(0.0);
    int32_t index = 0;
    while (at(index).kind == Kind::split) {
        const Node& node = at(index);
        bool on_plane = !oriented || std::abs(glm::dot(normal, node.plane.normal)) > 1.0 - 1e-9;
        for (const dvec3& v : face.vertices) {
            on_plane = on_plane && std::abs(node.plane.distance(v)) <= tolerance;
        }
        const bool front = node.plane.distance(interior) >= 0.0;
        if (on_plane) {
            return {index, front, node.plane};
        }
        index = front ? node.front : node.back;
    }
    return {};
}

BeamTree::Partition BeamTree::partition(const Polygon& polygon) const {
    Partition result;
    // Outside the near and far ranges: unlit.
    Split near_parts = split(polygon, influence_[4], epsilon_);
    if (!near_parts.front.empty())
        result.unlit.push_back(std::move(near_parts.front));
    Split far_parts = split(near_parts.back, influence_[5], epsilon_);
    if (!far_parts.front.empty())
        result.unlit.push_back(std::move(far_parts.front));
    if (far_parts.back.empty()) {
        return result;
    }
    auto divide = [&](Polygon piece, const Plane& plane, std::vector<Polygon>& front,
                      std::vector<Polygon>& back) {
        Split parts = split(piece, plane, epsilon_);
        if (parts.coplanar) {
            back.push_back(std::move(piece));  // on the boundary: the less certain side
            return;
        }
        if (!parts.front.empty())
            front.push_back(std::move(parts.front));
        if (!parts.back.empty())
            back.push_back(std::move(parts.back));
    };
    std::vector<std::pair<int32_t, Polygon>> stack;
    stack.emplace_back(0, std::move(far_parts.back));
    while (!stack.empty()) {
        auto [index, piece] = std::move(stack.back());
        stack.pop_back();
        const Node& node = at(index);
        switch (node.kind) {
            case Kind::split: {
                Split parts = split(piece, node.plane, epsilon_);
                if (parts.coplanar) {
                    stack.emplace_back(node.front, std::move(piece));
                    break;
                }
                if (!parts.front.empty())
                    stack.emplace_back(node.front, std::move(parts.front));
                if (!parts.back.empty())
                    stack.emplace_back(node.back, std::move(parts.back));
                break;
            }
            case Kind::out:
                result.unlit.push_back(std::move(piece));
                break;
            case Kind::open:
                result.lit.push_back(std::move(piece));
                break;
            case Kind::solid:
                divide(std::move(piece), node.plane, result.lit, result.uncertain);
                break;
            case Kind::blocker: {
                std::vector<Polygon> behind;
                divide(std::move(piece), node.plane, result.lit, behind);
                for (Polygon& part : behind) {
                    divide(std::move(part), stopper_of(node), result.uncertain, result.unlit);
                }
                break;
            }
        }
    }
    return result;
}

std::vector<BeamTree::LeafCell> BeamTree::split_cells(Polyhedron cell, double epsilon) const {
    std::vector<LeafCell> out;
    split_cells(0, std::move(cell), epsilon, 0, out);
    return out;
}

void BeamTree::split_cells(int32_t index, Polyhedron cell, double epsilon, int depth,
                           std::vector<LeafCell>& out) const {
    // While a split sends parts to both sides and fewer than kParallelDepth such splits lie
    // above, its two subtrees go to two tasks, each into its own list, joined front first;
    // below that, one thread walks its subtree depth first.
    constexpr int kParallelDepth = 8;
    auto emit_leaf = [&](const Node& node, Polyhedron&& part) {
        if (node.kind == Kind::out) {
            return;
        }
        Beam beam;
        beam.has_occluder = node.kind != Kind::open;
        beam.occluder = node.plane;
        beam.has_stopper = node.kind == Kind::blocker;
        if (beam.has_stopper) {
            beam.stopper = stopper_of(node);
        }
        out.push_back({std::move(part), beam});
    };
    while (depth < kParallelDepth) {
        const Node& node = at(index);
        if (node.kind != Kind::split) {
            emit_leaf(node, std::move(cell));
            return;
        }
        Polyhedron front = clip(cell, node.plane.flipped(), epsilon);
        Polyhedron back = clip(cell, node.plane, epsilon);
        if (front.empty() || back.empty()) {
            if (front.empty() && back.empty()) {
                return;
            }
            index = front.empty() ? node.back : node.front;
            cell = std::move(front.empty() ? back : front);
            continue;
        }
        std::vector<LeafCell> back_cells;
        tbb::parallel_invoke(
            [&] { split_cells(node.front, std::move(front), epsilon, depth + 1, out); },
            [&] { split_cells(node.back, std::move(back), epsilon, depth + 1, back_cells); });
        std::move(back_cells.begin(), back_cells.end(), std::back_inserter(out));
        return;
    }
    std::vector<std::pair<int32_t, Polyhedron>> stack;
    stack.emplace_back(index, std::move(cell));
    while (!stack.empty()) {
        auto [node_index, part] = std::move(stack.back());
        stack.pop_back();
        const Node& node = at(node_index);
        if (node.kind == Kind::split) {
            Polyhedron front = clip(part, node.plane.flipped(), epsilon);
            Polyhedron back = clip(part, node.plane, epsilon);
            if (!back.empty())
                stack.emplace_back(node.back, std::move(back));
            if (!front.empty())
                stack.emplace_back(node.front, std::move(front));
            continue;
        }
        emit_leaf(node, std::move(part));
    }
}

GpuTree BeamTree::gpu_tree(GpuTreeLayout layout) const {
    static_assert(int(Kind::split) == 0 && int(Kind::out) == 1 && int(Kind::open) == 2 &&
                  int(Kind::solid) == 3 && int(Kind::blocker) == 4);
    auto relative = [&](const Plane& plane) {
        return glm::vec4(glm::vec3(plane.normal), float(plane.distance(apex_)));
    };
    // The GPU links are 32-bit: a tree past that is a bug in the build, not in the scene.
    SL_CHECK(nodes_.size() < size_t(std::numeric_limits<int32_t>::max()));
    SL_CHECK(stoppers_.size() + 2 < size_t(std::numeric_limits<int32_t>::max()));
    // order[k]: the node placed at k; place[i]: where node i goes.
    std::vector<int32_t> order;
    order.reserve(nodes_.size());
    if (layout == GpuTreeLayout::build) {
        for (size_t i = 0; i < nodes_.size(); ++i) {
            order.push_back(int32_t(i));
        }
    } else {
        std::vector<int32_t> stack = {0};
        while (!stack.empty()) {
            const int32_t index = stack.back();
            stack.pop_back();
            order.push_back(index);
            const Node& node = at(index);
            if (node.kind == Kind::split) {
                stack.push_back(node.front);
                stack.push_back(node.back);  // popped first: the next node in memory
            }
        }
    }
    std::vector<int32_t> place(nodes_.size(), -1);
    for (size_t k = 0; k < order.size(); ++k) {
        place[size_t(order[k])] = int32_t(k);
    }
    // walk.glsl reads the pyramid's sides as nodes 0-3 and the root below them at 3's back.
    for (int32_t i = 0; i < 4; ++i) {
        SL_CHECK(place[size_t(i)] == i);
    }
    GpuTree gpu;
    gpu.planes = {relative(influence_[4]), relative(influence_[5])};
    for (const Plane& stopper : stoppers_) {
        gpu.planes.push_back(relative(stopper));
    }
    gpu.nodes.reserve(order.size());
    for (const int32_t index : order) {
        const Node& node = at(index);
        GpuTreeNode g;
        g.plane = relative(node.plane);
        const bool split = node.kind == Kind::split;
        g.link = glm::ivec4(split ? place[size_t(node.front)] : -1,
                            split ? place[size_t(node.back)] : -1, int(node.kind),
                            node.kind == Kind::blocker ? node.back + 2 : -1);
        gpu.nodes.push_back(g);
    }
    return gpu;
}

BeamTreeStats BeamTree::stats() const {
    BeamTreeStats stats;
    stats.nodes = nodes_.size();
    stats.outer_polygons = outer_polygons_;
    stats.stopper_polygons = stopper_polygons_;
    stats.exact_polygons = exact_polygons_;
    stats.hidden_polygons = hidden_polygons_;
    std::vector<std::pair<int32_t, size_t>> stack = {{0, 1}};
    while (!stack.empty()) {
        const auto [index, depth] = stack.back();
        stack.pop_back();
        stats.max_depth = std::max(stats.max_depth, depth);
        const Node& node = at(index);
        switch (node.kind) {
            case Kind::split:
                stack.emplace_back(node.front, depth + 1);
                stack.emplace_back(node.back, depth + 1);
                break;
            case Kind::open:
                ++stats.open_leaves;
                break;
            case Kind::solid:
                ++stats.solid_leaves;
                break;
            case Kind::blocker:
                ++stats.blocker_leaves;
                break;
            case Kind::out:
                break;
        }
    }
    return stats;
}

BeamTree build_scene_beam_tree(const Scene& scene) {
    VolumeLibrary& library = VolumeLibrary::shared(scene.bounds);
    return BeamTree(scene.light, library.build(scene, nullptr));
}

}  // namespace sl::bt
