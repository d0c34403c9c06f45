// Quake 3 BSP maps (scenes/q3_bsp.h): maps written here byte by byte, a patch against an
// independent evaluation of its Bezier surface, a real OpenArena map against its own lumps, and
// bad files refused with one message.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "scenes/model.h"
#include "scenes/pk3.h"
#include "scenes/q3_bsp.h"
#include "scenes/scene_file.h"
#include "tests/support.h"

namespace sl::test {
namespace {

namespace fs = std::filesystem;
using q3::FaceType;

// A map's lumps as records, written in the id Tech 3 layout (the reader's format, written
// independently here: offsets from the format's description, not from the reader).
struct BspWriter {
    struct TextureRecord {
        std::string name;
        int32_t flags = 0, contents = 1;  // CONTENTS_SOLID
    };
    struct FaceRecord {
        int32_t texture = 0, type = 1, vertex = 0, vertices = 0, mesh_vertex = 0, mesh_vertices = 0,
                width = 0, height = 0;
    };
    std::vector<TextureRecord> textures;
    std::vector<std::pair<glm::vec3, glm::vec3>> vertices;  // position, normal
    std::vector<int32_t> mesh_vertices;
    std::vector<FaceRecord> faces;
    std::vector<std::pair<int32_t, int32_t>> models;  // first face, face count (none: one, all)
    int32_t version = 46;

    template <typename T>
    static void put(std::vector<std::byte>& out, const T& value) {
        const auto* p = reinterpret_cast<const std::byte*>(&value);
        out.insert(out.end(), p, p + sizeof value);
    }

