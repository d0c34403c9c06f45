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

}  // namespace sl::sampling
