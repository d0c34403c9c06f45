#pragma once
// Quake 3 BSP maps (version 46, as id Tech 3 and OpenArena write them; 47 has the same lumps),
// read here rather than through assimp: Debian's assimp 5.2.5 Q3 BSP importer leaves its faces'
// indices unset, and its output fails assimp's own validation.
//
// What is kept is what a renderer draws of the world: the faces of the map's first model (the
// static world; brush entities such as doors and lifts move in the game, and their pose in the
// file is one arbitrary frame of that motion). Polygon and mesh faces keep their triangles,
// Bezier patches are tessellated (tessellate_patch), billboards are dropped, and so are the faces
// whose shader says they are not drawn: sky, nodraw, hint and skip surfaces, and fog volumes.
// Water, slime, lava and translucent surfaces are kept as glass (they cast no shadow).
// Textures are not read: each texture (shader) name becomes a part and its material, with a
// grey albedo taken from a hash of the name, so that surfaces differ in a picture.
//
// Coordinates stay the map's: Quake units (a player is 56 units tall, about an inch each) with z
// up. A scene places a map in metres with y up by `scale = [0.0254, 0.0254, 0.0254]` and
// `rotate = [-90, 0, 0]`.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "scenes/mesh.h"
#include "scenes/model.h"

namespace sl::q3 {

// The lumps of the format read here, by their index in the header's directory.
enum Lump : int {
    kEntities = 0,
    kTextures = 1,
    kModels = 7,
    kVertices = 10,
    kMeshVertices = 11,
    kFaces = 13,
    kLumpCount = 17
};

// Surface flags and content flags of a texture (the q3map compiler writes its shader's
// surfaceparms here).
constexpr int32_t kSurfaceSky = 0x4;
constexpr int32_t kSurfaceNoDraw = 0x80;
constexpr int32_t kSurfaceHint = 0x100;
constexpr int32_t kSurfaceSkip = 0x200;
constexpr int32_t kContentsLava = 0x8;
constexpr int32_t kContentsSlime = 0x10;
constexpr int32_t kContentsWater = 0x20;
constexpr int32_t kContentsFog = 0x40;
constexpr int32_t kContentsTranslucent = 0x20000000;

enum class FaceType : int32_t { polygon = 1, patch = 2, mesh = 3, billboard = 4 };

struct Texture {
    std::string name;
    int32_t surface_flags = 0;
    int32_t contents = 0;
    bool drawn() const;   // not sky, nodraw, hint, skip or fog
    bool opaque() const;  // not water, slime, lava or translucent
};

struct Vertex {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f};
};

struct Face {
    int32_t texture = 0;
    FaceType type = FaceType::polygon;
    int32_t first_vertex = 0, vertex_count = 0;
    int32_t first_mesh_vertex = 0, mesh_vertex_count = 0;
    int32_t patch_width = 0, patch_height = 0;  // control points of a patch (odd, >= 3)
};

struct BrushModel {
    glm::vec3 min{0.0f}, max{0.0f};
    int32_t first_face = 0, face_count = 0;
};

// The lumps above, each record checked: every index in range, every number finite, every
// patch's control grid odd and at least 3 by 3.
struct Map {
    std::vector<Texture> textures;
    std::vector<Vertex> vertices;
    std::vector<int32_t> mesh_vertices;  // offsets from a face's first vertex
    std::vector<Face> faces;
    std::vector<BrushModel> models;  // models[0] is the world
};

// The most triangles (and vertices) a map may give, patches tessellated: real levels hold 10^4
// to 10^5; beyond this a file is damage, or not a game level.
constexpr long long kMaxMapTriangles = 1 << 22;

// Parses a map's bytes; throws sl::Error naming `what`, the lump and the record on anything
// malformed (truncated, a wrong magic or version, a lump outside the file, an index out of range).
Map parse(std::span<const std::byte> bytes, const std::string& what);

// The largest patch control grid taken (Quake 3's own limit, MAX_PATCH_SIZE).
constexpr int kMaxPatchSize = 32;
// Patches are subdivided until a chord lies within this many units of the curved surface
// (Quake 3's r_subdivisions is 4), at most kMaxPatchLevel segments per 3x3 piece and direction.
constexpr float kPatchTolerance = 2.0f;
constexpr int kMaxPatchLevel = 16;

// A patch of width x height control points (row-major, width fastest) as a grid of triangles: it
// is made of biquadratic Bezier pieces of 3x3 control points sharing their border rows, each cut
// into the same number of segments per direction, so that neighbouring pieces meet without
// cracks. Normals are the control normals interpolated by the same Bezier, normalized.
Mesh tessellate_patch(std::span<const Vertex> control, int width, int height);

// The triangles of the world model's drawn faces, one part per texture (see the file comment).
Model to_model(const Map& map, const std::string& what);

// Reads a .bsp file: parse, then to_model. Throws sl::Error naming the file.
Model load_model(const std::filesystem::path& path);
// Reads the map `map` ("maps/dm6ish.bsp") from a pk3 archive (scenes/pk3.h).
Model load_model(const std::filesystem::path& archive, const std::string& map);

}  // namespace sl::q3