    std::vector<std::byte> bytes() const {
        std::array<std::vector<std::byte>, 17> lumps;
        for (const TextureRecord& t : textures) {
            char name[64] = {};
            std::strncpy(name, t.name.c_str(), 63);
            lumps[1].insert(lumps[1].end(), reinterpret_cast<const std::byte*>(name),
                            reinterpret_cast<const std::byte*>(name) + 64);
            put(lumps[1], t.flags);
            put(lumps[1], t.contents);
        }
        for (const auto& [first, count] :
             models.empty() ? std::vector<std::pair<int32_t, int32_t>>{{0, int32_t(faces.size())}}
                            : models) {
            for (int k = 0; k < 6; ++k) {
                put(lumps[7], k < 3 ? -1000.0f : 1000.0f);
            }
            for (const int32_t v : {first, count, 0, 0}) {
                put(lumps[7], v);
            }
        }
        for (const auto& [position, normal] : vertices) {
            for (const float v : {position.x, position.y, position.z, 0.f, 0.f, 0.f, 0.f, normal.x,
                                  normal.y, normal.z}) {
                put(lumps[10], v);
            }
            put(lumps[10], uint32_t(0xffffffff));  // colour
        }
        for (const int32_t m : mesh_vertices) {
            put(lumps[11], m);
        }
        for (const FaceRecord& f : faces) {
            for (const int32_t v : {f.texture, -1, f.type, f.vertex, f.vertices, f.mesh_vertex,
                                    f.mesh_vertices, 0, 0, 0, 0, 0}) {
                put(lumps[13], v);
            }
            for (int k = 0; k < 12; ++k) {
                put(lumps[13], 0.0f);  // lightmap origin and vectors, normal
            }
            put(lumps[13], f.width);
            put(lumps[13], f.height);
        }
        std::vector<std::byte> out;
        out.insert(out.end(), reinterpret_cast<const std::byte*>("IBSP"),
                   reinterpret_cast<const std::byte*>("IBSP") + 4);
        put(out, version);
        int32_t offset = 8 + 17 * 8;
        for (const auto& lump : lumps) {
            put(out, offset);
            put(out, int32_t(lump.size()));
            offset += int32_t(lump.size());
        }
        for (const auto& lump : lumps) {
            out.insert(out.end(), lump.begin(), lump.end());
        }
        return out;
    }
};

q3::Map parse(const BspWriter& writer) {
    return q3::parse(writer.bytes(), "test.bsp");
}

// A unit quad at height z as a polygon face (two triangles, Quake 3's clockwise winding about
// +z) with texture `texture`.
void add_quad(BspWriter& w, int32_t texture, float z) {
    const auto first = int32_t(w.vertices.size());
    for (const glm::vec3 p :
         {glm::vec3(0, 0, z), glm::vec3(1, 0, z), glm::vec3(1, 1, z), glm::vec3(0, 1, z)}) {
        w.vertices.emplace_back(p, glm::vec3(0, 0, 1));
    }
    const auto mesh_first = int32_t(w.mesh_vertices.size());
    for (const int32_t m : {0, 2, 1, 0, 3, 2}) {  // clockwise seen from +z
        w.mesh_vertices.push_back(m);
    }
    w.faces.push_back({.texture = texture,
                       .type = 1,
                       .vertex = first,
                       .vertices = 4,
                       .mesh_vertex = mesh_first,
                       .mesh_vertices = 6});
}

// The reader keeps the drawn polygon and mesh faces, one part per texture, wound
// counter-clockwise about their normals (Quake 3 winds them the other way), and drops sky, fog
// and nodraw faces, billboards, and the faces of brush entities.
TEST(Q3Bsp, KeepsTheWorldsDrawnFacesOnePartPerTexture) {
    BspWriter w;
    w.textures = {{"textures/base/floor"},
                  {"textures/skies/sky", q3::kSurfaceSky},
                  {"textures/fog/fog", 0, q3::kContentsFog},
                  {"textures/common/caulk", q3::kSurfaceNoDraw},
                  {"textures/liquids/water", 0, q3::kContentsWater}};
    add_quad(w, 0, 0.0f);
    add_quad(w, 0, 2.0f);
    add_quad(w, 1, 5.0f);
    add_quad(w, 2, 6.0f);
    add_quad(w, 3, 7.0f);
    add_quad(w, 4, 1.0f);
    w.faces.push_back({.texture = 0, .type = 4, .vertex = 0, .vertices = 1});  // a billboard
    add_quad(w, 0, 9.0f);                                                      // a door
    w.models = {{0, 7}, {7, 1}};
    const Model model = q3::to_model(parse(w), "test.bsp");
    ASSERT_EQ(model.parts.size(), 2u);
    EXPECT_EQ(model.parts[0].name, "textures/base/floor");
    EXPECT_EQ(model.parts[0].material, "textures/base/floor");
    EXPECT_EQ(model.parts[0].mesh->triangles.size(), 4u) << "two quads; not the door's";
    EXPECT_EQ(model.parts[0].opacity, 1.0f);
    EXPECT_EQ(model.parts[1].name, "textures/liquids/water");
    EXPECT_LT(model.parts[1].opacity, 1.0f) << "water is glass";
    for (const ModelPart& part : model.parts) {
        const Mesh& mesh = *part.mesh;
        for (const glm::uvec3& t : mesh.triangles) {
            const glm::vec3 n = glm::cross(mesh.positions[t.y] - mesh.positions[t.x],
                                           mesh.positions[t.z] - mesh.positions[t.x]);
            EXPECT_GT(glm::dot(n, mesh.normals[t.x]), 0.0f) << part.name;
            EXPECT_LT(mesh.positions[t.x].z, 3.0f) << "sky, fog, caulk and the door dropped";
        }
    }
    EXPECT_GE(model.parts[0].diffuse.x, 0.45f);
    EXPECT_LE(model.parts[0].diffuse.x, 0.75f);
}

// The control grid of a patch piece along one direction, evaluated by de Casteljau (an oracle
// independent of the reader's Bernstein weights).
glm::vec3 de_casteljau(glm::vec3 a, glm::vec3 b, glm::vec3 c, float t) {
    const glm::vec3 ab = glm::mix(a, b, t), bc = glm::mix(b, c, t);
    return glm::mix(ab, bc, t);
}

glm::vec3 patch_point(const std::vector<q3::Vertex>& control, int width, int piece_u, int piece_v,
                      float s, float t) {
    glm::vec3 rows[3];
    for (int j = 0; j < 3; ++j) {
        auto at = [&](int i) {
            return control[size_t((2 * piece_v + j) * width + 2 * piece_u + i)].position;
        };
        rows[j] = de_casteljau(at(0), at(1), at(2), s);
    }
    return de_casteljau(rows[0], rows[1], rows[2], t);
}

// Edges met by one triangle only, after welding equal positions.
std::multiset<std::pair<int, int>> border_edges(const Mesh& mesh) {
    std::map<std::array<float, 3>, int> ids;
    std::vector<int> id(mesh.positions.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3 p = mesh.positions[i];
        id[i] = ids.try_emplace({p.x, p.y, p.z}, int(ids.size())).first->second;
    }
    std::map<std::pair<int, int>, int> uses;
    for (const glm::uvec3& t : mesh.triangles) {
        for (int k = 0; k < 3; ++k) {
            const int a = id[t[k]], b = id[t[(k + 1) % 3]];
            ++uses[{std::min(a, b), std::max(a, b)}];
        }
    }
    std::multiset<std::pair<int, int>> border;
    for (const auto& [edge, count] : uses) {
        EXPECT_LE(count, 2) << "an edge met by more than two triangles";
        if (count == 1) {
            border.insert(edge);
        }
    }
    return border;
}

// A curved 5 x 3 patch (two pieces side by side): every grid vertex lies on the Bezier surface,
// the corners are the control corners, every chord lies within the tolerance of the surface,
// normals agree with the triangles' winding, and the only border is the grid's outline (no crack
// between the pieces).
TEST(Q3Bsp, APatchTessellatesOntoItsBezierSurfaceWithoutCracks) {
    std::vector<q3::Vertex> control;
    for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 5; ++i) {
            const float x = 32.0f * float(i), y = 32.0f * float(j);
            const float z = (i == 1 ? 40.0f : i == 3 ? -25.0f : 0.0f) + (j == 1 ? 30.0f : 0.0f);
            control.push_back({{x, y, z}, {0.0f, 0.0f, 1.0f}});
        }
    }
    const Mesh mesh = q3::tessellate_patch(control, 5, 3);
    ASSERT_GT(mesh.triangles.size(), 8u) << "curved: more than one segment per piece";
    // The grid: columns along u (two pieces), rows along v (one piece).
    size_t columns = 0;
    while (columns < mesh.positions.size() && mesh.positions[columns].y == 0.0f) {
        ++columns;
    }
    const size_t rows = mesh.positions.size() / columns;
    ASSERT_EQ(rows * columns, mesh.positions.size());
    ASSERT_EQ((columns - 1) % 2, 0u);
    const size_t level_u = (columns - 1) / 2, level_v = rows - 1;
    for (size_t r = 0; r < rows; ++r) {
        for (size_t c = 0; c < columns; ++c) {
            const int piece = std::min(int(c / level_u), 1);
            const float s = float(c - size_t(piece) * level_u) / float(level_u);
            const float t = float(r) / float(level_v);
            const glm::vec3 expected = patch_point(control, 5, piece, 0, s, t);
            EXPECT_LT(glm::length(mesh.positions[r * columns + c] - expected), 1e-3f) << r << c;
        }
    }
    EXPECT_EQ(mesh.positions.front(), control.front().position);
    EXPECT_EQ(mesh.positions.back(), control.back().position);
    // Chords within the tolerance: each grid edge's midpoint against the surface there.
    for (size_t r = 0; r < rows; ++r) {
        for (size_t c = 0; c + 1 < columns; ++c) {
            const int piece = std::min(int(c / level_u), 1);
            const float s = (float(c - size_t(piece) * level_u) + 0.5f) / float(level_u);
            const glm::vec3 mid =
                0.5f * (mesh.positions[r * columns + c] + mesh.positions[r * columns + c + 1]);
            const glm::vec3 surface =
                patch_point(control, 5, piece, 0, s, float(r) / float(level_v));
            EXPECT_LE(glm::length(mid - surface), q3::kPatchTolerance + 1e-3f);
        }
    }
    EXPECT_EQ(border_edges(mesh).size(), 2 * (columns - 1) + 2 * (rows - 1));
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::vec3 n = glm::cross(mesh.positions[t.y] - mesh.positions[t.x],
                                       mesh.positions[t.z] - mesh.positions[t.x]);
        EXPECT_GT(glm::dot(n, glm::vec3(0, 0, 1)), 0.0f) << "counter-clockwise about +z";
    }
}

