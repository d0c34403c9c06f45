#pragma once
// The objects of a scene file: [[objects]] (a shape: a mesh file or a procedural shape, its
// placement and explicit inner boxes) and [[models]] (every part of a model read through assimp
// as an object of its own). Internal to scenes/.

#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "scenes/scene.h"
#include "scenes/scene_file.h"
#include "scenes/scene_sections.h"

namespace sl {

// Meshes are shared between objects that name the same file and fit.
using MeshCache = std::map<std::string, std::shared_ptr<const Mesh>>;

// A mesh file as a scene names it: relative to the scene file's folder, else in paths.data
// (meshes/ first). An error naming the places it really looked in when it is in none.
std::filesystem::path resolve_mesh_path(const std::string& file,
                                        const std::filesystem::path& base_dir,
                                        const SceneSearchPaths& paths, TableReader& r);

// An object's shape: `shape` and its parameters (scenes/scene_file.h).
std::shared_ptr<const Mesh> read_shape(TableReader& r, const std::filesystem::path& base_dir,
                                       const SceneSearchPaths& paths, MeshCache& cache);
// `inner = [{ min, max }, ...]`, in the object's local frame.
std::vector<Box> read_inner_boxes(TableReader& r, const std::string& origin,
                                  const std::string& context);
// One [[models]] entry: its parts appended to scene.objects, their materials to scene.materials.
void read_model(TableReader& r, const std::filesystem::path& base_dir,
                const SceneSearchPaths& paths, std::map<std::string, int>& material_index,
                Scene& scene);

}  // namespace sl
