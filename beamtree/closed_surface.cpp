#include "beamtree/closed_surface.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "scenes/weld.h"

namespace sl::bt {

namespace {

uint32_t find_root(std::vector<uint32_t>& parent, uint32_t i) {
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

// Whether a closed component (its triangles, corners as welded ids) cuts itself, or is not a
// manifold surface (two sheets through one edge or vertex).
bool cuts_itself(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& id,
                 const std::vector<glm::uvec3>& triangles, const std::vector<uint32_t>& faces) {
    using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
    using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
    SurfaceMesh mesh;
    std::unordered_map<uint32_t, SurfaceMesh::Vertex_index> vertex;
    auto corner = [&](uint32_t k) {
        const auto [it, added] = vertex.emplace(id[k], SurfaceMesh::Vertex_index());
        if (added) {
            const glm::vec3& p = positions[k];
            it->second = mesh.add_vertex({p.x, p.y, p.z});
        }
        return it->second;
    };
    for (const uint32_t f : faces) {
        const glm::uvec3& t = triangles[f];
        if (mesh.add_face(corner(t.x), corner(t.y), corner(t.z)) == SurfaceMesh::null_face()) {
            return true;
        }
    }
    return CGAL::Polygon_mesh_processing::does_self_intersect(mesh);
}

}  // namespace

bool ClosedSurface::usable() const {
    return std::any_of(outward.begin(), outward.end(), [](int8_t side) { return side != 0; });
}

ClosedSurface closed_surface(const Mesh& mesh) {
    ClosedSurface out;
    const size_t n = mesh.triangles.size();
    if (n == 0) {
        out.why_not = "no triangles";
        return out;
    }
    const std::vector<uint32_t> id = weld_equal_positions(mesh.positions);
    // Components: triangles joined through shared (welded) edges.
    std::vector<uint32_t> parent(n);
    std::iota(parent.begin(), parent.end(), 0u);
    std::vector<std::pair<uint64_t, uint32_t>> directed;  // (from << 32 | to, triangle)
    directed.reserve(3 * n);
    {
        std::unordered_map<uint64_t, uint32_t> edge_owner;
        edge_owner.reserve(3 * n);
        for (uint32_t f = 0; f < n; ++f) {
            const glm::uvec3& t = mesh.triangles[f];
            const uint32_t v[3] = {id[t.x], id[t.y], id[t.z]};
            for (int e = 0; e < 3; ++e) {
                const uint32_t from = v[e], to = v[(e + 1) % 3];
                directed.emplace_back(uint64_t(from) << 32 | to, f);
                const uint64_t key = uint64_t(std::min(from, to)) << 32 | std::max(from, to);
                const auto [it, added] = edge_owner.emplace(key, f);
                if (!added) {
                    parent[find_root(parent, f)] = find_root(parent, it->second);
                }
            }
        }
    }
    std::vector<uint32_t> root(n);
    for (uint32_t f = 0; f < n; ++f) {
        root[f] = find_root(parent, f);
    }
    // Why each component (by its root) is not a closed surface; nullptr while it may be.
    std::vector<const char*> why(n, nullptr);
    // Closed and consistently wound: every directed edge once, and its reverse once.
    std::sort(directed.begin(), directed.end());
    for (size_t i = 0; i < directed.size(); ++i) {
        const uint64_t edge = directed[i].first;
        const uint64_t twin = edge << 32 | edge >> 32;
        const bool repeated = (i + 1 < directed.size() && directed[i + 1].first == edge) ||
                              (i > 0 && directed[i - 1].first == edge);
        const auto at = std::lower_bound(directed.begin(), directed.end(),
                                         std::pair<uint64_t, uint32_t>(twin, 0u));
        if (repeated || at == directed.end() || at->first != twin) {
            why[root[directed[i].second]] = "not closed and consistently wound";
        }
    }
    // Each component's signed volume (divergence theorem, about its first corner's position so
    // that far-off components keep their digits), and its size for the zero test.
    std::vector<double> volume(n, 0.0), size(n, 0.0);
    for (uint32_t f = 0; f < n; ++f) {
        const glm::uvec3& t = mesh.triangles[f];
        const uint32_t r = root[f];
        const glm::dvec3 origin(mesh.positions[mesh.triangles[r].x]);
        const glm::dvec3 a = glm::dvec3(mesh.positions[t.x]) - origin;
        const glm::dvec3 b = glm::dvec3(mesh.positions[t.y]) - origin;
        const glm::dvec3 c = glm::dvec3(mesh.positions[t.z]) - origin;
        volume[r] += glm::dot(a, glm::cross(b, c)) / 6.0;
        for (const glm::dvec3& p : {a, b, c}) {
            size[r] = std::max(size[r], std::pow(glm::length(p), 3.0));
        }
    }
    std::vector<std::vector<uint32_t>> faces(n);  // per closed component, its triangles
    for (uint32_t f = 0; f < n; ++f) {
        const uint32_t r = root[f];
        if (!why[r] && !(std::abs(volume[r]) > 1e-9 * size[r])) {
            why[r] = "a component encloses no volume";
        }
        if (!why[r]) {
            faces[r].push_back(f);
        }
    }
    for (uint32_t r = 0; r < n; ++r) {
        if (!faces[r].empty() && cuts_itself(mesh.positions, id, mesh.triangles, faces[r])) {
            why[r] = "it cuts itself";
        }
    }
    out.outward.resize(n);
    for (uint32_t f = 0; f < n; ++f) {
        const uint32_t r = root[f];
        out.outward[f] = why[r] ? 0 : volume[r] > 0.0 ? 1 : -1;
        if (why[r] && out.why_not.empty()) {
            out.why_not = why[r];
        }
    }
    return out;
}

}  // namespace sl::bt
