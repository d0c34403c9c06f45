#include "scenes/q3_bsp.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "core/text.h"
#include "scenes/pk3.h"

namespace sl::q3 {

namespace {

constexpr size_t kHeaderSize = 8 + 8 * kLumpCount;
// Record sizes of the lumps read, in bytes (the id Tech 3 layout).
constexpr size_t kTextureSize = 72;
constexpr size_t kModelSize = 40;
constexpr size_t kVertexSize = 44;
constexpr size_t kFaceSize = 104;

const char* lump_name(Lump lump) {
    switch (lump) {
        case kTextures:
            return "textures";
        case kModels:
            return "models";
        case kVertices:
            return "vertices";
        case kMeshVertices:
            return "mesh vertices";
        case kFaces:
            return "faces";
        default:
            return "entities";
    }
}

// Little-endian reads from a record (the format is little-endian, as is every machine this
// builds on; memcpy keeps unaligned reads defined).
int32_t int_at(const std::byte* record, size_t offset) {
    int32_t value;
    std::memcpy(&value, record + offset, sizeof value);
    return value;
}

float float_at(const std::byte* record, size_t offset) {
    float value;
    std::memcpy(&value, record + offset, sizeof value);
    return value;
}

glm::vec3 vec3_at(const std::byte* record, size_t offset) {
    return {float_at(record, offset), float_at(record, offset + 4), float_at(record, offset + 8)};
}

bool finite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// One lump's records, checked against the file's size and the record size.
struct LumpView {
    const std::byte* data = nullptr;
    size_t count = 0;
    const std::byte* record(size_t i, size_t size) const { return data + i * size; }
};

class Reader {
public:
    Reader(std::span<const std::byte> bytes, const std::string& what) : bytes_(bytes), what_(what) {
        if (bytes.size() < kHeaderSize) {
            fail("{}: not a Quake 3 BSP map: {} bytes, shorter than its {}-byte header", what,
                 bytes.size(), kHeaderSize);
        }
        if (std::memcmp(bytes.data(), "IBSP", 4) != 0) {
            fail("{}: not a Quake 3 BSP map: it does not start with \"IBSP\"", what);
        }
        if (const int32_t version = int_at(bytes.data(), 4); version != 46 && version != 47) {
            fail("{}: BSP version {}; Quake 3 maps are version 46 (47: Quake Live)", what, version);
        }
    }

    LumpView lump(Lump lump, size_t record_size) const {
        const int32_t offset = int_at(bytes_.data(), 8 + 8 * size_t(lump));
        const int32_t length = int_at(bytes_.data(), 12 + 8 * size_t(lump));
        if (offset < 0 || length < 0 || size_t(offset) > bytes_.size() ||
            size_t(length) > bytes_.size() - size_t(offset)) {
            fail("{}: the {} lump (offset {}, length {}) lies outside the file's {} bytes", what_,
                 lump_name(lump), offset, length, bytes_.size());
        }
        if (size_t(length) % record_size != 0) {
            fail("{}: the {} lump's length {} is not a multiple of its {}-byte records", what_,
                 lump_name(lump), length, record_size);
        }
        return {bytes_.data() + offset, size_t(length) / record_size};
    }

