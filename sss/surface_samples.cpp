#include "sss/surface_samples.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <random>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "core/error.h"

namespace sl::sss {

namespace {

// A uniform hash grid over points: the neighbours of a point within the cell size.
class HashGrid {
public:
    HashGrid(const std::vector<glm::vec3>& points, double cell) : points_(points), cell_(cell) {
        for (size_t i = 0; i < points.size(); ++i) {
            cells_[key(cell_of(points[i]))].push_back(uint32_t(i));
        }
    }
    // Calls f(j, distance) for every j ≠ i within `radius` ≤ cell size of point i.
    template <typename F>
    void for_neighbours(size_t i, double radius, F&& f) const {
        const glm::ivec3 c = cell_of(points_[i]);
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const auto it = cells_.find(key(c + glm::ivec3(dx, dy, dz)));
                    if (it == cells_.end())
                        continue;
                    for (const uint32_t j : it->second) {
                        if (j == i)
                            continue;
                        const double d =
                            glm::distance(glm::dvec3(points_[i]), glm::dvec3(points_[j]));
                        if (d < radius)
                            f(j, d);
                    }
                }
    }

private:
    glm::ivec3 cell_of(const glm::vec3& p) const {
        return glm::ivec3(glm::floor(glm::dvec3(p) / cell_));
    }
    static uint64_t key(const glm::ivec3& c) {
        return (uint64_t(uint32_t(c.x) & 0x1fffff) << 42) |
               (uint64_t(uint32_t(c.y) & 0x1fffff) << 21) | uint64_t(uint32_t(c.z) & 0x1fffff);
    }
    const std::vector<glm::vec3>& points_;
    double cell_;
    std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
};

double packing_radius(double area, size_t count) {
    return std::sqrt(area / (2.0 * std::sqrt(3.0) * double(count)));
}

}  // namespace

SurfaceSamples random_surface_points(const Mesh& mesh, const glm::mat4& transform, size_t count,
                                     uint64_t seed) {
    if (mesh.triangles.empty() || count == 0) {
        fail("surface samples: need a mesh with triangles and a positive count");
    }
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(transform)));
    std::vector<glm::dvec3> p(mesh.positions.size());
    for (size_t i = 0; i < p.size(); ++i) {
        p[i] = glm::dvec3(transform * glm::vec4(mesh.positions[i], 1.0f));
    }
    std::vector<double> cumulative(mesh.triangles.size());
    double area = 0.0;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const glm::uvec3 tri = mesh.triangles[t];
        area += 0.5 * glm::length(glm::cross(p[tri.y] - p[tri.x], p[tri.z] - p[tri.x]));
        cumulative[t] = area;
    }
    if (!(area > 0.0)) {
        fail("surface samples: the mesh has no area");
    }
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    SurfaceSamples s;
    s.area = area;
    s.positions.reserve(count);
    s.normals.reserve(count);
    for (size_t k = 0; k < count; ++k) {
        const size_t t =
            size_t(std::lower_bound(cumulative.begin(), cumulative.end(), uniform(rng) * area) -
                   cumulative.begin());
        const glm::uvec3 tri = mesh.triangles[std::min(t, mesh.triangles.size() - 1)];
        double a = uniform(rng), b = uniform(rng);
        if (a + b > 1.0) {
            a = 1.0 - a;
            b = 1.0 - b;
        }
        const double c = 1.0 - a - b;
        s.positions.emplace_back(c * p[tri.x] + a * p[tri.y] + b * p[tri.z]);
        glm::vec3 n = float(c) * mesh.normals[tri.x] + float(a) * mesh.normals[tri.y] +
                      float(b) * mesh.normals[tri.z];
        n = normal_matrix * n;
        const float length = glm::length(n);
        s.normals.push_back(length > 0.0f ? n / length : glm::vec3(0, 1, 0));
    }
    return s;
}

SurfaceSamples eliminate_samples(const SurfaceSamples& candidates, size_t count) {
    const size_t m = candidates.positions.size();
    if (count == 0 || count > m) {
        fail("sample elimination: cannot keep {} of {} candidates", count, m);
    }
    const double r_max = packing_radius(candidates.area, count);
    const double r_min = r_max * (1.0 - std::pow(double(count) / double(m), 1.5)) * 0.65;
    auto weight = [&](double d) { return std::pow(1.0 - std::max(d, r_min) / (2.0 * r_max), 8.0); };
    const HashGrid grid(candidates.positions, 2.0 * r_max);
    std::vector<std::vector<std::pair<uint32_t, float>>> neighbours(m);
    std::vector<double> w(m, 0.0);
    for (size_t i = 0; i < m; ++i) {
        grid.for_neighbours(i, 2.0 * r_max, [&](uint32_t j, double d) {
            neighbours[i].emplace_back(j, float(d));
            w[i] += weight(d);
        });
    }
    // A max-heap with lazy deletion: an entry is current while its weight matches w[i].
    std::priority_queue<std::pair<double, uint32_t>> heap;
    for (size_t i = 0; i < m; ++i) {
        heap.emplace(w[i], uint32_t(i));
    }
    std::vector<bool> alive(m, true);
    size_t remaining = m;
    while (remaining > count) {
        const auto [wi, i] = heap.top();
        heap.pop();
        if (!alive[i] || wi != w[i]) {
            continue;
        }
        alive[i] = false;
        --remaining;
        for (const auto& [j, d] : neighbours[i]) {
            if (alive[j]) {
                w[j] -= weight(d);
                heap.emplace(w[j], j);
            }
        }
    }
    SurfaceSamples out;
    out.area = candidates.area;
    for (size_t i = 0; i < m; ++i) {
        if (alive[i]) {
            out.positions.push_back(candidates.positions[i]);
            out.normals.push_back(candidates.normals[i]);
        }
    }
    return out;
}

Uniformity measure_uniformity(const std::vector<glm::vec3>& positions, double area) {
    Uniformity u;
    if (positions.size() < 2 || !(area > 0.0)) {
        return u;
    }
    u.packing_radius = packing_radius(area, positions.size());
    // Nearest neighbours through a grid of growing cell size until every point finds one.
    std::vector<double> nearest(positions.size(), INFINITY);
    for (double cell = 2.0 * u.packing_radius;; cell *= 2.0) {
        const HashGrid grid(positions, cell);
        bool all = true;
        for (size_t i = 0; i < positions.size(); ++i) {
            if (std::isfinite(nearest[i]))
                continue;
            grid.for_neighbours(i, cell,
                                [&](uint32_t, double d) { nearest[i] = std::min(nearest[i], d); });
            all &= std::isfinite(nearest[i]);
        }
        if (all)
            break;
    }
    double sum = 0.0, sum2 = 0.0;
    u.min_distance = INFINITY;
    for (const double d : nearest) {
        u.min_distance = std::min(u.min_distance, d);
        sum += d;
        sum2 += d * d;
    }
    const double n = double(nearest.size());
    u.mean_nearest = sum / n;
    u.nearest_cv =
        std::sqrt(std::max(0.0, sum2 / n - u.mean_nearest * u.mean_nearest)) / u.mean_nearest;
    u.relative_radius = 0.5 * u.min_distance / u.packing_radius;
    return u;
}

}  // namespace sl::sss
