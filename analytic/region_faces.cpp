#include "analytic/region_faces.h"

#include <glm/vec4.hpp>

#include "analytic/shaders/analytic_interface.h"
#include "gl/functions.h"

namespace sl::analytic {

void RegionFaces::bind() const {
    gl::GL.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SL_FACE_CORNERS_BINDING, corners.id());
    gl::GL.BindVertexArray(mesh.vertex_array.id());
}

RegionFaces create_region_faces(const std::vector<glm::vec3>& positions,
                                const std::vector<glm::uvec3>& triangles) {
    RegionFaces faces;
    faces.mesh = gl::create_triangle_mesh(positions, triangles);
    if (triangles.empty()) {
        return faces;
    }
    std::vector<glm::vec4> corners;
    corners.reserve(triangles.size() * 3);
    for (const glm::uvec3& t : triangles) {
        for (int k = 0; k < 3; ++k) {
            corners.emplace_back(positions[t[k]], 1.0f);
        }
    }
    faces.corners = gl::create_buffer(corners.data(), corners.size() * sizeof(glm::vec4));
    return faces;
}

}  // namespace sl::analytic