    [[noreturn]] void refuse(Lump lump, size_t index, const std::string& why) const {
        fail("{}: {} record {}: {}", what_, lump_name(lump), index, why);
    }

private:
    std::span<const std::byte> bytes_;
    const std::string& what_;
};

std::vector<Texture> read_textures(const Reader& reader) {
    const LumpView lump = reader.lump(kTextures, kTextureSize);
    std::vector<Texture> textures(lump.count);
    for (size_t i = 0; i < lump.count; ++i) {
        const std::byte* record = lump.record(i, kTextureSize);
        const auto* name = reinterpret_cast<const char*>(record);
        textures[i].name = printable(std::string(name, strnlen(name, 64)));
        textures[i].surface_flags = int_at(record, 64);
        textures[i].contents = int_at(record, 68);
    }
    return textures;
}

std::vector<Vertex> read_vertices(const Reader& reader) {
    const LumpView lump = reader.lump(kVertices, kVertexSize);
    std::vector<Vertex> vertices(lump.count);
    for (size_t i = 0; i < lump.count; ++i) {
        const std::byte* record = lump.record(i, kVertexSize);
        vertices[i] = {vec3_at(record, 0), vec3_at(record, 28)};
        if (!finite(vertices[i].position)) {
            reader.refuse(kVertices, i, "its position is not finite");
        }
        if (!finite(vertices[i].normal)) {
            vertices[i].normal = glm::vec3(0.0f);  // computed from the triangles instead
        }
    }
    return vertices;
}

std::vector<int32_t> read_mesh_vertices(const Reader& reader) {
    const LumpView lump = reader.lump(kMeshVertices, 4);
    std::vector<int32_t> offsets(lump.count);
    for (size_t i = 0; i < lump.count; ++i) {
        offsets[i] = int_at(lump.record(i, 4), 0);
    }
    return offsets;
}

// [first, first + count) within [0, size).
bool in_range(int32_t first, int32_t count, size_t size) {
    return first >= 0 && count >= 0 && size_t(first) <= size && size_t(count) <= size - first;
}

void check_face(const Reader& reader, const Map& map, size_t index, const Face& face) {
    auto refuse = [&](const std::string& why) { reader.refuse(kFaces, index, why); };
    if (face.texture < 0 || size_t(face.texture) >= map.textures.size()) {
        refuse(fmt::format("texture {} of {}", face.texture, map.textures.size()));
    }
    if (!in_range(face.first_vertex, face.vertex_count, map.vertices.size())) {
        refuse(fmt::format("vertices {} + {} outside the {} vertices", face.first_vertex,
                           face.vertex_count, map.vertices.size()));
    }
    if (face.type == FaceType::polygon || face.type == FaceType::mesh) {
        if (!in_range(face.first_mesh_vertex, face.mesh_vertex_count, map.mesh_vertices.size()) ||
            face.mesh_vertex_count % 3 != 0) {
            refuse(fmt::format(
                "mesh vertices {} + {}: not whole triangles within the {} mesh "
                "vertices",
                face.first_mesh_vertex, face.mesh_vertex_count, map.mesh_vertices.size()));
        }
        for (int32_t k = 0; k < face.mesh_vertex_count; ++k) {
            const int32_t offset = map.mesh_vertices[size_t(face.first_mesh_vertex + k)];
            if (offset < 0 || offset >= face.vertex_count) {
                refuse(fmt::format("mesh vertex {} points at vertex {} of the face's {}",
                                   face.first_mesh_vertex + k, offset, face.vertex_count));
            }
        }
    } else if (face.type == FaceType::patch) {
        const int32_t w = face.patch_width, h = face.patch_height;
        if (w < 3 || h < 3 || w % 2 == 0 || h % 2 == 0 || w > kMaxPatchSize || h > kMaxPatchSize ||
            int64_t(w) * h != face.vertex_count) {
            refuse(
                fmt::format("a patch of {} x {} control points over {} vertices (odd sizes "
                            "from 3 to {}, their product the vertex count)",
                            w, h, face.vertex_count, kMaxPatchSize));
        }
    }
}

std::vector<Face> read_faces(const Reader& reader, const Map& map) {
    const LumpView lump = reader.lump(kFaces, kFaceSize);
    std::vector<Face> faces(lump.count);
    for (size_t i = 0; i < lump.count; ++i) {
        const std::byte* record = lump.record(i, kFaceSize);
        const int32_t type = int_at(record, 8);
        if (type < 1 || type > 4) {
            reader.refuse(kFaces, i,
                          fmt::format("type {} (1 polygon, 2 patch, 3 mesh, "
                                      "4 billboard)",
                                      type));
        }
        Face& face = faces[i];
        face.texture = int_at(record, 0);
        face.type = FaceType(type);
        face.first_vertex = int_at(record, 12);
        face.vertex_count = int_at(record, 16);
        face.first_mesh_vertex = int_at(record, 20);
        face.mesh_vertex_count = int_at(record, 24);
        face.patch_width = int_at(record, 96);
        face.patch_height = int_at(record, 100);
        if (face.type != FaceType::billboard) {
            check_face(reader, map, i, face);
        }
    }
    return faces;
}

std::vector<BrushModel> read_models(const Reader& reader, size_t face_count) {
    const LumpView lump = reader.lump(kModels, kModelSize);
    if (lump.count == 0) {
        reader.refuse(kModels, 0, "missing: a map has at least its world model");
    }
    std::vector<BrushModel> models(lump.count);
    for (size_t i = 0; i < lump.count; ++i) {
        const std::byte* record = lump.record(i, kModelSize);
        models[i] = {vec3_at(record, 0), vec3_at(record, 12), int_at(record, 24),
                     int_at(record, 28)};
        if (!in_range(models[i].first_face, models[i].face_count, face_count)) {
            reader.refuse(kModels, i,
                          fmt::format("faces {} + {} outside the {} faces", models[i].first_face,
                                      models[i].face_count, face_count));
        }
    }
    return models;
}

// Quadratic Bernstein weights at t.
std::array<float, 3> bernstein(float t) {
    const float s = 1.0f - t;
    return {s * s, 2.0f * s * t, t * t};
}

// Segments per 3x3 piece along one direction: the most any control line along it needs for its
// chords to lie within kPatchTolerance of the curve. A quadratic's chord is farthest from it at
// its middle, |P0 - 2 P1 + P2| / 4, and n equal segments divide that by n^2; the surface's
// second difference along a direction is a convex combination of its control lines', so their
// maximum bounds it.
int patch_level(std::span<const Vertex> control, int width, int height, bool along_width) {
    const int lines = along_width ? height : width;
    const int pieces = ((along_width ? width : height) - 1) / 2;
    float deviation = 0.0f;
    for (int line = 0; line < lines; ++line) {
        for (int piece = 0; piece < pieces; ++piece) {
            auto at = [&](int k) {
                const int i = along_width ? 2 * piece + k : line;
                const int j = along_width ? line : 2 * piece + k;
                return control[size_t(j) * size_t(width) + size_t(i)].position;
            };
            deviation = std::max(deviation, 0.25f * glm::length(at(0) - 2.0f * at(1) + at(2)));
        }
    }
    const float level = std::ceil(std::sqrt(deviation / kPatchTolerance));
    if (!(level < float(kMaxPatchLevel))) {  // also where the control points overflow to inf
        return kMaxPatchLevel;
    }
    return std::max(1, int(level));
}

// The piece a grid line falls in and the parameter within it (a border line belongs to the
// piece after it, the last line to the last piece).
std::pair<int, float> grid_piece(int line, int level, int pieces) {
    const int piece = std::min(line / level, pieces - 1);
    return {piece, float(line - piece * level) / float(level)};
}

std::span<const Vertex> face_vertices(const Map& map, const Face& face) {
    return std::span<const Vertex>(map.vertices)
        .subspan(size_t(face.first_vertex), size_t(face.vertex_count));
}

// One part's mesh, gathered face by face: a face's vertices are shared by its triangles.
class PartBuilder {
public:
    void add_triangles(const Map& map, const Face& face) {
        const auto base = uint32_t(mesh_.positions.size());
        for (const Vertex& v : face_vertices(map, face)) {
            mesh_.positions.push_back(v.position);
            file_normals_.push_back(v.normal);
        }
        for (int32_t k = 0; k + 2 < face.mesh_vertex_count; k += 3) {
            const int32_t* offsets = &map.mesh_vertices[size_t(face.first_mesh_vertex + k)];
            // Quake 3 winds its faces clockwise about their normals; ours turn the other way.
            push({base + uint32_t(offsets[0]), base + uint32_t(offsets[2]),
                  base + uint32_t(offsets[1])});
        }
    }

