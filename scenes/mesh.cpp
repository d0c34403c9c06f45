#include "scenes/mesh.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "scenes/weld.h"

namespace sl {

namespace fs = std::filesystem;

void Bounds::extend(glm::vec3 p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
}

Bounds Mesh::bounds() const {
    Bounds b;
    for (const glm::vec3& p : positions) {
        b.extend(p);
    }
    return b;
}

double Mesh::area() const {
    double sum = 0.0;
    for (const glm::uvec3& t : triangles) {
        const glm::dvec3 a(positions[t.x]), b(positions[t.y]), c(positions[t.z]);
        sum += 0.5 * glm::length(glm::cross(b - a, c - a));
    }
    return sum;
}

bool Mesh::is_closed() const {
    // Weld equal positions so that flat-shaded meshes (duplicated corners) count as closed.
    const std::vector<uint32_t> id = weld_equal_positions(positions);
    // Closed and consistently oriented: every directed edge once, and its reverse once.
    std::vector<uint64_t> edges;
    edges.reserve(triangles.size() * 3);
    for (const glm::uvec3& t : triangles) {
        const uint32_t v[3] = {id[t.x], id[t.y], id[t.z]};
        for (int e = 0; e < 3; ++e) {
            edges.push_back(uint64_t(v[e]) << 32 | v[(e + 1) % 3]);
        }
    }
    std::sort(edges.begin(), edges.end());
    for (size_t i = 0; i < edges.size(); ++i) {
        const uint64_t twin = edges[i] << 32 | edges[i] >> 32;
        if ((i + 1 < edges.size() && edges[i + 1] == edges[i]) ||
            !std::binary_search(edges.begin(), edges.end(), twin)) {
            return false;
        }
    }
    return !edges.empty();
}

void compute_vertex_normals(Mesh& mesh) {
    mesh.normals.assign(mesh.positions.size(), glm::vec3(0.0f));
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::vec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
        const glm::vec3 n = glm::cross(b - a, c - a);  // length = 2 * area: area weighting
        mesh.normals[t.x] += n;
        mesh.normals[t.y] += n;
        mesh.normals[t.z] += n;
    }
    for (glm::vec3& n : mesh.normals) {
        const float len = glm::length(n);
        n = len > 0.0f ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
    }
}

size_t validate_mesh(Mesh& mesh, const std::string& what) {
    for (const glm::vec3& p : mesh.positions) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            fail("{}: vertex position is not finite", what);
        }
    }
    const size_t count = mesh.positions.size();
    const size_t before = mesh.triangles.size();
    std::erase_if(mesh.triangles, [&](const glm::uvec3& t) {
        if (t.x >= count || t.y >= count || t.z >= count) {
            fail("{}: face index {} out of range (mesh has {} vertices)", what,
                 std::max({t.x, t.y, t.z}), count);
        }
        const glm::vec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
        return glm::length(glm::cross(b - a, c - a)) == 0.0f;
    });
    if (mesh.triangles.empty()) {
        fail("{}: mesh has no triangle of non-zero area", what);
    }
    return before - mesh.triangles.size();
}

void fit_mesh(Mesh& mesh, float size) {
    const Bounds b = mesh.bounds();
    const float extent = std::max({b.extent().x, b.extent().y, b.extent().z});
    if (!(extent > 0.0f)) {
        fail("mesh has zero extent: cannot fit it to size {}", size);
    }
    const float s = size / extent;
    const glm::vec3 origin(b.center().x, b.min.y, b.center().z);
    for (glm::vec3& p : mesh.positions) {
        p = (p - origin) * s;
    }
}

