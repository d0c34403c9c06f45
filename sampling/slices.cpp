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
    // Every pyramid vertex is within far·sqrt(1 + 2 tan²θ) of L.
    const double radius = glm::length(dvec3(light.position)) +
                          double(light.far) * std::sqrt(1.0 + 2.0 * tangent * tangent) + 1.0;
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

void remove_t_junctions(const std::vector<bt::Polygon*>& pieces, double tolerance) {
    if (pieces.size() < 2)
        return;
    // A uniform grid over the plane (about one vertex per cell) finds, for each edge, the
    // vertices near it: cells are visited along the edge, so each edge costs its length in cells.
    const dvec3 normal = glm::normalize(bt::area_vector(*pieces.front()));
    const dvec3 u = glm::normalize(std::abs(normal.x) < 0.9 ? glm::cross(normal, dvec3(1, 0, 0))
                                                            : glm::cross(normal, dvec3(0, 1, 0)));
    const dvec3 w = glm::cross(normal, u);
    struct Vertex {
        glm::dvec2 at;
        dvec3 position;
        uint32_t piece;
    };
    std::vector<Vertex> vertices;
    glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    for (uint32_t i = 0; i < pieces.size(); ++i) {
        for (const dvec3& p : pieces[i]->vertices) {
            const glm::dvec2 at(glm::dot(p, u), glm::dot(p, w));
            vertices.push_back({at, p, i});
            lo = glm::min(lo, at);
            hi = glm::max(hi, at);
        }
    }
    const glm::dvec2 extent = glm::max(hi - lo, glm::dvec2(tolerance));
    const double cell =
        std::max(std::sqrt(extent.x * extent.y / double(vertices.size())), 4.0 * tolerance);
    const int nx = std::min(4096, int(extent.x / cell) + 1);
    const int ny = std::min(4096, int(extent.y / cell) + 1);
    auto cell_of = [&](glm::dvec2 at) {
        return glm::ivec2(std::clamp(int((at.x - lo.x) / cell), 0, nx - 1),
                          std::clamp(int((at.y - lo.y) / cell), 0, ny - 1));
    };
    // Each vertex goes into every cell within `tolerance` of it (almost always one), sorted by
    // cell (counting sort): cell c holds entries[start[c] .. start[c + 1]).
    std::vector<std::pair<uint32_t, uint32_t>> cell_vertex;  // (cell, vertex)
    for (uint32_t i = 0; i < vertices.size(); ++i) {
        const glm::ivec2 c0 = cell_of(vertices[i].at - tolerance);
        const glm::ivec2 c1 = cell_of(vertices[i].at + tolerance);
        for (int cy = c0.y; cy <= c1.y; ++cy)
            for (int cx = c0.x; cx <= c1.x; ++cx)
                cell_vertex.emplace_back(uint32_t(cy * nx + cx), i);
    }
    std::vector<uint32_t> start(size_t(nx) * ny + 1, 0), entries(cell_vertex.size());
    for (const auto& [c, v] : cell_vertex)
        ++start[c + 1];
    for (size_t c = 1; c < start.size(); ++c)
        start[c] += start[c - 1];
    {
        std::vector<uint32_t> fill(start.begin(), start.end() - 1);
        for (const auto& [c, v] : cell_vertex)
            entries[fill[c]++] = v;
    }
    const double tolerance2 = tolerance * tolerance;
    std::vector<std::pair<double, dvec3>> on_edge;
    for (uint32_t i = 0; i < pieces.size(); ++i) {
        const std::vector<dvec3> original = pieces[i]->vertices;
        std::vector<dvec3> conforming;
        for (size_t e = 0; e < original.size(); ++e) {
            const dvec3 a = original[e], b = original[(e + 1) % original.size()];
            const dvec3 d = b - a;
            const double length2 = glm::dot(d, d);
            conforming.push_back(a);
            if (length2 <= tolerance2)
                continue;
            const double length = std::sqrt(length2);
            on_edge.clear();
            auto visit = [&](size_t c) {
                for (uint32_t k = start[c]; k < start[c + 1]; ++k) {
                    const Vertex& v = vertices[entries[k]];
                    if (v.piece == i)
                        continue;
                    const double t = glm::dot(v.position - a, d) / length2;
                    const dvec3 off = v.position - a - t * d;
                    if (glm::dot(off, off) > tolerance2)
                        continue;
                    if (t * length > tolerance && t * length < length - tolerance)
                        on_edge.emplace_back(t, v.position);
                }
            };
            // The cells the segment passes through (Amanatides & Woo's grid traversal).
            const glm::dvec2 a2 = (glm::dvec2(glm::dot(a, u), glm::dot(a, w)) - lo) / cell;
            const glm::dvec2 b2 = (glm::dvec2(glm::dot(b, u), glm::dot(b, w)) - lo) / cell;
            glm::ivec2 c = cell_of(lo + a2 * cell);
            const glm::ivec2 last = cell_of(lo + b2 * cell);
            const glm::dvec2 delta = b2 - a2;
            const glm::ivec2 step(delta.x > 0 ? 1 : -1, delta.y > 0 ? 1 : -1);
            const double inf = std::numeric_limits<double>::infinity();
            const glm::dvec2 t_delta(delta.x != 0 ? std::abs(1.0 / delta.x) : inf,
                                     delta.y != 0 ? std::abs(1.0 / delta.y) : inf);
            glm::dvec2 t_max(
                delta.x != 0 ? ((step.x > 0 ? c.x + 1 - a2.x : a2.x - c.x) * t_delta.x) : inf,
                delta.y != 0 ? ((step.y > 0 ? c.y + 1 - a2.y : a2.y - c.y) * t_delta.y) : inf);
            for (int guard = 0; guard < nx + ny + 2; ++guard) {
                visit(size_t(c.y) * nx + c.x);
                if (c == last)
                    break;
                if (t_max.x < t_max.y) {
                    c.x = std::clamp(c.x + step.x, 0, nx - 1);
                    t_max.x += t_delta.x;
                } else {
                    c.y = std::clamp(c.y + step.y, 0, ny - 1);
                    t_max.y += t_delta.y;
                }
            }
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