    void add_patch(const Mesh& patch) {
        const auto base = uint32_t(mesh_.positions.size());
        mesh_.positions.insert(mesh_.positions.end(), patch.positions.begin(),
                               patch.positions.end());
        file_normals_.insert(file_normals_.end(), patch.normals.begin(), patch.normals.end());
        for (const glm::uvec3& t : patch.triangles) {
            push(t + base);
        }
    }

    // No triangle of non-zero area (a part of only degenerate faces is left out).
    bool empty() const { return mesh_.triangles.empty(); }

    // The mesh, normals from the file where it gives them.
    std::shared_ptr<const Mesh> finish(const std::string& what) {
        validate_mesh(mesh_, what);
        compute_vertex_normals(mesh_);
        for (size_t i = 0; i < file_normals_.size(); ++i) {
            if (const float length = glm::length(file_normals_[i]); length > 1e-6f) {
                mesh_.normals[i] = file_normals_[i] / length;
            }
        }
        return std::make_shared<const Mesh>(std::move(mesh_));
    }

private:
    // Keeps a triangle of non-zero area (validate_mesh's criterion; patches of coincident control
    // points make many of zero area).
    void push(glm::uvec3 t) {
        const glm::vec3 a = mesh_.positions[t.x], b = mesh_.positions[t.y];
        if (glm::length(glm::cross(b - a, mesh_.positions[t.z] - a)) != 0.0f) {
            mesh_.triangles.push_back(t);
        }
    }

