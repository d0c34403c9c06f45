#include "beamtree/coplanar_faces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "scenes/weld.h"

namespace sl::bt {

namespace {

using dvec3 = glm::dvec3;

uint64_t edge_key(uint32_t from, uint32_t to) {
    return uint64_t(from) << 32 | to;
}

// b turns left (about `normal`) from a to c by more than 1e-9 radians.
bool turns_left(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& normal) {
    const dvec3 in = b - a, out = c - b;
    return glm::dot(glm::cross(in, out), normal) > 1e-9 * glm::length(in) * glm::length(out);
}

}  // namespace

CoplanarFaces coplanar_faces(const Mesh& mesh) {
    const std::vector<uint32_t> id = weld_equal_positions(mesh.positions);
    // One position per welded id, and its coordinates.
    std::vector<uint32_t> position_of(mesh.positions.size(), 0);
    std::vector<dvec3> point(mesh.positions.size());
    double extent = 0.0;
    for (size_t i = mesh.positions.size(); i-- > 0;) {  // the first position of each id wins
        position_of[id[i]] = uint32_t(i);
        point[id[i]] = dvec3(mesh.positions[i]);
        const glm::vec3& p = mesh.positions[i];
        extent =
            std::max({extent, double(std::abs(p.x)), double(std::abs(p.y)), double(std::abs(p.z))});
    }
    const double on_plane = 1e-9 * extent;

    const size_t n = mesh.triangles.size();
    std::vector<std::array<uint32_t, 3>> corners(n);
    std::vector<dvec3> normal(n);  // unit, or zero where degenerate
    // The triangle across each directed edge; -1 where two triangles walk it the same way.
    std::unordered_map<uint64_t, int64_t> walked;
    walked.reserve(3 * n);
    for (size_t t = 0; t < n; ++t) {
        const glm::uvec3& tri = mesh.triangles[t];
        corners[t] = {id[tri.x], id[tri.y], id[tri.z]};
        const auto [a, b, c] = corners[t];
        const dvec3 cross = glm::cross(point[b] - point[a], point[c] - point[a]);
        const double length = glm::length(cross);
        const bool degenerate = a == b || b == c || c == a || !(length > 0.0);
        normal[t] = degenerate ? dvec3(0.0) : cross / length;
        if (degenerate) {
            continue;
        }
        for (int k = 0; k < 3; ++k) {
            const auto [it, fresh] = walked.emplace(
                edge_key(corners[t][size_t(k)], corners[t][size_t((k + 1) % 3)]), int64_t(t));
            if (!fresh) {
                it->second = -1;  // not a consistently wound edge of two triangles
            }
        }
    }

    CoplanarFaces out;
    std::vector<char> used(n, 0);
    std::vector<uint32_t> loop;
    for (size_t t = 0; t < n; ++t) {
        if (used[t]) {
            continue;
        }
        used[t] = 1;
        loop.assign(corners[t].begin(), corners[t].end());
        const dvec3 plane_normal = normal[t];
        const dvec3 origin = point[loop[0]];
        bool grew = glm::length(plane_normal) > 0.0;
        while (grew) {
            grew = false;
            for (size_t i = 0; i < loop.size() && loop.size() < CoplanarFaces::kMaxCorners; ++i) {
                const size_t m = loop.size();
                const uint32_t p = loop[i], q = loop[(i + 1) % m];
                const auto across = walked.find(edge_key(q, p));
                if (across == walked.end() || across->second < 0 || used[size_t(across->second)] ||
                    walked.at(edge_key(p, q)) < 0) {
                    continue;
                }
                const auto u = size_t(across->second);
                const auto& c = corners[u];
                const uint32_t r = c[0] != p && c[0] != q   ? c[0]
                                   : c[1] != p && c[1] != q ? c[1]
                                                            : c[2];
                if (std::find(loop.begin(), loop.end(), r) != loop.end() ||
                    glm::dot(normal[u], plane_normal) <= 0.0 ||
                    std::abs(glm::dot(point[r] - origin, plane_normal)) > on_plane) {
                    continue;
                }
                const dvec3& before = point[loop[(i + m - 1) % m]];
                const dvec3& after = point[loop[(i + 2) % m]];
                if (!turns_left(before, point[p], point[r], plane_normal) ||
                    !turns_left(point[p], point[r], point[q], plane_normal) ||
                    !turns_left(point[r], point[q], after, plane_normal)) {
                    continue;
                }
                loop.insert(loop.begin() + std::ptrdiff_t(i + 1), r);
                used[u] = 1;
                grew = true;
            }
        }
        std::vector<uint32_t> face;
        face.reserve(loop.size());
        for (const uint32_t corner : loop) {
            face.push_back(position_of[corner]);
        }
        out.faces.push_back(std::move(face));
        out.triangle.push_back(uint32_t(t));
    }
    return out;
}

}  // namespace sl::bt
