#include "beamtree/conforming.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace sl::bt {

namespace {

// A bounding-volume hierarchy over points (median splits on the widest axis), each with an id,
// queried with a segment: a point within `tolerance` of the segment lies in a node whose box,
// grown by `tolerance`, the segment crosses. Adaptive, so the clusters of vertices where beams
// meet (the tree splits densest near the light and the silhouettes) cost a lookup no more than
// open space.
class PointTree {
public:
    struct Point {
        dvec3 position;
        uint32_t id;
    };

    explicit PointTree(std::vector<Point> points) : points_(std::move(points)) {
        nodes_.reserve(2 * points_.size() / kLeafSize + 1);
        build(0, uint32_t(points_.size()));
    }

    // Calls visit(point) for every point in a node the segment [a, b] grown by `tolerance` meets.
    template <class Visit>
    void query(const dvec3& a, const dvec3& b, double tolerance, Visit&& visit) const {
        const Segment segment(a, b, tolerance);
        std::array<uint32_t, 64> stack;
        size_t top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& node = nodes_[stack[--top]];
            if (!segment.crosses(node)) {
                continue;
            }
            if (node.right == 0) {
                for (uint32_t i = node.begin; i < node.end; ++i) {
                    visit(points_[i]);
                }
                continue;
            }
            stack[top++] = uint32_t(&node - nodes_.data()) + 1;
            stack[top++] = node.right;
        }
    }

private:
    static constexpr uint32_t kLeafSize = 8;

    struct Node {
        dvec3 lo, hi;
        uint32_t begin, end;
        uint32_t right;  // 0 for a leaf; the left child follows its parent
    };

    // The segment a + t d, t in [0, 1], and its inverse direction, found once per query.
    struct Segment {
        Segment(const dvec3& from, const dvec3& to, double margin)
            : a(from), d(to - from), grow(margin) {
            for (int axis = 0; axis < 3; ++axis) {
                inverse[axis] = d[axis] == 0.0 ? 0.0 : 1.0 / d[axis];
            }
        }
        // Slab test against the node's box grown by `grow`.
        bool crosses(const Node& node) const {
            double t0 = 0.0, t1 = 1.0;
            for (int axis = 0; axis < 3; ++axis) {
                const double lo = node.lo[axis] - grow, hi = node.hi[axis] + grow;
                if (d[axis] == 0.0) {
                    if (a[axis] < lo || a[axis] > hi) {
                        return false;
                    }
                    continue;
                }
                double near = (lo - a[axis]) * inverse[axis], far = (hi - a[axis]) * inverse[axis];
                if (near > far) {
                    std::swap(near, far);
                }
                t0 = std::max(t0, near);
                t1 = std::min(t1, far);
                if (t0 > t1) {
                    return false;
                }
            }
            return true;
        }
        dvec3 a, d, inverse;
        double grow;
    };

    // Depth first, so that a node's left child is the next node (depth ≤ log2(n / kLeafSize)).
    void build(uint32_t begin, uint32_t end) {
        const auto index = uint32_t(nodes_.size());
        Node node{dvec3(std::numeric_limits<double>::infinity()),
                  dvec3(-std::numeric_limits<double>::infinity()), begin, end, 0};
        for (uint32_t i = begin; i < end; ++i) {
            node.lo = glm::min(node.lo, points_[i].position);
            node.hi = glm::max(node.hi, points_[i].position);
        }
        nodes_.push_back(node);
        if (end - begin <= kLeafSize) {
            return;
        }
        const dvec3 extent = node.hi - node.lo;
        const int axis =
            extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
        const uint32_t middle = begin + (end - begin) / 2;
        std::nth_element(
            points_.begin() + begin, points_.begin() + middle, points_.begin() + end,
            [axis](const Point& p, const Point& q) { return p.position[axis] < q.position[axis]; });
        build(begin, middle);
        nodes_[index].right = uint32_t(nodes_.size());
        build(middle, end);
    }

    std::vector<Point> points_;
    std::vector<Node> nodes_;
};

}  // namespace

bool has_collinear_vertex(const Polygon& polygon) {
    const std::vector<dvec3>& v = polygon.vertices;
    for (size_t i = 0; i < v.size(); ++i) {
        const dvec3 in = v[i] - v[(i + v.size() - 1) % v.size()];
        const dvec3 out = v[(i + 1) % v.size()] - v[i];
        if (glm::length(glm::cross(in, out)) <= 1e-4 * glm::length(in) * glm::length(out)) {
            return true;
        }
    }
    return false;
}

