// Convex pieces (beamtree/pieces.h): every piece is convex, the pieces cover every triangle, and
// no piece reaches outside the mesh's own hull.
#include <gtest/gtest.h>

#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "beamtree/bounding_volumes.h"
#include "beamtree/pieces.h"

namespace sl::test {
namespace {

// A wall 4 x 3 x 0.3 with a 1 x 1 window at (2, 1.5), as four boxes around the opening (one mesh
// of touching closed parts, as IFC exporters write them).
Mesh wall_with_window() {
    Mesh wall;
    auto add_box = [&](glm::vec3 lo, glm::vec3 hi) {
        Mesh box = make_box(hi - lo);
        const auto base = uint32_t(wall.positions.size());
        for (const glm::vec3& p : box.positions) {
            wall.positions.push_back(p + 0.5f * (lo + hi));
        }
        for (const glm::uvec3& t : box.triangles) {
            wall.triangles.push_back(t + base);
        }
    };
    add_box({0, 0, 0}, {1.5f, 3, 0.3f});
    add_box({2.5f, 0, 0}, {4, 3, 0.3f});
    add_box({1.5f, 0, 0}, {2.5f, 1, 0.3f});
    add_box({1.5f, 2, 0}, {2.5f, 3, 0.3f});
    compute_vertex_normals(wall);
    return wall;
}

void expect_pieces_cover_and_stay_inside(const Mesh& mesh,
                                         const std::vector<bt::ConvexVolume>& hulls) {
    const bt::ConvexVolume whole = bt::convex_hull(mesh, 0);
    const double extent = glm::length(mesh.bounds().extent());
    for (const bt::ConvexVolume& hull : hulls) {
        for (const bt::Polygon& face : hull.faces) {
            for (const glm::dvec3& v : face.vertices) {
                for (const bt::Plane& plane : hull.planes) {  // convex: behind every face plane
                    EXPECT_LE(plane.distance(v), 1e-9 * extent);
                }
                for (const bt::Plane& plane : whole.planes) {  // inside the mesh's own hull
                    EXPECT_LE(plane.distance(v), 1e-7 * extent);
                }
            }
        }
    }
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const glm::uvec3& t : mesh.triangles) {
        for (int sample = 0; sample < 8; ++sample) {
            double u = unit(random), v = unit(random);
            if (u + v > 1.0) {
                u = 1.0 - u;
                v = 1.0 - v;
            }
            const glm::dvec3 a(mesh.positions[t.x]), b(mesh.positions[t.y]), c(mesh.positions[t.z]);
            const glm::dvec3 p = a + u * (b - a) + v * (c - a);
            const bool covered = std::any_of(hulls.begin(), hulls.end(), [&](const auto& hull) {
                return hull.contains(p, -1e-7 * extent);
            });
            EXPECT_TRUE(covered) << p.x << " " << p.y << " " << p.z;
        }
    }
}

// (Whether a piece also covers part of the window is not checked.)
TEST(Pieces, AWallWithAWindowIsCutAndThePiecesCoverIt) {
    const Mesh wall = wall_with_window();
    const bt::Pieces pieces = bt::convex_pieces(wall);
    ASSERT_FALSE(pieces.whole);
    EXPECT_GE(pieces.parts.size(), 2u);
    EXPECT_LE(pieces.parts.size(), 8u);
    std::vector<bt::ConvexVolume> hulls;
    for (const Mesh& part : pieces.parts) {
        hulls.push_back(bt::convex_hull(part, 0));
    }
    expect_pieces_cover_and_stay_inside(wall, hulls);
}

// The process's shared libraries (what the methods build with) are one per option set, pieces
// included: the wall gets its pieces from the library of a scene that asks for them, even after
// the library with the same hull options and no pieces has been made. (Keyed without `pieces`,
// the house rendered after a scene without pieces got whole hulls: no lit region in the room.)
TEST(Pieces, SharedLibrariesAreOnePerOptionSetPiecesIncluded) {
    const auto wall = std::make_shared<const Mesh>(wall_with_window());
    bt::VolumeLibrary& whole = bt::VolumeLibrary::shared({.pieces = false});
    bt::VolumeLibrary& cut = bt::VolumeLibrary::shared({.pieces = true});
    EXPECT_NE(&whole, &cut);
    EXPECT_TRUE(whole.local(wall).pieces.empty());
    EXPECT_GE(cut.local(wall).pieces.size(), 2u);
}

// A convex mesh stays one piece (its hull is tight); a torus is cut, and its pieces cover it.
TEST(Pieces, ConvexMeshesStayWholeAndATorusIsCoveredByItsPieces) {
    EXPECT_TRUE(bt::convex_pieces(make_box(glm::vec3(1.0f, 2.0f, 0.5f))).whole);
    EXPECT_TRUE(bt::convex_pieces(make_sphere(1.0f, 24)).whole);
    const Mesh torus = make_torus(1.0f, 0.25f, 32, 12);
    const bt::Pieces pieces = bt::convex_pieces(torus);
    EXPECT_FALSE(pieces.whole);
    std::vector<bt::ConvexVolume> hulls;
    for (const Mesh& part : pieces.parts) {
        hulls.push_back(bt::convex_hull(part, 0));
    }
    for (const bt::ConvexVolume& hull : hulls) {
        EXPECT_FALSE(hull.contains(glm::dvec3(0.0), 0.0)) << "a piece covers the torus' hole";
    }
    expect_pieces_cover_and_stay_inside(torus, hulls);
}

// A piece's hull is grown by a small delta (beamtree/bounding_volumes.cpp), so that neighbouring
// pieces do not share faces. Offsetting the planes alone carries a sharp edge delta / sin(angle/2)
// away: for a wedge of 0.005 rad, 400 delta (found on the engine's thin pieces, 52 times the part's
// size). Grown, the volume still holds the wedge and stays within its box grown by 2 delta.
TEST(Pieces, GrownHullsOfSharpWedgesStayNearThem) {
    Mesh wedge;
    for (const float z : {0.0f, 1.0f}) {
        for (const glm::vec3 p :
             {glm::vec3(0, 0, z), glm::vec3(1, 0, z), glm::vec3(1, 0.005f, z)}) {
            wedge.positions.push_back(p);
        }
    }
    wedge.triangles = {{0, 2, 1}, {3, 4, 5}, {0, 1, 4}, {0, 4, 3},
                       {1, 2, 5}, {1, 5, 4}, {2, 0, 3}, {2, 3, 5}};
    const bt::ConvexVolume hull = bt::convex_hull(wedge, 0);
    const double delta = 1e-4;
    const bt::ConvexVolume grown = bt::inflated(hull, delta);
    ASSERT_FALSE(grown.empty());
    for (const glm::vec3& p : wedge.positions) {
        EXPECT_TRUE(grown.contains(glm::dvec3(p), 0.5 * delta)) << p.x << " " << p.y << " " << p.z;
    }
    const glm::dvec3 lo(0.0, 0.0, 0.0), hi(1.0, 0.005, 1.0);
    for (const bt::Polygon& face : grown.faces) {
        for (const glm::dvec3& v : face.vertices) {
            for (int a = 0; a < 3; ++a) {
                EXPECT_GE(v[a], lo[a] - 2.0 * delta) << "axis " << a;
                EXPECT_LE(v[a], hi[a] + 2.0 * delta) << "axis " << a;
            }
        }
    }
}

}  // namespace
}  // namespace sl::test
