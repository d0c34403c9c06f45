#pragma once
// A region surface on the GPU: its triangles to rasterize, and each triangle's corners for the
// fragment shaders that need a crossing's distance along the eye ray
// (analytic/shaders/face_distance.glsl).
//
// Why not the interpolated position: the boundary meshes (beamtree/boundary.h) hold triangles
// that are degenerate in float (three collinear corners, which keep the mesh watertight at a
// T-vertex) and slivers seen edge-on. Rasterized, such a triangle can still cover a pixel centre
// (the mesh stays watertight, so a neighbour covers it once more with the other sign), and its
// interpolated position there is far off, NaN or infinite. The pair then adds G(z) at two
// different z instead of cancelling (docs/design.md §9; the measurements are in results/house.md).

#include <vector>

#include <glm/vec3.hpp>

#include "gl/objects.h"

namespace sl::analytic {

struct RegionFaces {
    gl::TriangleMesh mesh;
    gl::Buffer corners;  // 3 vec4 per triangle, in the order drawn (gl_PrimitiveID)

    GLsizei index_count() const { return mesh.index_count; }
    // Binds the corners at SL_FACE_CORNERS_BINDING (analytic/shaders/analytic_interface.h) and the
    // vertex array; the caller draws all of it in one DrawElements (gl_PrimitiveID counts from 0
    // per draw).
    void bind() const;
};

// Empty (index_count 0) for no triangles.
RegionFaces create_region_faces(const std::vector<glm::vec3>& positions,
                                const std::vector<glm::uvec3>& triangles);

}  // namespace sl::analytic
