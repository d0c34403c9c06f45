#include "sampling/slices.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "beamtree/beam_tree.h"
#include "core/error.h"

namespace sl::sampling {

namespace {

using glm::dvec3;

bt::Polyhedron influence_pyramid(const SpotLight& light) {
    const double tangent = std::tan(glm::radians(double(light.cone_half_angle_degrees)));
    // Every pyramid vertex is within far·sqrt(1 + 2 tan²θ) of L; a parallel box's within
    // far + sqrt(2) half-widths.
    const double reach = light.parallel()
                             ? double(light.far) + std::sqrt(2.0) * double(light.half_width)
                             : double(light.far) * std::sqrt(1.0 + 2.0 * tangent * tangent);
    const double radius = glm::length(dvec3(light.position)) + reach + 1.0;
    return bt::polyhedron_from_planes(bt::influence_planes(light), radius,
                                      bt::BeamTree::kRelativeEpsilon * double(light.far));
}

dvec3 forward_of(const Camera& camera) {
    return glm::normalize(dvec3(camera.target) - dvec3(camera.position));
}

std::pair<double, double> depth_range(const bt::Polyhedron& pyramid, const Camera& camera) {
    const dvec3 eye(camera.position), forward = forward_of(camera);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const bt::Polygon& face : pyramid.faces) {
        for (const dvec3& v : face.vertices) {
            const double depth = glm::dot(v - eye, forward);
            lo = std::min(lo, depth);
            hi = std::max(hi, depth);
        }
    }
    return {lo, hi};
}

}  // namespace

std::pair<double, double> influence_depth_range(const Camera& camera, const SpotLight& light) {
    return depth_range(influence_pyramid(light), camera);
}

std::vector<Slice> influence_slices(const Camera& camera, const SpotLight& light, double dz,
                                    size_t max_slices) {
    if (!(dz > 0.0) || !std::isfinite(dz)) {
        fail("slice spacing dz = {} must be positive and finite", dz);
    }
    const bt::Polyhedron pyramid = influence_pyramid(light);
    const dvec3 eye(camera.position), forward = forward_of(camera);
    const auto [lo, hi] = depth_range(pyramid, camera);
    // Slices in front of the camera only: slab k covers [k dz, (k + 1) dz).
    const double first = std::max(0.0, std::floor(lo / dz)), last = std::floor(hi / dz);
    if (last - first + 1.0 > double(max_slices)) {
        fail(
            "dz = {} would need {} sampling planes over the light's {:.3g} m of eye depth (at "
            "most {})",
            dz, last - first + 1.0, hi - std::max(lo, 0.0), max_slices);
    }
    const double epsilon = bt::BeamTree::kRelativeEpsilon * double(light.far);
    std::vector<Slice> slices;
    for (double k = first; k <= last; k += 1.0) {
        const double depth = (k + 0.5) * dz;
        const bt::Plane plane{forward, -glm::dot(forward, eye) - depth};
        std::vector<dvec3> points;
        for (const bt::Polygon& face : pyramid.faces) {
            const bt::Split parts = bt::split(face, plane, epsilon);
            points.insert(points.end(), parts.cut.begin(), parts.cut.end());
            if (parts.coplanar) {
                points.insert(points.end(), face.vertices.begin(), face.vertices.end());
            }
        }
        bt::Polygon polygon = bt::convex_polygon_on_plane(std::move(points), plane, epsilon);
        if (!polygon.empty()) {
            slices.push_back({depth, std::move(polygon)});
        }
    }
    return slices;
}

namespace {

// The pieces' vertices in a uniform grid over their plane (about one vertex per cell): cells are
// visited along an edge, so finding the vertices near an edge costs its length in cells.
class VertexGrid {
public:
    VertexGrid(const std::vector<bt::Polygon*>& pieces, double tolerance) : tolerance_(tolerance) {
        const dvec3 normal = glm::normalize(bt::area_vector(*pieces.front()));
        u_ = glm::normalize(std::abs(normal.x) < 0.9 ? glm::cross(normal, dvec3(1, 0, 0))
                                                     : glm::cross(normal, dvec3(0, 1, 0)));
        w_ = glm::cross(normal, u_);
        glm::dvec2 hi(-std::numeric_limits<double>::infinity());
        lo_ = -hi;
        for (uint32_t i = 0; i < pieces.size(); ++i) {
            for (const dvec3& p : pieces[i]->vertices) {
                const glm::dvec2 at = on_plane(p);
                vertices_.push_back({at, p, i});
                lo_ = glm::min(lo_, at);
                hi = glm::max(hi, at);
            }
        }
        const glm::dvec2 extent = glm::max(hi - lo_, glm::dvec2(tolerance));
        cell_ =
            std::max(std::sqrt(extent.x * extent.y / double(vertices_.size())), 4.0 * tolerance);
        nx_ = std::min(4096, int(extent.x / cell_) + 1);
        ny_ = std::min(4096, int(extent.y / cell_) + 1);
        fill_cells();
    }

