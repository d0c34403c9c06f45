#pragma once
// Triangle meshes: loading (OFF here, every other format through assimp: scenes/model.h),
// procedural shapes, validation. Positions are in the object's
// local frame; normals are per vertex (smooth for loaded meshes, flat per face for boxes).

#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace sl {

struct Bounds {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{std::numeric_limits<float>::lowest()};
    void extend(glm::vec3 p);
    glm::vec3 extent() const { return max - min; }
    glm::vec3 center() const { return 0.5f * (min + max); }
    bool empty() const { return min.x > max.x; }
};

struct Mesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::uvec3> triangles;

    Bounds bounds() const;
    double area() const;
    // True when every edge is shared by exactly two triangles (after welding equal positions).
    bool is_closed() const;
};

// What a loaded mesh may hold; beyond it a file is refused with an error naming the limit (a
// scene that needs more should be split, or decimated first).
constexpr long long kMaxMeshVertices = 1 << 24;
constexpr long long kMaxMeshTriangles = 1 << 25;
// What a procedural shape of a scene file may hold (a sphere of 1024 segments): the hulls, inner
// boxes and reference of a finer one take minutes, and a model file is the way to bring one.
constexpr long long kMaxShapeTriangles = 1 << 20;
// An OFF face is fanned when convex and ear-clipped otherwise (quadratic or worse in its size):
// polygons larger than this are not faces of a mesh but damage.
constexpr long long kMaxFaceVertices = 1024;

// Load by extension: .off with the reader below, every other format through assimp
// (scenes/model.h), the model's parts flattened into one mesh. Zero-area triangles are dropped.
Mesh load_mesh(const std::filesystem::path& path);
// OFF, read here rather than by assimp: Debian's assimp 5.2.5 OFF importer drops a face with an
// out-of-range or negative index without a word, where this reader names the file and line.
// Faces of more than three corners are triangulated (fanned if convex, else ear-clipped).
Mesh load_off(const std::filesystem::path& path);

// Procedural shapes, centred on the origin (the plane lies in y = 0 facing +y), outward normals.
Mesh make_box(glm::vec3 size);
Mesh make_sphere(float radius, int segments);
Mesh make_cylinder(float radius, float height, int segments);
Mesh make_torus(float major_radius, float minor_radius, int major_segments, int minor_segments);
Mesh make_plane(glm::vec2 size);

// Area-weighted vertex normals from the triangles.
void compute_vertex_normals(Mesh& mesh);
// Removes zero-area triangles; throws (naming `what`) on out-of-range indices, non-finite
// positions, or a mesh with no triangle left. Returns the number of triangles removed.
size_t validate_mesh(Mesh& mesh, const std::string& what);
// Uniform scale and translation so that the bounds' largest extent is `size`, centred in x and z,
// resting on y = 0.
void fit_mesh(Mesh& mesh, float size);

}  // namespace sl
