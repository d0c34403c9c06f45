#pragma once
// Random inputs for the beam tree's oracles (tests/beamtree_*_test.cpp): numbers, directions and
// convex polygons; the shapes the canonical scenes hold; meshes as real models come (walls with
// openings, several parts in one mesh, open boxes, height fields, inside out, unwelded); and
// whole random scenes under one spot light. Deterministic in their seeds.

#include <memory>
#include <random>
#include <string>

#include <glm/mat4x4.hpp>

#include "beamtree/bounding_volumes.h"
#include "beamtree/geometry.h"
#include "scenes/mesh.h"
#include "scenes/scene.h"

namespace sl::test {

using bt::dvec3;

// Uniform in [lo, hi), from 27 bits of the generator.
double uniform(std::mt19937& rng, double lo, double hi);
dvec3 random_unit(std::mt19937& rng);
// A convex polygon of 3 to 10 vertices on a circle of `radius` about `center`, facing a random
// direction.
bt::Polygon random_convex_polygon(std::mt19937& rng, const dvec3& center, double radius);

// The shapes the canonical scenes are made of, made once: unit box, sphere, torus, plane, and the
// bunny fitted to 1 m.
struct ShapeMeshes {
    std::shared_ptr<const Mesh> box = std::make_shared<const Mesh>(make_box(glm::vec3(1.0f)));
    std::shared_ptr<const Mesh> sphere = std::make_shared<const Mesh>(make_sphere(0.5f, 16));
    std::shared_ptr<const Mesh> torus = std::make_shared<const Mesh>(make_torus(0.5f, 0.2f, 16, 8));
    std::shared_ptr<const Mesh> plane = std::make_shared<const Mesh>(make_plane({1.0f, 1.0f}));
    std::shared_ptr<const Mesh> bunny;
    ShapeMeshes();
};
ShapeMeshes& shapes();

Object make_object(const std::string& name, std::shared_ptr<const Mesh> mesh,
                   const glm::mat4& transform);

// Meshes as real models come: non-convex, open, in several parts, inside out, unwelded.
// Each quad gets its own four vertices (nothing is welded), wound counter-clockwise seen from
// the side its normal points to.
struct MeshBuilder {
    Mesh mesh;
    void quad(dvec3 a, dvec3 b, dvec3 c, dvec3 d) {
        const auto base = uint32_t(mesh.positions.size());
        for (const dvec3& p : {a, b, c, d}) {
            mesh.positions.emplace_back(p);
        }
        mesh.triangles.emplace_back(base, base + 1, base + 2);
        mesh.triangles.emplace_back(base, base + 2, base + 3);
    }
    // The box [lo, hi] transformed by `m`, without the faces `skip` names (bit 2*axis + side).
    void box(const glm::dmat4& m, dvec3 lo, dvec3 hi, unsigned skip = 0) {
        auto at = [&](int i) {  // corner i: bit k picks hi on axis k
            return dvec3(
                m * glm::dvec4(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z, 1.0));
        };
        const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                 {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
        for (int f = 0; f < 6; ++f) {
            if (!(skip >> f & 1)) {
                quad(at(faces[f][0]), at(faces[f][1]), at(faces[f][2]), at(faces[f][3]));
            }
        }
    }
    std::shared_ptr<const Mesh> finish(bool inside_out) {
        if (inside_out) {
            for (glm::uvec3& t : mesh.triangles) {
                std::swap(t.y, t.z);
            }
        }
        compute_vertex_normals(mesh);
        return std::make_shared<const Mesh>(std::move(mesh));
    }
};

// A wall in x, y in [-1, 1], z in [-t, t] with one to three rectangular openings, as exporters
// write it (T-junctions, sometimes open, sometimes inside out).
std::shared_ptr<const Mesh> random_wall(std::mt19937& rng);
// Two or three boxes in one mesh, apart, touching or overlapping; sometimes one open.
std::shared_ptr<const Mesh> random_parts(std::mt19937& rng);
// A box with one to three faces missing.
std::shared_ptr<const Mesh> random_open_box(std::mt19937& rng);
// A height field over [-1, 1]^2, `n` quads a side (4 to 9 when 0), its normals facing +y, or -y
// when `inside_out`.
std::shared_ptr<const Mesh> random_terrain(std::mt19937& rng, int n = 0, bool inside_out = false);

struct RandomScene {
    Scene scene;
    std::string kinds;  // what it contains, for failure messages
};

// What random_scene() puts under its light:
//   canonical  boxes (some with explicit inner boxes), spheres, tori, the bunny, flat polygons
//              (some edge-on to the light), pairs of boxes sharing a face, overlapping objects;
//   real       walls with openings, several boxes in one mesh, open boxes, terrain, tori, and
//              rooms (large open boxes, some inside out) that hold the light;
//   terrain    height fields of 4 to 9 quads a side tilted by at most 35 degrees, their normals
//              facing towards the light on odd seeds and away from it on even ones.
enum class Shapes { canonical, real, terrain };

// A random scene under one spot light, with objects around and behind the light. An object with
// an outer volume (a piece's, with `library`'s options) that would contain the light is drawn
// again.
RandomScene random_scene(int seed, bt::VolumeLibrary& library, Shapes kinds = Shapes::canonical);

// A point around the light's cone: mostly inside it (up to 5% beyond its sides and far range),
// one in eight anywhere around the light.
dvec3 random_point(std::mt19937& rng, const SpotLight& light);

}  // namespace sl::test
