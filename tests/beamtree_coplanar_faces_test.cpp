// Coplanar faces (beamtree/coplanar_faces.h): a mesh's triangles joined into convex polygons.
// Checked against the triangles themselves: every triangle in one face, each face planar,
// strictly convex, wound as its triangles, and covering exactly their area; and the joins that
// must not happen (a fold, a winding that turns, a notch, a straight corner) do not.

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>

#include <glm/geometric.hpp>

#include "beamtree/coplanar_faces.h"
#include "scenes/mesh.h"

namespace sl::test {
namespace {

using dvec3 = glm::dvec3;

dvec3 at(const Mesh& mesh, uint32_t i) {
    return dvec3(mesh.positions[i]);
}

// The area vector of a face (Newell), or of a triangle.
dvec3 area_vector(const Mesh& mesh, const std::vector<uint32_t>& corners) {
    dvec3 sum(0.0);
    for (size_t i = 1; i + 1 < corners.size(); ++i) {
        sum += glm::cross(at(mesh, corners[i]) - at(mesh, corners[0]),
                          at(mesh, corners[i + 1]) - at(mesh, corners[0]));
    }
    return 0.5 * sum;
}

// The properties every result must have, on any mesh.
void expect_faces_tile_the_triangles(const Mesh& mesh, const bt::CoplanarFaces& result) {
    ASSERT_EQ(result.faces.size(), result.triangle.size());
    dvec3 faces_area(0.0), triangles_area(0.0);
    double extent = 0.0;
    for (const glm::vec3& p : mesh.positions) {
        extent =
            std::max({extent, double(std::abs(p.x)), double(std::abs(p.y)), double(std::abs(p.z))});
    }
    size_t corners = 0;
    for (size_t f = 0; f < result.faces.size(); ++f) {
        const std::vector<uint32_t>& face = result.faces[f];
        ASSERT_GE(face.size(), 3u);
        ASSERT_LE(face.size(), bt::CoplanarFaces::kMaxCorners);
        corners += face.size();
        const dvec3 area = area_vector(mesh, face);
        faces_area += area;
        const glm::uvec3 t = mesh.triangles[result.triangle[f]];
        const dvec3 own = area_vector(mesh, {t.x, t.y, t.z});
        if (glm::length(own) == 0.0) {
            continue;  // a degenerate triangle alone
        }
        const dvec3 n = glm::normalize(own);
        EXPECT_GT(glm::dot(area, n), 0.0) << "face " << f << " wound as its triangle";
        for (size_t i = 0; i < face.size(); ++i) {
            const dvec3 a = at(mesh, face[i]), b = at(mesh, face[(i + 1) % face.size()]),
                        c = at(mesh, face[(i + 2) % face.size()]);
            EXPECT_LE(std::abs(glm::dot(a - at(mesh, face[0]), n)), 1e-6 * extent) << "planar";
            EXPECT_GT(glm::dot(glm::cross(b - a, c - b), n), 0.0) << "face " << f << " convex";
        }
    }
    for (const glm::uvec3& t : mesh.triangles) {
        triangles_area += area_vector(mesh, {t.x, t.y, t.z});
    }
    // Summed area vectors (each face's, each triangle's) agree, and so do the unsigned areas
    // (triangles counted once each): the faces tile the triangles without gap or overlap.
    EXPECT_LT(glm::length(faces_area - triangles_area), 1e-9 * (1.0 + extent * extent));
    double faces_total = 0.0, triangles_total = 0.0;
    for (const auto& face : result.faces) {
        faces_total += glm::length(area_vector(mesh, face));
    }
    for (const glm::uvec3& t : mesh.triangles) {
        triangles_total += glm::length(area_vector(mesh, {t.x, t.y, t.z}));
    }
    EXPECT_NEAR(faces_total, triangles_total, 1e-9 * triangles_total);
    // Joining k triangles into a face of c corners: c = k + 2, so corners count the triangles.
    EXPECT_EQ(corners, mesh.triangles.size() + 2 * result.faces.size());
}

Mesh quad(const std::array<glm::vec3, 4>& corners) {
    Mesh mesh;
    mesh.positions.assign(corners.begin(), corners.end());
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    return mesh;
}

TEST(CoplanarFaces, ABoxIsSixSquares) {
    const Mesh box = make_box(glm::vec3(1.0f, 2.0f, 3.0f));
    const bt::CoplanarFaces result = bt::coplanar_faces(box);
    expect_faces_tile_the_triangles(box, result);
    ASSERT_EQ(result.faces.size(), 6u);
    for (const auto& face : result.faces) {
        EXPECT_EQ(face.size(), 4u);
    }
}

TEST(CoplanarFaces, OnlyFlatConvexConsistentlyWoundNeighboursJoin) {
    // A flat square: one face.
    EXPECT_EQ(bt::coplanar_faces(quad({{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}})).faces.size(),
              1u);
    // Folded by 1e-6 of its size: two (far above the 1e-9 it is joined within).
    EXPECT_EQ(
        bt::coplanar_faces(quad({{{0, 0, 0}, {1, 0, 0}, {1, 1, 1e-6f}, {0, 1, 0}}})).faces.size(),
        2u);
    // A dart (the quad is not convex): two.
    EXPECT_EQ(
        bt::coplanar_faces(quad({{{0, 0, 0}, {1, 0, 0}, {0.2f, 0.2f, 0}, {0, 1, 0}}})).faces.size(),
        2u);
    // A straight corner (0, 1, 2 on one line): two, or the face would have an edge of zero turn.
    EXPECT_EQ(bt::coplanar_faces(quad({{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {1, 1, 0}}})).faces.size(),
              2u);
    // The second triangle wound the other way: they walk their edge the same way, two faces.
    Mesh turned = quad({{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}});
    turned.triangles[1] = {0, 3, 2};
    EXPECT_EQ(bt::coplanar_faces(turned).faces.size(), 2u);
    // Corners that are copies of one position (a flat-shaded mesh) are welded first.
    Mesh copies = quad({{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}});
    copies.positions.push_back(copies.positions[0]);
    copies.positions.push_back(copies.positions[2]);
    copies.triangles[1] = {4, 5, 3};
    EXPECT_EQ(bt::coplanar_faces(copies).faces.size(), 1u);
}

TEST(CoplanarFaces, AFanOfARegularPolygonIsOneFace) {
    // A regular 12-gon fanned from one of its corners joins back into the 12-gon.
    Mesh disc;
    const int n = 12;
    for (int i = 0; i < n; ++i) {
        const float a = 2.0f * float(M_PI) * float(i) / float(n);
        disc.positions.emplace_back(std::cos(a), 0.0f, -std::sin(a));
    }
    for (uint32_t i = 1; i + 1 < uint32_t(n); ++i) {
        disc.triangles.emplace_back(0, i, i + 1);
    }
    const bt::CoplanarFaces result = bt::coplanar_faces(disc);
    expect_faces_tile_the_triangles(disc, result);
    EXPECT_EQ(result.faces.size(), 1u);
}

TEST(CoplanarFaces, TileEveryProceduralShapeAndRandomSoups) {
    std::vector<Mesh> meshes = {make_box(glm::vec3(2.0f)), make_sphere(1.0f, 24),
                                make_cylinder(0.5f, 2.0f, 32), make_torus(1.0f, 0.3f, 24, 12),
                                make_plane(glm::vec2(3.0f, 2.0f))};
    std::mt19937 rng(46);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int s = 0; s < 4; ++s) {  // random soups: shared corners, some on one plane
        Mesh soup;
        for (int i = 0; i < 40; ++i) {
            soup.positions.emplace_back(u(rng), s % 2 ? 0.0f : u(rng), u(rng));
        }
        std::uniform_int_distribution<uint32_t> pick(0, 39);
        for (int t = 0; t < 60; ++t) {
            soup.triangles.emplace_back(pick(rng), pick(rng), pick(rng));
        }
        meshes.push_back(std::move(soup));
    }
    for (const Mesh& mesh : meshes) {
        expect_faces_tile_the_triangles(mesh, bt::coplanar_faces(mesh));
    }
    // The cylinder's sides join into quads, and its caps (fans around a centre) into a few
    // faces each (a join stops where the centre would become a straight corner).
    const Mesh cylinder = make_cylinder(0.5f, 2.0f, 32);
    EXPECT_LT(bt::coplanar_faces(cylinder).faces.size(), cylinder.triangles.size());
}

}  // namespace
}  // namespace sl::test