namespace {

// Welding: the tree computes a corner shared by several cells once per cell, and the copies
// differ by round-off, which float can round apart. Every cluster of positions chained within
// `tolerance` becomes its lexicographically smallest member (union-find, smaller index wins), in
// every polygon. Returns the welded positions; false (nothing changed) under three.
bool weld(const std::vector<Polygon*>& polygons, double tolerance,
          std::vector<PointTree::Point>& welded) {
    // Every vertex of every polygon with its place (its polygon's first place plus its index),
    // sorted by position: each distinct position gets its rank, and each place that rank, so
    // that no position is looked up again.
    std::vector<PointTree::Point> vertices;
    for (const Polygon* polygon : polygons) {
        for (const dvec3& v : polygon->vertices) {
            vertices.push_back({v, uint32_t(vertices.size())});
        }
    }
    std::sort(vertices.begin(), vertices.end(),
              [](const PointTree::Point& p, const PointTree::Point& q) {
                  return lexicographic_less(p.position, q.position);
              });
    std::vector<uint32_t> rank_of(vertices.size());
    std::vector<PointTree::Point> distinct;  // id: the rank
    for (const PointTree::Point& vertex : vertices) {
        if (distinct.empty() || distinct.back().position != vertex.position) {
            distinct.push_back({vertex.position, uint32_t(distinct.size())});
        }
        rank_of[vertex.id] = uint32_t(distinct.size() - 1);
    }
    if (distinct.size() < 3) {
        return false;
    }
    std::vector<dvec3> positions(distinct.size());  // by rank
    for (const PointTree::Point& p : distinct) {
        positions[p.id] = p.position;
    }
    std::vector<uint32_t> parent(positions.size());
    for (uint32_t i = 0; i < parent.size(); ++i) {
        parent[i] = i;
    }
    const auto root = [&parent](uint32_t i) {
        while (parent[i] != i) {
            i = parent[i] = parent[parent[i]];
        }
        return i;
    };
    const PointTree near(std::move(distinct));
    const double tolerance2 = tolerance * tolerance;
    for (uint32_t i = 0; i < positions.size(); ++i) {
        near.query(positions[i], positions[i], tolerance, [&](const PointTree::Point& q) {
            const dvec3 gap = q.position - positions[i];
            if (glm::dot(gap, gap) <= tolerance2) {
                const uint32_t a = root(i), b = root(q.id);
                parent[std::max(a, b)] = std::min(a, b);
            }
        });
    }
    welded.clear();
    for (uint32_t i = 0; i < positions.size(); ++i) {
        if (root(i) == i) {
            welded.push_back({positions[i], uint32_t(welded.size())});
        }
    }
    uint32_t place = 0;
    for (Polygon* polygon : polygons) {
        std::vector<dvec3>& v = polygon->vertices;
        for (dvec3& p : v) {
            p = positions[root(rank_of[place++])];
        }
        v.erase(std::unique(v.begin(), v.end()), v.end());
        while (v.size() > 1 && v.front() == v.back()) {
            v.pop_back();
        }
    }
    return true;
}

// A vertex of a convex polygon is never inside one of its own edges, so every point of `tree`
// found within `tolerance` of an edge's interior (and farther than that from its ends) is a
// T-vertex, whichever polygon it belongs to: each edge gains the T-vertices on it, in order.
void insert_t_vertices(const std::vector<Polygon*>& polygons, const PointTree& tree,
                       double tolerance) {
    const double tolerance2 = tolerance * tolerance;
    std::vector<std::pair<double, dvec3>> on_edge;
    std::vector<dvec3> conforming;
    for (Polygon* polygon : polygons) {
        const std::vector<dvec3>& original = polygon->vertices;
        conforming.clear();
        for (size_t e = 0; e < original.size() && original.size() >= 2; ++e) {
            const dvec3 a = original[e], b = original[(e + 1) % original.size()];
            conforming.push_back(a);
            const dvec3 d = b - a;
            const double length2 = glm::dot(d, d);
            const double length = std::sqrt(length2);
            on_edge.clear();
            tree.query(a, b, tolerance, [&](const PointTree::Point& point) {
                const dvec3& p = point.position;
                const double t = glm::dot(p - a, d) / length2;
                const dvec3 off = p - a - t * d;
                if (t * length > tolerance && t * length < length - tolerance &&
                    glm::dot(off, off) <= tolerance2) {
                    on_edge.emplace_back(t, p);
                }
            });
            std::sort(on_edge.begin(), on_edge.end(),
                      [](const auto& x, const auto& y) { return x.first < y.first; });
            for (const auto& [t, p] : on_edge) {
                conforming.push_back(p);
            }
        }
        polygon->vertices = conforming;
        polygon->on_split_plane = 0;
    }
}

}  // namespace

void make_conforming(const std::vector<Polygon*>& polygons, double tolerance) {
    std::vector<PointTree::Point> welded;
    if (weld(polygons, tolerance, welded)) {
        insert_t_vertices(polygons, PointTree(std::move(welded)), tolerance);
    }
}

}  // namespace sl::bt