namespace {

// Reads the non-empty lines of a mesh file with '#' comments removed; tracks the line number for
// errors.
class LineReader {
public:
    explicit LineReader(const fs::path& path) : path_(path), in_(path) {
        if (!in_) {
            fail("{}: cannot open mesh file", path.string());
        }
    }
    // The next line, false at the end of the file.
    bool read(std::string& line) {
        while (std::getline(in_, line)) {
            ++line_number_;
            if (const size_t hash = line.find('#'); hash != std::string::npos) {
                line.resize(hash);
            }
            if (line.find_first_not_of(" \t\r") != std::string::npos) {
                return true;
            }
        }
        return false;
    }
    std::istringstream next(const char* expecting) {
        std::string line;
        if (!read(line)) {
            fail("{}: unexpected end of file, expecting {}", path_.string(), expecting);
        }
        return std::istringstream(line);
    }
    [[noreturn]] void error(const std::string& reason) const {
        fail("{}:{}: {}", path_.string(), line_number_, reason);
    }

private:
    fs::path path_;
    std::ifstream in_;
    int line_number_ = 0;
};

// Appends the triangles of a simple polygon given by vertex indices: a convex polygon is fanned
// from its first corner; any other one is ear-clipped in the plane of its Newell normal (a
// keyhole polygon, whose bridge edges run twice, clips like any other). Returns false when no ear
// is left, i.e. the polygon is not simple.
bool append_polygon(const std::vector<uint32_t>& face, Mesh& mesh) {
    const size_t n = face.size();
    const auto& p = mesh.positions;
    glm::dvec3 normal(0.0);  // Newell's method: robust for non-planar and non-convex polygons
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec3 a(p[face[i]]), b(p[face[(i + 1) % n]]);
        normal += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x),
                             (a.x - b.x) * (a.y + b.y));
    }
    auto turn = [&](uint32_t a, uint32_t b, uint32_t c) {
        return glm::dot(
            glm::cross(glm::dvec3(p[b]) - glm::dvec3(p[a]), glm::dvec3(p[c]) - glm::dvec3(p[b])),
            normal);
    };
    bool convex = true;
    for (size_t i = 0; i < n && convex; ++i) {
        convex = turn(face[i], face[(i + 1) % n], face[(i + 2) % n]) >= 0.0;
    }
    if (convex || glm::length(normal) == 0.0) {
        for (size_t k = 1; k + 1 < n; ++k) {
            mesh.triangles.emplace_back(face[0], face[k], face[k + 1]);
        }
        return true;
    }
    // Ear clipping: a corner is an ear when it turns left and no other corner lies inside its
    // triangle (in the polygon's plane). O(n^2) per ear found, so faces are capped in size.
    std::vector<uint32_t> ring = face;
    auto inside = [&](uint32_t q, uint32_t a, uint32_t b, uint32_t c) {
        return turn(a, b, q) > 0.0 && turn(b, c, q) > 0.0 && turn(c, a, q) > 0.0;
    };
    while (ring.size() > 3) {
        const size_t m = ring.size();
        bool clipped = false;
        for (size_t i = 0; i < m && !clipped; ++i) {
            const uint32_t a = ring[(i + m - 1) % m], b = ring[i], c = ring[(i + 1) % m];
            if (turn(a, b, c) <= 0.0) {
                continue;
            }
            bool ear = true;
            for (size_t j = 0; j < m && ear; ++j) {
                const uint32_t q = ring[j];
                ear = q == a || q == b || q == c || p[q] == p[a] || p[q] == p[b] || p[q] == p[c] ||
                      !inside(q, a, b, c);
            }
            if (ear) {
                mesh.triangles.emplace_back(a, b, c);
                ring.erase(ring.begin() + std::ptrdiff_t(i));
                clipped = true;
            }
        }
        if (!clipped) {
            return false;
        }
    }
    mesh.triangles.emplace_back(ring[0], ring[1], ring[2]);
    return true;
}

}  // namespace

