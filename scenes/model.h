#pragma once
// Models read through assimp (glTF 2.0, OBJ, OFF, PLY, FBX, Collada, IFC, 3DS, STL and the other
// formats its importers know): every (node, mesh) pair becomes a part that keeps the node's name,
// its material and its place in the model. Polygons are triangulated by assimp's
// post-processing, which ear-clips non-convex polygons and keyhole polygons with holes. Quake 3
// BSP maps (.bsp) are read by the project instead (scenes/q3_bsp.h).

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "scenes/mesh.h"

namespace sl {

struct ModelPart {
    std::string name;      // the node's name, with "/<material>" when the node holds several meshes
    std::string material;  // the file's material name ("" when it has none)
    glm::vec3 diffuse{0.8f};
    float opacity = 1.0f;              // the file's opacity; below 1 marks glass by default
    glm::mat4 transform{1.0f};         // mesh frame -> model frame (the node's global transform)
    std::shared_ptr<const Mesh> mesh;  // shared by every node that instances it
};

struct Model {
    std::vector<ModelPart> parts;
    size_t triangle_count() const;
};

// Reads a model; throws sl::Error naming the file (and assimp's reason) when it cannot be read,
// holds no triangle, or exceeds the limits of scenes/mesh.h. Points and lines are dropped.
Model load_model(const std::filesystem::path& path);

// The whole model as one mesh in the model's frame (the node transforms applied).
Mesh flatten(const Model& model, const std::string& what);

}  // namespace sl
