#pragma once
// Welding a mesh's equal positions: flat-shaded meshes repeat each corner once per face, and
// whether a mesh is closed (Mesh::is_closed) or which of its triangles bound a solid
// (beamtree/closed_surface.h) is a question about the welded corners.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace sl {

// One id per distinct position: bitwise-equal coordinates share one; ids count from 0 in the
// order of the positions sorted by x, then y, then z.
std::vector<uint32_t> weld_equal_positions(const std::vector<glm::vec3>& positions);

}  // namespace sl