Mesh load_off(const fs::path& path) {
    LineReader reader(path);
    std::istringstream header = reader.next("the OFF header");
    std::string magic;
    header >> magic;
    if (magic != "OFF") {
        reader.error(fmt::format("expected 'OFF' header, got {}", quote(magic)));
    }
    long long vertex_count = -1, face_count = -1, edge_count = 0;
    if (!(header >> vertex_count)) {  // the counts may sit on the header line or the next one
        header = reader.next("vertex, face and edge counts");
        header >> vertex_count;
    }
    if (!(header >> face_count >> edge_count) || vertex_count < 0 || face_count < 0) {
        reader.error("malformed counts line (expected: vertices faces edges)");
    }
    if (vertex_count > kMaxMeshVertices) {
        reader.error(fmt::format("{} vertices, at most {}", vertex_count, kMaxMeshVertices));
    }
    if (face_count > kMaxMeshTriangles) {
        reader.error(fmt::format("{} faces, at most {}", face_count, kMaxMeshTriangles));
    }
    Mesh mesh;
    mesh.positions.reserve(size_t(vertex_count));
    for (long long i = 0; i < vertex_count; ++i) {
        std::istringstream line = reader.next("a vertex");
        glm::vec3 p;
        if (!(line >> p.x >> p.y >> p.z)) {
            reader.error("malformed vertex (expected three numbers)");
        }
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            reader.error("vertex coordinate is not finite");
        }
        mesh.positions.push_back(p);
    }
    std::vector<uint32_t> face;
    for (long long i = 0; i < face_count; ++i) {
        std::istringstream line = reader.next("a face");
        long long n = 0;
        if (!(line >> n) || n < 3) {
            reader.error("malformed face (expected a vertex count of at least 3)");
        }
        if (n > kMaxFaceVertices) {
            reader.error(fmt::format("face of {} vertices, at most {}", n, kMaxFaceVertices));
        }
        face.resize(size_t(n));
        for (auto& v : face) {
            long long index = -1;
            if (!(line >> index)) {
                reader.error(fmt::format("face lists fewer than {} vertex indices", n));
            }
            if (index < 0 || index >= vertex_count) {
                reader.error(
                    fmt::format("face index {} out of range [0, {})", index, vertex_count));
            }
            v = uint32_t(index);
        }
        if (static_cast<long long>(mesh.triangles.size()) + n - 2 > kMaxMeshTriangles) {
            reader.error(fmt::format("more than {} triangles", kMaxMeshTriangles));
        }
        if (!append_polygon(face, mesh)) {
            reader.error(fmt::format("face of {} vertices is not a simple polygon", n));
        }
    }
    validate_mesh(mesh, path.string());
    compute_vertex_normals(mesh);
    return mesh;
}

Mesh make_box(glm::vec3 size) {
    Mesh mesh;
    const glm::vec3 h = 0.5f * size;
    // Each face: outward normal and two tangents whose cross product is the normal (CCW outside).
    const glm::vec3 axes[6][3] = {
        {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
        {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}}, {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}, {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}},
    };
    for (const auto& [n, u, v] : axes) {
        const auto base = uint32_t(mesh.positions.size());
        const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (const auto& c : corners) {
            mesh.positions.push_back(h * (n + c[0] * u + c[1] * v));
            mesh.normals.push_back(n);
        }
        mesh.triangles.emplace_back(base, base + 1, base + 2);
        mesh.triangles.emplace_back(base, base + 2, base + 3);
    }
    return mesh;
}

