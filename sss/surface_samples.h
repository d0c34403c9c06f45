#pragma once
// Uniform sample points on a mesh surface for environment lighting (Rohat §4.5.1, §5.3.1): area-
// weighted random points, made uniform by weighted sample elimination (Yuksel 2015), and the
// uniformity measure that compares the two.

#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "scenes/mesh.h"

namespace sl::sss {

struct SurfaceSamples {
    std::vector<glm::vec3> positions;  // world space
    std::vector<glm::vec3> normals;    // interpolated, unit
    double area = 0.0;                 // of the whole surface, world units²
};

// `count` points uniformly distributed over the transformed surface (triangle chosen by area,
// uniform barycentrics), deterministic for a seed.
SurfaceSamples random_surface_points(const Mesh& mesh, const glm::mat4& transform, size_t count,
                                     uint64_t seed);

// Weighted sample elimination (Yuksel 2015): weights w = (1 − d̂/2r_max)^8 over neighbours within
// 2 r_max, r_max = √(A / (2√3 N)) (the densest packing's disk radius), d̂ = max(d, r_min) with
// r_min = r_max (1 − (N/M)^1.5) 0.65; repeatedly removes the heaviest until `count` remain.
// Neighbours come from a uniform hash grid of cell 2 r_max.
SurfaceSamples eliminate_samples(const SurfaceSamples& candidates, size_t count);

// How evenly a point set covers its surface: the relative radius ρ = (d_min / 2) / r_max of
// Lagae & Dutré (1 for a perfect hexagonal packing, ~0 for random points), and the mean and
// coefficient of variation of the nearest-neighbour distances.
struct Uniformity {
    double min_distance = 0.0;
    double mean_nearest = 0.0;
    double nearest_cv = 0.0;
    double packing_radius = 0.0;  // r_max
    double relative_radius = 0.0;
};
Uniformity measure_uniformity(const std::vector<glm::vec3>& positions, double area);

}  // namespace sl::sss
