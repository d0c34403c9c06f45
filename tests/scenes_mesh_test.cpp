// Meshes: procedural shapes against closed-form volumes, the OFF and OBJ readers on real and
// malformed files.

#include <cmath>
#include <cstdint>
#include <numbers>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "core/error.h"
#include "scenes/mesh.h"
#include "scenes/scene_file.h"
#include "tests/support.h"

namespace sl::test {
namespace {

constexpr double kPi = std::numbers::pi;

// Signed volume by the divergence theorem: positive iff the triangles wind outwards.
double signed_volume(const Mesh& mesh) {
    double volume = 0.0;
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::dvec3 a(mesh.positions[t.x]), b(mesh.positions[t.y]), c(mesh.positions[t.z]);
        volume += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    return volume;
}

// Every closed procedural shape winds outwards and encloses its closed-form volume (to the
// accuracy of its tessellation, from below since the tessellation is inscribed).
TEST(Mesh, ProceduralShapesAreClosedOutwardAndHaveTheirVolume) {
    struct Case {
        const char* name;
        Mesh mesh;
        double volume;
        double tolerance;
    };
    const Case cases[] = {
        {"box", make_box({1.0f, 2.0f, 3.0f}), 6.0, 1e-6},
        {"sphere", make_sphere(0.5f, 96), 4.0 / 3.0 * kPi * 0.125, 0.005},
        {"cylinder", make_cylinder(0.5f, 2.0f, 128), kPi * 0.25 * 2.0, 0.002},
        {"torus", make_torus(1.0f, 0.25f, 128, 64), 2.0 * kPi * kPi * 1.0 * 0.0625, 0.003},
    };
    for (const Case& c : cases) {
        EXPECT_TRUE(c.mesh.is_closed()) << c.name;
        const double volume = signed_volume(c.mesh);
        EXPECT_GT(volume, 0.0) << c.name << " winds inwards";
        EXPECT_NEAR(volume / c.volume, 1.0, c.tolerance) << c.name;
        EXPECT_LE(volume, c.volume * (1.0 + 1e-6)) << c.name << " is inscribed";
        EXPECT_EQ(c.mesh.normals.size(), c.mesh.positions.size()) << c.name;
    }
    const Mesh plane = make_plane({2.0f, 3.0f});
    EXPECT_FALSE(plane.is_closed());
    EXPECT_NEAR(plane.area(), 6.0, 1e-6);
}

// Smooth vertex normals of a sphere point away from its centre.
TEST(Mesh, VertexNormalsPointOutwards) {
    const Mesh sphere = make_sphere(1.0f, 32);
    for (size_t i = 0; i < sphere.positions.size(); ++i) {
        EXPECT_GT(glm::dot(sphere.normals[i], glm::normalize(sphere.positions[i])), 0.99f);
    }
}

// The Stanford bunny from libcgal-demo loads completely.
TEST(Mesh, LoadsTheBunnyFromCgalData) {
    const Mesh bunny = load_mesh(SceneSearchPaths::defaults().data / "meshes" / "bunny00.off");
    EXPECT_EQ(bunny.positions.size(), 37706u);
    EXPECT_GT(bunny.triangles.size(), 75000u);
    EXPECT_GT(bunny.area(), 0.0);
}

// fit_mesh scales to the requested largest extent and rests the mesh on y = 0, centred in x, z.
TEST(Mesh, FitScalesAndRestsOnTheFloor) {
    Mesh box = make_box({2.0f, 4.0f, 1.0f});
    fit_mesh(box, 1.0f);
    const Bounds b = box.bounds();
    EXPECT_NEAR(b.extent().y, 1.0f, 1e-6f);
    EXPECT_NEAR(b.min.y, 0.0f, 1e-6f);
    EXPECT_NEAR(b.center().x, 0.0f, 1e-6f);
    EXPECT_NEAR(b.center().z, 0.0f, 1e-6f);
}

// Every malformed OFF file gives one error naming the file (and line) and the reason.
TEST(Mesh, MalformedOffFilesGiveClearErrors) {
    const std::pair<const char*, const char*> cases[] = {
        {"", "unexpected end of file"},
        {"OFX\n3 1 0\n", "expected 'OFF' header"},
        {"OFF\n3 one 0\n", "malformed counts"},
        {"OFF\n-3 1 0\n", "malformed counts"},
        {"OFF\n3 1 0\n0 0 0\n1 0 0\n", "unexpected end of file, expecting a vertex"},
        {"OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n", "malformed vertex"},
        {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", "face index 7 out of range"},
        {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "vertex count of at least 3"},
        {"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n", "fewer than 3 vertex indices"},
        {"OFF\n3 1 0\n0 0 0\n1 0 0\n2 0 0\n3 0 1 2\n", "no triangle of non-zero area"},
        {"OFF\n3 1 0\n0 0 0\n1e39 0 0\n0 1 0\n3 0 1 2\n", "vertex"},
        {"OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 # counts on the header line\n", nullptr},
    };
    TempDir dir;
    for (const auto& [text, expected] : cases) {
        const auto path = dir / "mesh.off";
        write_text(path, text);
        if (!expected) {
            EXPECT_EQ(load_mesh(path).triangles.size(), 1u);
            continue;
        }
        try {
            load_mesh(path);
            ADD_FAILURE() << "no error for:\n" << text;
        } catch (const Error& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find(expected), std::string::npos) << message;
            EXPECT_NE(message.find("mesh.off"), std::string::npos) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
        }
    }
    EXPECT_THROW(load_mesh(dir / "missing.off"), Error);
    write_text(dir / "mesh.ply", "ply\n");
    EXPECT_THROW(load_mesh(dir / "mesh.ply"), Error);
}

// OBJ files (through assimp): polygons with v/vt/vn corners and negative indices are read and
// triangulated; bad indices are one-line errors naming the file and line, empty files name the
// file.
TEST(Mesh, ObjFilesLoadAndBadOnesFail) {
    TempDir dir;
    write_text(dir / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    const Mesh quad = load_mesh(dir / "quad.obj");
    EXPECT_EQ(quad.triangles.size(), 2u);
    EXPECT_NEAR(quad.area(), 1.0, 1e-6);
    write_text(dir / "corners.obj",
               "o quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
               "s off\nf 1/1/1 2/1/1 3//1\nf -4 -2 -1\n");
    const Mesh corners = load_mesh(dir / "corners.obj");
    EXPECT_EQ(corners.triangles.size(), 2u);
    EXPECT_NEAR(corners.area(), 1.0, 1e-6);
    const std::pair<const char*, const char*> cases[] = {
        {"v 0 0 0\nv 1 0 0\nf 1 2 9\n", "bad.obj:3: vertex index 9 out of range"},
        {"# nothing\n", "cannot read the model"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", "bad.obj:4: vertex index -4 out of range"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", "bad.obj:4: vertex index 0 out of range"},
        // The fuzzer's find: an index out of range in a second group (assimp 5.2.5 leaks the
        // first group's mesh when it throws on this one).
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\ng first\nf 1 3 2\ng second\nf 3  24\n",
         "bad.obj:8: vertex index 24 out of range"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n",
         "bad.obj:5: texture coordinate index 2 out of range"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 \\\n 2//1 3//-2\n",
         "bad.obj:5: normal index -2 out of range"},
    };
    for (const auto& [text, expected] : cases) {
        write_text(dir / "bad.obj", text);
        try {
            load_mesh(dir / "bad.obj");
            ADD_FAILURE() << "no error for:\n" << text;
        } catch (const Error& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find(expected), std::string::npos) << message;
            EXPECT_NE(message.find("bad.obj"), std::string::npos) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
        }
    }
}

// PLY headers are checked before assimp reads the data: a count beyond the mesh limits (assimp
// reserves it first: a bad_alloc for 4e9 faces), more data than the file holds, an unknown type
// or format each give one line naming the file, the header line and what is wrong; a well-formed
// binary file with 16-bit list counts loads.
TEST(Mesh, PlyHeadersAreCheckedBeforeAssimpReadsTheData) {
    TempDir dir;
    auto binary = [](const std::string& header, int faces_written) {
        std::string data = header;
        const float vertices[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        data.append(reinterpret_cast<const char*>(vertices), sizeof(vertices));
        const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
        for (int f = 0; f < faces_written; ++f) {
            const uint16_t count = 3;  // little-endian on every machine this builds on
            data.append(reinterpret_cast<const char*>(&count), sizeof(count));
            data.append(reinterpret_cast<const char*>(faces[f]), sizeof(faces[f]));
        }
        return data;
    };
    auto header = [](const std::string& vertices, const std::string& faces,
                     const std::string& list = "ushort int") {
        return "ply\nformat binary_little_endian 1.0\nelement vertex " + vertices +
               "\nproperty float x\nproperty float y\nproperty float z\nelement face " + faces +
               "\nproperty list " + list + " vertex_indices\nend_header\n";
    };
    write_text(dir / "tetra.ply", binary(header("4", "4"), 4));
    EXPECT_EQ(load_mesh(dir / "tetra.ply").triangles.size(), 4u);
    const std::pair<std::string, std::string> cases[] = {
        {binary(header("4", "4000000000"), 4),
         "bad.ply:7: element 'face' declares 4000000000 items, at most 33554432"},
        {binary(header("4000000000", "4"), 4),
         "bad.ply:3: element 'vertex' declares 4000000000 items, at most 16777216"},
        {binary(header("4", "20000000"), 4),
         "bad.ply:9: the data ends in element 'face' item 5 of 20000000 (line 7)"},
        {binary(header("4", "4"), 2), "the data ends in element 'face' item 3 of 4 (line 7)"},
        {binary(header("4", "4", "half int"), 4), "bad.ply:8: unknown list type 'half'"},
        {binary(header("4", "4", "float int"), 4),
         "bad.ply:8: a list's count must be an integer type"},
        {binary(header("4", "-1"), 4), "bad.ply:7: element 'face': count '-1' is not"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
         "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
         "end_header\n0 0 0\n1 0 0\n",
         "which need at least 10 numbers, but 6 follow"},
        {"ply\nformat binary_middle_endian 1.0\nend_header\n",
         "bad.ply:2: unknown format 'binary_middle_endian'"},
        {"ply\nformat ascii 1.0\nelement vertex 3\n", "no end_header line"},
    };
    for (const auto& [text, expected] : cases) {
        write_text(dir / "bad.ply", text);
        try {
            load_mesh(dir / "bad.ply");
            ADD_FAILURE() << "no error; expected " << expected;
        } catch (const Error& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find(expected), std::string::npos) << message;
            EXPECT_NE(message.find("bad.ply"), std::string::npos) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
        }
    }
}

// A square with a square hole, written as one keyhole polygon (the outer ring, a bridge in, the
// inner ring the other way, the bridge out: how exporters write a wall with an opening), loads
// without filling the hole, in OBJ (assimp's triangulation) and in OFF (ours): area 16 - 4, and
// a ray through the hole's centre meets no triangle while one through the solid part does.
TEST(Mesh, KeyholePolygonsTriangulateWithoutFillingTheirHole) {
    TempDir dir;
    const std::string corners = "0 0 0\n4 0 0\n4 4 0\n0 4 0\n1 1 0\n1 3 0\n3 3 0\n3 1 0\n";
    std::string obj;
    for (size_t start = 0; start < corners.size();) {
        const size_t end = corners.find('\n', start);
        obj += "v " + corners.substr(start, end - start) + "\n";
        start = end + 1;
    }
    write_text(dir / "keyhole.obj", obj + "f 1 2 3 4 1 5 6 7 8 5\n");
    write_text(dir / "keyhole.off", "OFF\n8 1 0\n" + corners + "10 0 1 2 3 0 4 5 6 7 4\n");
    auto hits = [](const Mesh& mesh, glm::dvec2 p) {
        int count = 0;  // the vertical ray through (p, z) against each triangle, in 2D
        for (const glm::uvec3& t : mesh.triangles) {
            const glm::dvec2 a(mesh.positions[t.x]), b(mesh.positions[t.y]), c(mesh.positions[t.z]);
            auto side = [&](glm::dvec2 u, glm::dvec2 v) {
                return (v.x - u.x) * (p.y - u.y) - (v.y - u.y) * (p.x - u.x);
            };
            const double s0 = side(a, b), s1 = side(b, c), s2 = side(c, a);
            count += (s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0);
        }
        return count;
    };
    for (const char* name : {"keyhole.obj", "keyhole.off"}) {
        const Mesh mesh = load_mesh(dir / name);
        EXPECT_NEAR(mesh.area(), 12.0, 1e-5) << name;
        EXPECT_EQ(hits(mesh, {2.0, 2.0}), 0) << name << ": the hole is filled";
        EXPECT_EQ(hits(mesh, {0.5, 2.1}), 1) << name;
        EXPECT_EQ(hits(mesh, {3.5, 0.6}), 1) << name;
    }
}

// Every format claimed loads a small model of Debian's assimp-testmodels with the right
// triangle count and bounds (each file's numbers read off the file itself).
TEST(Mesh, EachClaimedFormatLoadsADebianTestModel) {
    const std::filesystem::path root = "/usr/share/assimp/models";
    struct Case {
        const char* file;
        size_t triangles;
        glm::vec3 min, max;
    };
    const Case cases[] = {
        {"OBJ/box.obj", 12, {-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}},
        {"PLY/cube.ply", 12, {0.f, 0.f, 0.f}, {1.f, 1.f, 1.f}},  // 6 quads
        // 1368 facets, of which the zero-area ones are dropped.
        {"STL/Spider_ascii.stl", 0, {-3.1149f, -4.f, -1.64933f}, {3.1149f, 4.f, 1.64933f}},
        {"glTF2/BoxTextured-glTF/BoxTextured.gltf", 12, {-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}},
        {"Collada/cube_triangulate.dae", 12, {-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}},
        {"FBX/box.fbx", 12, {}, {}},  // its node's transform is applied
        {"3DS/fels.3ds", 768, {}, {}},
        {"OFF/Cube.off", 12, {-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}},
    };
    for (const Case& c : cases) {
        const std::filesystem::path path = root / c.file;
        if (!std::filesystem::exists(path)) {
            ADD_FAILURE() << path << " is missing (assimp-testmodels: scripts/setup.sh)";
            continue;
        }
        SCOPED_TRACE(c.file);
        const Mesh mesh = load_mesh(path);
        EXPECT_GT(mesh.triangles.size(), 1300u * (c.file[0] == 'S'));
        EXPECT_LE(mesh.triangles.size(), 1368u);
        if (c.triangles > 0) {
            EXPECT_EQ(mesh.triangles.size(), c.triangles);
        }
        if (c.max != c.min) {
            const Bounds b = mesh.bounds();
            EXPECT_NEAR(glm::length(b.min - c.min), 0.0, 1e-4);
            EXPECT_NEAR(glm::length(b.max - c.max), 0.0, 1e-4);
        }
    }
}

// A face of 10^6 vertex indices (fuzzing found one hang the loader, and another the render) is
// refused with the limit named, in OFF and in OBJ; a face at the limit loads as its fan, one
// triangle per vertex beyond the second.
TEST(Mesh, HugeFacesAreRefusedAndFacesAtTheLimitFan) {
    TempDir dir;
    auto polygon = [](long long corners, long long vertices, bool obj) {
        std::string text = obj ? "" : fmt::format("OFF\n{} 1 0\n", vertices);
        for (long long i = 0; i < vertices; ++i) {
            const double angle = 2.0 * kPi * double(i) / double(vertices);
            text += fmt::format("{}{} {} 0\n", obj ? "v " : "", std::cos(angle), std::sin(angle));
        }
        text += obj ? "f" : std::to_string(corners);
        for (long long i = 0; i < corners; ++i) {
            text += fmt::format(" {}", i % vertices + (obj ? 1 : 0));
        }
        return text + "\n";
    };
    for (const bool obj : {false, true}) {
        const auto path = dir / (obj ? "face.obj" : "face.off");
        // (assimp itself refuses faces beyond 32767 corners, before the limit is checked)
        write_text(path, polygon(obj ? 4 * kMaxFaceVertices : 1'000'000, 1000, obj));
        try {
            load_mesh(path);
            ADD_FAILURE() << "a face of 10^6 vertices loaded";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(std::to_string(kMaxFaceVertices)),
                      std::string::npos)
                << e.what();
        }
        write_text(path, polygon(kMaxFaceVertices, kMaxFaceVertices, obj));
        const Mesh fan = load_mesh(path);
        EXPECT_EQ(fan.triangles.size(), size_t(kMaxFaceVertices - 2));
        EXPECT_NEAR(fan.area(), kPi, 1e-2);
    }
}

// Whatever bytes a file starts with, the error quotes them printable and truncated: a binary
// header's control bytes are escaped, a megabyte token is cut, the message stays one line.
TEST(Mesh, BinaryHeadersAreQuotedPrintableAndShort) {
    TempDir dir;
    const auto path = dir / "binary.off";
    write_text(path, std::string("\x01\x02\x1b[31mOFF\x7f") + std::string(100000, 'A') + "\n");
    try {
        load_mesh(path);
        ADD_FAILURE() << "a binary header loaded";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_LT(message.size(), 400u) << message;
        for (const char c : message) {
            EXPECT_FALSE(static_cast<unsigned char>(c) < 0x20 || c == 0x7f) << message;
        }
        EXPECT_NE(message.find("\\x1b[31mOFF\\x7f"), std::string::npos) << message;
        EXPECT_NE(message.find("(100011 bytes)"), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace sl::test