namespace {

// A (rows+1) x (columns+1) vertex grid mapped through `point(u, v)`, u and v in [0, 1], with the
// seam vertices welded (u always wraps, v wraps when wrap_v, poles collapse when collapse_v_ends)
// so the result is a closed manifold where the surface is.
template <typename PointFn>
Mesh make_grid_surface(int columns, int rows, bool wrap_v, bool collapse_v_ends, PointFn point) {
    // Orientation: triangles (a, b, c) wind counter-clockwise seen from where dp/du x dp/dv points.
    Mesh mesh;
    std::vector<uint32_t> index((columns + 1) * (rows + 1));
    auto at = [&](int i, int j) -> uint32_t& { return index[j * (columns + 1) + i]; };
    for (int j = 0; j <= rows; ++j) {
        for (int i = 0; i <= columns; ++i) {
            const bool pole = collapse_v_ends && (j == 0 || j == rows);
            if (i == columns) {
                at(i, j) = at(0, j);
            } else if (wrap_v && j == rows) {
                at(i, j) = at(i, 0);
            } else if (pole && i > 0) {
                at(i, j) = at(0, j);
            } else {
                at(i, j) = uint32_t(mesh.positions.size());
                mesh.positions.push_back(point(float(i) / columns, float(j) / rows));
            }
        }
    }
    for (int j = 0; j < rows; ++j) {
        for (int i = 0; i < columns; ++i) {
            const uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            if (a != b) {
                mesh.triangles.emplace_back(a, b, c);
            }
            if (c != d) {
                mesh.triangles.emplace_back(a, c, d);
            }
        }
    }
    compute_vertex_normals(mesh);
    return mesh;
}

constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;

}  // namespace

Mesh make_sphere(float radius, int segments) {
    const int rings = std::max(2, segments / 2);
    return make_grid_surface(segments, rings, false, true, [&](float u, float v) {
        const float phi = u * kTwoPi, theta = v * std::numbers::pi_v<float>;
        return radius * glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                  std::sin(theta) * std::sin(phi));
    });
}

Mesh make_cylinder(float radius, float height, int segments) {
    Mesh mesh;
    const float h = 0.5f * height;
    // Side (own vertices, radial normals), then two caps (own vertices, axial normals).
    for (int i = 0; i < segments; ++i) {
        const float phi = kTwoPi * float(i) / segments;
        const glm::vec3 n(std::cos(phi), 0.0f, std::sin(phi));
        mesh.positions.push_back(radius * n + glm::vec3(0, -h, 0));
        mesh.positions.push_back(radius * n + glm::vec3(0, h, 0));
        mesh.normals.push_back(n);
        mesh.normals.push_back(n);
    }
    for (int i = 0; i < segments; ++i) {
        const uint32_t a = 2 * i, b = 2 * ((i + 1) % segments);
        mesh.triangles.emplace_back(a, a + 1, b + 1);
        mesh.triangles.emplace_back(a, b + 1, b);
    }
    for (const float y : {-h, h}) {
        const auto center = uint32_t(mesh.positions.size());
        const glm::vec3 n(0.0f, y > 0 ? 1.0f : -1.0f, 0.0f);
        mesh.positions.emplace_back(0.0f, y, 0.0f);
        mesh.normals.push_back(n);
        for (int i = 0; i < segments; ++i) {
            const float phi = kTwoPi * float(i) / segments;
            mesh.positions.emplace_back(radius * std::cos(phi), y, radius * std::sin(phi));
            mesh.normals.push_back(n);
        }
        for (int i = 0; i < segments; ++i) {
            const uint32_t a = center + 1 + i, b = center + 1 + (i + 1) % segments;
            if (y > 0) {
                mesh.triangles.emplace_back(center, b, a);
            } else {
                mesh.triangles.emplace_back(center, a, b);
            }
        }
    }
    return mesh;
}

Mesh make_torus(float major_radius, float minor_radius, int major_segments, int minor_segments) {
    return make_grid_surface(major_segments, minor_segments, true, false, [&](float u, float v) {
        const float phi = u * kTwoPi, theta = v * kTwoPi;
        const float ring = major_radius + minor_radius * std::cos(theta);
        return glm::vec3(ring * std::cos(phi), -minor_radius * std::sin(theta),
                         ring * std::sin(phi));
    });
}

Mesh make_plane(glm::vec2 size) {
    Mesh mesh;
    const glm::vec2 h = 0.5f * size;
    mesh.positions = {{-h.x, 0, -h.y}, {h.x, 0, -h.y}, {h.x, 0, h.y}, {-h.x, 0, h.y}};
    mesh.normals.assign(4, glm::vec3(0, 1, 0));
    mesh.triangles = {{0, 2, 1}, {0, 3, 2}};
    return mesh;
}

}  // namespace sl