    Mesh mesh_;
    std::vector<glm::vec3> file_normals_;
};

// A grey in [0.45, 0.75] from the texture's name (FNV-1a), the same on every machine.
glm::vec3 grey_of(const std::string& name) {
    uint32_t hash = 2166136261u;
    for (const char c : name) {
        hash = (hash ^ uint8_t(c)) * 16777619u;
    }
    return glm::vec3(0.45f + 0.3f * float(hash % 1024u) / 1023.0f);
}

}  // namespace

bool Texture::drawn() const {
    return (surface_flags & (kSurfaceSky | kSurfaceNoDraw | kSurfaceHint | kSurfaceSkip)) == 0 &&
           (contents & kContentsFog) == 0;
}

bool Texture::opaque() const {
    return (contents & (kContentsWater | kContentsSlime | kContentsLava | kContentsTranslucent)) ==
           0;
}

Map parse(std::span<const std::byte> bytes, const std::string& what) {
    const Reader reader(bytes, what);
    Map map;
    map.textures = read_textures(reader);
    map.vertices = read_vertices(reader);
    map.mesh_vertices = read_mesh_vertices(reader);
    map.faces = read_faces(reader, map);
    map.models = read_models(reader, map.faces.size());
    return map;
}

Mesh tessellate_patch(std::span<const Vertex> control, int width, int height) {
    const int pieces_u = (width - 1) / 2, pieces_v = (height - 1) / 2;
    const int level_u = patch_level(control, width, height, true);
    const int level_v = patch_level(control, width, height, false);
    const int columns = pieces_u * level_u + 1, rows = pieces_v * level_v + 1;
    Mesh mesh;
    mesh.positions.reserve(size_t(columns) * size_t(rows));
    for (int row = 0; row < rows; ++row) {
        const auto [piece_v, t] = grid_piece(row, level_v, pieces_v);
        const std::array<float, 3> bv = bernstein(t);
        for (int column = 0; column < columns; ++column) {
            const auto [piece_u, s] = grid_piece(column, level_u, pieces_u);
            const std::array<float, 3> bu = bernstein(s);
            glm::vec3 position(0.0f), normal(0.0f);
            for (int j = 0; j < 3; ++j) {
                for (int i = 0; i < 3; ++i) {
                    const Vertex& c =
                        control[size_t(2 * piece_v + j) * size_t(width) + size_t(2 * piece_u + i)];
                    position += bu[size_t(i)] * bv[size_t(j)] * c.position;
                    normal += bu[size_t(i)] * bv[size_t(j)] * c.normal;
                }
            }
            const float length = glm::length(normal);
            mesh.positions.push_back(position);
            mesh.normals.push_back(length > 1e-6f ? normal / length : glm::vec3(0.0f));
        }
    }
    // Counter-clockwise about the normal (a patch's rows run along its normal's right hand, as
    // Quake 3 lays them out), as shaftlab's meshes are wound.
    for (int row = 0; row + 1 < rows; ++row) {
        for (int column = 0; column + 1 < columns; ++column) {
            const auto v00 = uint32_t(row * columns + column);
            const auto v10 = v00 + 1, v01 = v00 + uint32_t(columns), v11 = v01 + 1;
            mesh.triangles.emplace_back(v00, v10, v01);
            mesh.triangles.emplace_back(v10, v11, v01);
        }
    }
    return mesh;
}

Model to_model(const Map& map, const std::string& what) {
    const BrushModel& world = map.models.front();
    std::vector<PartBuilder> builders(map.textures.size());
    long long vertices = 0, triangles = 0;
    for (int32_t f = world.first_face; f < world.first_face + world.face_count; ++f) {
        const Face& face = map.faces[size_t(f)];
        if (face.type == FaceType::billboard || !map.textures[size_t(face.texture)].drawn()) {
            continue;
        }
        // A patch is tessellated before it is counted: one grid is at most (15 x 16 + 1)^2
        // vertices, so the budget still stops a file of many patches early.
        const bool patch = face.type == FaceType::patch;
        const Mesh grid =
            patch ? tessellate_patch(face_vertices(map, face), face.patch_width, face.patch_height)
                  : Mesh();
        vertices += patch ? static_cast<long long>(grid.positions.size()) : face.vertex_count;
        triangles +=
            patch ? static_cast<long long>(grid.triangles.size()) : face.mesh_vertex_count / 3;
        if (vertices > kMaxMapTriangles || triangles > kMaxMapTriangles) {
            fail(
                "{}: more than {} vertices or triangles (patches tessellated); a game level "
                "holds far fewer",
                what, kMaxMapTriangles);
        }
        PartBuilder& part = builders[size_t(face.texture)];
        patch ? part.add_patch(grid) : part.add_triangles(map, face);
    }
    Model model;
    std::unordered_map<std::string, int> names;
    for (size_t t = 0; t < builders.size(); ++t) {
        if (builders[t].empty()) {
            continue;
        }
        const Texture& texture = map.textures[t];
        ModelPart part;
        part.material = texture.name.empty() ? "texture" : texture.name;
        part.name = part.material;
        if (const int seen = names[part.name]++; seen > 0) {
            part.name += fmt::format("#{}", seen + 1);
        }
        part.diffuse = grey_of(part.material);
        part.opacity = texture.opaque() ? 1.0f : 0.5f;
        part.mesh = builders[t].finish(fmt::format("{}: texture {}", what, quote(part.name)));
        model.parts.push_back(std::move(part));
    }
    if (model.parts.empty()) {
        fail("{}: the map's world holds no drawn triangle", what);
    }
    return model;
}

Model load_model(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) {
        fail("{}: cannot open the map", path.string());
    }
    const std::vector<char> chars((std::istreambuf_iterator<char>(file)),
                                  std::istreambuf_iterator<char>());
    const auto bytes = std::as_bytes(std::span<const char>(chars));
    return to_model(parse(bytes, path.string()), path.string());
}

Model load_model(const std::filesystem::path& archive, const std::string& map) {
    const std::string what = fmt::format("{}: {}", archive.string(), quote(map));
    return to_model(parse(pk3::read_entry(archive, map), what), what);
}

}  // namespace sl::q3
