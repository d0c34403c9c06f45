#include "tests/embree_oracle.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace sl::test {

EmbreeOccluder::EmbreeOccluder() : device_(rtcNewDevice("threads=1")), scene_(nullptr) {
    if (!device_) {
        throw std::runtime_error("Embree device could not be created");
    }
    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
}

EmbreeOccluder::~EmbreeOccluder() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
}

void EmbreeOccluder::add(const std::vector<glm::dvec3>& positions,
                         const std::vector<glm::uvec3>& triangles) {
    if (triangles.empty()) {
        return;
    }
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), positions.size()));
    for (size_t i = 0; i < positions.size(); ++i) {
        vertices[3 * i] = float(positions[i].x);
        vertices[3 * i + 1] = float(positions[i].y);
        vertices[3 * i + 2] = float(positions[i].z);
    }
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), triangles.size()));
    for (size_t i = 0; i < triangles.size(); ++i) {
        indices[3 * i] = triangles[i].x;
        indices[3 * i + 1] = triangles[i].y;
        indices[3 * i + 2] = triangles[i].z;
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
}

void EmbreeOccluder::add(const bt::Polygon& polygon) {
    std::vector<glm::uvec3> fan;
    for (uint32_t i = 1; i + 1 < polygon.size(); ++i) {
        fan.emplace_back(0, i, i + 1);
    }
    add(polygon.vertices, fan);
}

void EmbreeOccluder::commit() {
    rtcCommitScene(scene_);
}

bool EmbreeOccluder::blocked(const glm::dvec3& from, const glm::dvec3& to) const {
    const glm::dvec3 d = to - from;
    const double length = glm::length(d);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    ray.org_x = float(from.x);
    ray.org_y = float(from.y);
    ray.org_z = float(from.z);
    ray.dir_x = float(d.x / length);
    ray.dir_y = float(d.y / length);
    ray.dir_z = float(d.z / length);
    ray.tnear = 0.0f;
    ray.tfar = float(length);
    ray.mask = 0xFFFFFFFFu;
    rtcOccluded1(scene_, &context, &ray);
    return ray.tfar == -std::numeric_limits<float>::infinity();
}

}  // namespace sl::test
