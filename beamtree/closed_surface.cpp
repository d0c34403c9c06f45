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

bool cuts_itself(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& id,
                 const std::vector<glm::uvec3>& triangles) {
    using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
    using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
    SurfaceMesh mesh;
    std::vector<SurfaceMesh::Vertex_index> vertex;
    for (size_t i = 0; i < positions.size(); ++i) {
        if (id[i] == vertex.size()) {  // ids rise with the first corner of each position
            vertex.push_back(mesh.add_vertex({positions[i].x, positions[i].y, positions[i].z}));
        }
    }
    for (const glm::uvec3& t : triangles) {
        if (mesh.add_face(vertex[id[t.x]], vertex[id[t.y]], vertex[id[t.z]]) ==
            SurfaceMesh::null_face()) {
            return true;  // not a manifold surface (two components sharing a vertex or edge)
        }
    }
    return CGAL::Polygon_mesh_processing::does_self_intersect(mesh);
}

}  // namespace

ClosedSurface closed_surface(const Mesh& mesh) {
    ClosedSurface out;
    if (mesh.triangles.empty() || !mesh.is_closed()) {
        out.why_not = "not closed and consistently wound";
        return out;
    }
    // Renumber the welded ids by first use, so that cuts_itself can add vertices in one pass.
    std::vector<uint32_t> id = weld_equal_positions(mesh.positions);
    {
        std::vector<uint32_t> first(mesh.positions.size(), UINT32_MAX);
        uint32_t next = 0;
        for (uint32_t& i : id) {
            if (first[i] == UINT32_MAX) {
                first[i] = next++;
            }
            i = first[i];
        }
    }
    // Components: triangles joined through shared (welded) edges.
    const size_t n = mesh.triangles.size();
    std::vector<uint32_t> parent(n);
    std::iota(parent.begin(), parent.end(), 0u);
    std::unordered_map<uint64_t, uint32_t> edge_owner;
    edge_owner.reserve(3 * n);
    for (uint32_t f = 0; f < n; ++f) {
        const glm::uvec3& t = mesh.triangles[f];
        const uint32_t v[3] = {id[t.x], id[t.y], id[t.z]};
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = std::min(v[e], v[(e + 1) % 3]), b = std::max(v[e], v[(e + 1) % 3]);
            const auto [it, added] = edge_owner.emplace(uint64_t(a) << 32 | b, f);
            if (!added) {
                parent[find_root(parent, f)] = find_root(parent, it->second);
            }
        }
    }
    // Each component's signed volume (divergence theorem, about its first corner's position so
    // that far-off components keep their digits), and its size for the zero test.
    std::unordered_map<uint32_t, std::pair<double, double>> volume;  // root -> (volume, extent³)
    for (uint32_t f = 0; f < n; ++f) {
        const glm::uvec3& t = mesh.triangles[f];
        const uint32_t root = find_root(parent, f);
        const glm::dvec3 origin(mesh.positions[mesh.triangles[root].x]);
        const glm::dvec3 a = glm::dvec3(mesh.positions[t.x]) - origin;
        const glm::dvec3 b = glm::dvec3(mesh.positions[t.y]) - origin;
        const glm::dvec3 c = glm::dvec3(mesh.positions[t.z]) - origin;
        auto& [v, size] = volume[root];
        v += glm::dot(a, glm::cross(b, c)) / 6.0;
        for (const glm::dvec3& p : {a, b, c}) {
            size = std::max(size, std::pow(glm::length(p), 3.0));
        }
    }
    for (const auto& [root, v] : volume) {
        if (!(std::abs(v.first) > 1e-9 * v.second)) {
            out.why_not = "a component encloses no volume";
            return out;
        }
    }
    if (cuts_itself(mesh.positions, id, mesh.triangles)) {
        out.why_not = "it cuts itself";
        return out;
    }
    out.outward.resize(n);
    for (uint32_t f = 0; f < n; ++f) {
        out.outward[f] = volume[find_root(parent, f)].first > 0.0 ? 1 : -1;
    }
    return out;
}

}  // namespace sl::bt