// A patch whose control rows close on themselves (a column: the first and last control columns
// equal, as Quake 3's pillars are built) tessellates to a closed tube: its only borders are its
// two end rings, whatever the level chosen.
TEST(Q3Bsp, APatchClosingOnItselfTessellatesToAClosedTube) {
    // A square ring of 9 control points per row (4 quadratic pieces: corner-mid-corner), 3 rows.
    const glm::vec2 ring[9] = {{1, 0},   {1, 1},  {0, 1},  {-1, 1}, {-1, 0},
                               {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
    std::vector<q3::Vertex> control;
    for (int j = 0; j < 3; ++j) {
        for (const glm::vec2 p : ring) {
            control.push_back({{64.0f * p.x, 64.0f * p.y, 50.0f * float(j)}, {p.x, p.y, 0.0f}});
        }
    }
    const Mesh mesh = q3::tessellate_patch(control, 9, 3);
    const size_t border = border_edges(mesh).size();
    const auto ring_segments = size_t(std::count_if(mesh.positions.begin(), mesh.positions.end(),
                                                    [](glm::vec3 p) { return p.z == 0.0f; }));
    EXPECT_EQ(border, 2 * (ring_segments - 1)) << "two end rings, no seam";
}

// Control points near the float range's end (a fuzzer's find): the second difference that picks
// the level overflows to inf, and the patch takes the finest level rather than converting inf to
// an int; its surface itself stays finite.
TEST(Q3Bsp, APatchWhoseCurvatureOverflowsTakesTheFinestLevel) {
    std::vector<q3::Vertex> control;
    for (int k = 0; k < 9; ++k) {
        control.push_back({{float(k % 3), float(k / 3), k == 4 ? -3e38f : 3e38f}, {0, 0, 1}});
    }
    const Mesh mesh = q3::tessellate_patch(control, 3, 3);
    const auto side = size_t(q3::kMaxPatchLevel + 1);
    EXPECT_EQ(mesh.positions.size(), side * side);
    for (const glm::vec3& p : mesh.positions) {
        EXPECT_TRUE(std::isfinite(p.z));
    }
}

// What each malformed file is refused with: one message naming the file and what is wrong.
TEST(Q3Bsp, RefusesBadFilesWithOneClearError) {
    BspWriter good;
    good.textures = {{"textures/base/floor"}};
    add_quad(good, 0, 0.0f);
    const std::vector<std::byte> bytes = good.bytes();
    auto refused = [](const std::vector<std::byte>& b, const std::string& expected) {
        try {
            q3::to_model(q3::parse(b, "bad.bsp"), "bad.bsp");
            ADD_FAILURE() << "accepted; expected: " << expected;
        } catch (const Error& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find("bad.bsp: "), std::string::npos) << message;
            EXPECT_NE(message.find(expected), std::string::npos) << message;
        }
    };
    refused(std::vector<std::byte>(bytes.begin(), bytes.begin() + 100), "shorter than its");
    std::vector<std::byte> b = bytes;
    b[0] = std::byte{'X'};
    refused(b, "does not start with \"IBSP\"");
    BspWriter w = good;
    w.version = 38;
    refused(w.bytes(), "BSP version 38");
    b = bytes;
    const int32_t far = 1 << 30;
    std::memcpy(&b[8 + 8 * 13], &far, 4);
    refused(b, "the faces lump (offset 1073741824");
    b = bytes;
    const int32_t odd = 103;
    std::memcpy(&b[12 + 8 * 13], &odd, 4);
    refused(b, "not a multiple of its 104-byte records");
    w = good;
    w.faces[0].texture = 3;
    refused(w.bytes(), "faces record 0: texture 3 of 1");
    w = good;
    w.mesh_vertices[2] = 4;
    refused(w.bytes(), "faces record 0: mesh vertex 2 points at vertex 4 of the face's 4");
    w = good;
    w.faces[0].mesh_vertices = 5;
    refused(w.bytes(), "not whole triangles");
    w = good;
    w.faces[0].type = 7;
    refused(w.bytes(), "faces record 0: type 7");
    w = good;
    w.faces[0] = {.texture = 0, .type = 2, .vertex = 0, .vertices = 4, .width = 2, .height = 2};
    refused(w.bytes(), "a patch of 2 x 2 control points");
    w = good;
    w.vertices[1].first.y = std::nanf("");
    refused(w.bytes(), "vertices record 1: its position is not finite");
    w = good;
    w.models = {{0, 2}};
    refused(w.bytes(), "models record 0: faces 0 + 2 outside the 1 faces");
    w = good;
    w.textures[0].flags = q3::kSurfaceSky;
    refused(w.bytes(), "holds no drawn triangle");
    // Patches whose tessellation would pass the budget: many faces over one wavy grid.
    w = good;
    for (int j = 0; j < 31; ++j) {
        for (int i = 0; i < 31; ++i) {
            w.vertices.emplace_back(glm::vec3(i * 8.0f, j * 8.0f, (i + j) % 2 ? 500.0f : 0.0f),
                                    glm::vec3(0, 0, 1));
        }
    }
    for (int k = 0; k < 80; ++k) {
        w.faces.push_back(
            {.texture = 0, .type = 2, .vertex = 4, .vertices = 961, .width = 31, .height = 31});
    }
    refused(w.bytes(), "a game level holds far fewer");
}

fs::path real_map() {
    return SceneSearchPaths::defaults().data / "models" / "dm6ish.bsp";
}

// dm6ish from Debian's openarena-081-maps against its own lumps, read here from the header: the
// record counts, the triangles of its drawn polygon and mesh faces (each kept but the degenerate
// ones), a part per texture, every vertex within the world model's bounds, and the winding of
// every triangle about its file normals.
TEST(Q3Bsp, ReadsARealMapAgreeingWithItsLumps) {
    std::ifstream file(real_map(), std::ios::binary);
    ASSERT_TRUE(file) << real_map();
    const std::vector<char> chars((std::istreambuf_iterator<char>(file)),
                                  std::istreambuf_iterator<char>());
    auto header = [&](int lump, int field) {
        int32_t v;
        std::memcpy(&v, chars.data() + 8 + 8 * lump + 4 * field, 4);
        return v;
    };
    const q3::Map map = q3::parse(std::as_bytes(std::span<const char>(chars)), "dm6ish.bsp");
    EXPECT_EQ(map.textures.size(), size_t(header(1, 1) / 72));
    EXPECT_EQ(map.models.size(), size_t(header(7, 1) / 40));
    EXPECT_EQ(map.vertices.size(), size_t(header(10, 1) / 44));
    EXPECT_EQ(map.mesh_vertices.size(), size_t(header(11, 1) / 4));
    EXPECT_EQ(map.faces.size(), size_t(header(13, 1) / 104));
    const q3::BrushModel& world = map.models.front();
    size_t flat = 0, patches = 0;
    std::set<int32_t> textures;
    for (int32_t f = world.first_face; f < world.first_face + world.face_count; ++f) {
        const q3::Face& face = map.faces[size_t(f)];
        if (face.type == FaceType::billboard || !map.textures[size_t(face.texture)].drawn()) {
            continue;
        }
        textures.insert(face.texture);
        patches += face.type == FaceType::patch ? 1 : 0;
        flat += face.type == FaceType::patch ? 0 : size_t(face.mesh_vertex_count / 3);
    }
    // Counted independently (a Python reading of the lumps): 1441 faces in the world model, 4933
    // triangles and 60 patches drawn, over 26 textures.
    EXPECT_EQ(world.face_count, 1441);
    EXPECT_EQ(flat, 4933u);
    EXPECT_EQ(patches, 60u);
    EXPECT_EQ(textures.size(), 26u);
    const Model model = load_model(real_map());
    EXPECT_EQ(model.parts.size(), textures.size());
    size_t wound = 0, triangles = 0;
    for (const ModelPart& part : model.parts) {
        const Mesh& mesh = *part.mesh;
        triangles += mesh.triangles.size();
        for (const glm::vec3& p : mesh.positions) {
            for (int k = 0; k < 3; ++k) {
                EXPECT_GE(p[k], world.min[k] - 1e-3f);
                EXPECT_LE(p[k], world.max[k] + 1e-3f);
            }
        }
        for (const glm::uvec3& t : mesh.triangles) {
            const glm::vec3 n = glm::cross(mesh.positions[t.y] - mesh.positions[t.x],
                                           mesh.positions[t.z] - mesh.positions[t.x]);
            wound += glm::dot(n, mesh.normals[t.x] + mesh.normals[t.y] + mesh.normals[t.z]) > 0.0f;
        }
    }
    EXPECT_GT(triangles, flat) << "the patches add theirs";
    EXPECT_LE(triangles - flat, size_t(60 * 2 * 16 * 16)) << "at most the finest level";
    EXPECT_GE(double(wound), 0.99 * double(triangles)) << "counter-clockwise about the normals";
    std::printf(
        "dm6ish: %zu triangles (%zu of polygons and meshes, %zu of 60 patches), %zu "
        "parts\n",
        triangles, flat, triangles - flat, model.parts.size());
}

const fs::path kMapsArchive = "/usr/share/games/openarena/baseoa/pak1-maps.pk3";

// A map read from its pk3 (scenes/pk3.h; the archive Debian's openarena-081-maps installs) is the
// map the build extracted from it; an entry is matched without regard to case, and a missing one
// is named with the nearest entry; a file that is no zip is refused.
TEST(Q3Bsp, ReadsAMapFromItsPk3) {
    const Model extracted = load_model(real_map());
    const Model archived = q3::load_model(kMapsArchive, "maps/DM6ISH.bsp");
    ASSERT_EQ(archived.parts.size(), extracted.parts.size());
    for (size_t i = 0; i < archived.parts.size(); ++i) {
        EXPECT_EQ(archived.parts[i].name, extracted.parts[i].name);
        EXPECT_EQ(archived.parts[i].mesh->positions, extracted.parts[i].mesh->positions);
        EXPECT_EQ(archived.parts[i].mesh->triangles, extracted.parts[i].mesh->triangles);
    }
    EXPECT_EQ(pk3::entries(kMapsArchive, ".bsp").size(), 50u);
    try {
        q3::load_model(kMapsArchive, "maps/dm6isch.bsp");
        ADD_FAILURE() << "a missing entry accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no entry 'maps/dm6isch.bsp' (did you mean "
                                             "'maps/dm6ish.bsp'?)"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_THROW(q3::load_model(real_map(), "maps/dm6ish.bsp"), Error) << "a .bsp is no zip";
}

// In a scene file a pk3 takes `map`, which no other model file takes.
TEST(Q3Bsp, APk3InASceneNamesItsMap) {
    TempDir dir;
    const std::string head =
        "[camera]\nposition = [0.0, 1.0, 5.0]\ntarget = [0.0, 0.0, 0.0]\n"
        "[light]\nposition = [0.0, 5.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\n"
        "[beamtree]\noccluders = \"triangles\"\n[[models]]\n";
    auto message = [&](const std::string& models) {
        write_text(dir.path() / "s.toml", head + models);
        try {
            load_scene_file(dir.path() / "s.toml", SceneSearchPaths::defaults());
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("loaded");
    };
    const std::string file = "file = \"" + kMapsArchive.string() + "\"\n";
    EXPECT_EQ(message(file + "map = \"maps/dm6ish.bsp\"\n"), "loaded");
    EXPECT_NE(message(file).find("map: required with a .pk3 file: the map inside it to load (50 "
                                 "maps, such as 'maps/aggressor.bsp'"),
              std::string::npos)
        << message(file);
    const std::string bsp = "file = \"" + real_map().string() + "\"\nmap = \"maps/a.bsp\"\n";
    EXPECT_NE(message(bsp).find("map: names a map inside a .pk3 archive"), std::string::npos)
        << message(bsp);
}

}  // namespace
}  // namespace sl::test