    // Appends (t, vertex) for each vertex of another piece than `piece` within the tolerance of
    // segment ab and more than the tolerance from its ends, t along ab in [0, 1].
    void vertices_on_edge(const dvec3& a, const dvec3& b, uint32_t piece,
                          std::vector<std::pair<double, dvec3>>& out) const {
        const dvec3 d = b - a;
        const double length2 = glm::dot(d, d), length = std::sqrt(length2);
        const double tolerance2 = tolerance_ * tolerance_;
        cells_along(on_plane(a), on_plane(b), [&](size_t c) {
            for (uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
                const Vertex& v = vertices_[entries_[k]];
                if (v.piece == piece)
                    continue;
                const double t = glm::dot(v.position - a, d) / length2;
                const dvec3 off = v.position - a - t * d;
                if (glm::dot(off, off) > tolerance2)
                    continue;
                if (t * length > tolerance_ && t * length < length - tolerance_)
                    out.emplace_back(t, v.position);
            }
        });
    }

private:
    struct Vertex {
        glm::dvec2 at;
        dvec3 position;
        uint32_t piece;
    };

    glm::dvec2 on_plane(const dvec3& p) const { return {glm::dot(p, u_), glm::dot(p, w_)}; }
    glm::ivec2 cell_of(glm::dvec2 at) const {
        return glm::ivec2(std::clamp(int((at.x - lo_.x) / cell_), 0, nx_ - 1),
                          std::clamp(int((at.y - lo_.y) / cell_), 0, ny_ - 1));
    }

    // Each vertex goes into every cell within the tolerance of it (almost always one), sorted by
    // cell (counting sort): cell c holds entries_[start_[c] .. start_[c + 1]).
    void fill_cells() {
        std::vector<std::pair<uint32_t, uint32_t>> cell_vertex;  // (cell, vertex)
        for (uint32_t i = 0; i < vertices_.size(); ++i) {
            const glm::ivec2 c0 = cell_of(vertices_[i].at - tolerance_);
            const glm::ivec2 c1 = cell_of(vertices_[i].at + tolerance_);
            for (int cy = c0.y; cy <= c1.y; ++cy)
                for (int cx = c0.x; cx <= c1.x; ++cx)
                    cell_vertex.emplace_back(uint32_t(cy * nx_ + cx), i);
        }
        start_.assign(size_t(nx_) * ny_ + 1, 0);
        entries_.resize(cell_vertex.size());
        for (const auto& [c, v] : cell_vertex)
            ++start_[c + 1];
        for (size_t c = 1; c < start_.size(); ++c)
            start_[c] += start_[c - 1];
        std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
        for (const auto& [c, v] : cell_vertex)
            entries_[fill[c]++] = v;
    }

    // Calls visit(cell) for the cells the segment from a to b (on the plane) passes through
    // (Amanatides & Woo's grid traversal).
    template <typename Visit>
    void cells_along(glm::dvec2 a, glm::dvec2 b, Visit&& visit) const {
        const glm::dvec2 a2 = (a - lo_) / cell_, b2 = (b - lo_) / cell_;
        glm::ivec2 c = cell_of(lo_ + a2 * cell_);
        const glm::ivec2 last = cell_of(lo_ + b2 * cell_);
        const glm::dvec2 delta = b2 - a2;
        const glm::ivec2 step(delta.x > 0 ? 1 : -1, delta.y > 0 ? 1 : -1);
        const double inf = std::numeric_limits<double>::infinity();
        const glm::dvec2 t_delta(delta.x != 0 ? std::abs(1.0 / delta.x) : inf,
                                 delta.y != 0 ? std::abs(1.0 / delta.y) : inf);
        glm::dvec2 t_max(
            delta.x != 0 ? ((step.x > 0 ? c.x + 1 - a2.x : a2.x - c.x) * t_delta.x) : inf,
            delta.y != 0 ? ((step.y > 0 ? c.y + 1 - a2.y : a2.y - c.y) * t_delta.y) : inf);
        for (int guard = 0; guard < nx_ + ny_ + 2; ++guard) {
            visit(size_t(c.y) * nx_ + c.x);
            if (c == last)
                break;
            if (t_max.x < t_max.y) {
                c.x = std::clamp(c.x + step.x, 0, nx_ - 1);
                t_max.x += t_delta.x;
            } else {
                c.y = std::clamp(c.y + step.y, 0, ny_ - 1);
                t_max.y += t_delta.y;
            }
        }
    }

    double tolerance_;
    dvec3 u_, w_;
    glm::dvec2 lo_;
    double cell_ = 0.0;
    int nx_ = 1, ny_ = 1;
    std::vector<Vertex> vertices_;
    std::vector<uint32_t> start_, entries_;
};

}  // namespace

void remove_t_junctions(const std::vector<bt::Polygon*>& pieces, double tolerance) {
    if (pieces.size() < 2)
        return;
    const VertexGrid grid(pieces, tolerance);
    const double tolerance2 = tolerance * tolerance;
    std::vector<std::pair<double, dvec3>> on_edge;
    for (uint32_t i = 0; i < pieces.size(); ++i) {
        const std::vector<dvec3> original = pieces[i]->vertices;
        std::vector<dvec3> conforming;
        for (size_t e = 0; e < original.size(); ++e) {
            const dvec3 a = original[e], b = original[(e + 1) % original.size()];
            conforming.push_back(a);
            if (glm::dot(b - a, b - a) <= tolerance2)
                continue;
            on_edge.clear();
            grid.vertices_on_edge(a, b, i, on_edge);
            std::sort(on_edge.begin(), on_edge.end(),
                      [](const auto& x, const auto& y) { return x.first < y.first; });
            for (const auto& [t, v] : on_edge) {
                const dvec3 gap = v - conforming.back();
                if (glm::dot(gap, gap) > tolerance2)
                    conforming.push_back(v);
            }
        }
        pieces[i]->vertices = std::move(conforming);
        pieces[i]->on_split_plane = 0;  // edge flags no longer line up with edges
    }
}

}  // namespace sl::sampling
