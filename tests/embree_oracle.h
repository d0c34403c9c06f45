#pragma once
// Segment occlusion by Embree (float precision BVH ray casts), an oracle independent of the beam
// tree's own geometry: one scene per set of polygons or meshes.

#include <embree3/rtcore.h>

#include <vector>

#include <glm/vec3.hpp>

#include "beamtree/geometry.h"

namespace sl::test {

class EmbreeOccluder {
public:
    EmbreeOccluder();
    ~EmbreeOccluder();
    EmbreeOccluder(const EmbreeOccluder&) = delete;
    EmbreeOccluder& operator=(const EmbreeOccluder&) = delete;

    // Adds triangles (world space); call commit() once all are added.
    void add(const std::vector<glm::dvec3>& positions, const std::vector<glm::uvec3>& triangles);
    void add(const bt::Polygon& polygon);
    void commit();
    // True when the open segment (from, to) hits a triangle.
    bool blocked(const glm::dvec3& from, const glm::dvec3& to) const;

private:
    RTCDevice device_;
    RTCScene scene_;
};

}  // namespace sl::test
