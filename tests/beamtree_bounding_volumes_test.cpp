// Bounding volumes (beamtree/bounding_volumes.h): hulls enclose their meshes, also reduced;
// volumes do not depend on the heap's layout; inner boxes lie inside their meshes (ray parity);
// an explicit inner box outside its mesh is refused; shared volumes are reused only while the
// scene state they were built from lasts.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "beamtree/beam_tree.h"
#include "beamtree/bounding_volumes.h"
#include "core/error.h"
#include "tests/random_scenes.h"
#include "tests/support.h"

namespace sl::test {
namespace {

// The hull encloses every vertex of the mesh, also when reduced to K planes, and has at most K.
TEST(BoundingVolumes, HullsEncloseTheirMeshesAlsoWhenReduced) {
    for (const auto& mesh : {shapes().bunny, shapes().torus, shapes().sphere}) {
        const bt::ConvexVolume full = bt::convex_hull(*mesh, 0);
        const bt::ConvexVolume reduced = bt::convex_hull(*mesh, 12);
        EXPECT_LE(reduced.faces.size(), 12u);
        EXPECT_GE(reduced.volume(), full.volume() * (1.0 - 1e-9));
        const double tolerance = 1e-7;
        for (const glm::vec3& p : mesh->positions) {
            for (const auto* volume : {&full, &reduced}) {
                for (const bt::Plane& plane : volume->planes) {
                    ASSERT_LE(plane.distance(dvec3(p)), tolerance);
                }
            }
        }
    }
    const bt::ConvexVolume flat = bt::convex_hull(*shapes().plane, 0);
    EXPECT_TRUE(flat.flat);
    ASSERT_EQ(flat.faces.size(), 2u);
    EXPECT_NEAR(bt::area(flat.faces[0]), 1.0, 1e-12);
}

// Crossings of the ray from p along +x with the mesh (brute force): odd means inside.
int crossings(const Mesh& mesh, const glm::vec3& p) {
    const CpuRayCaster* unused = nullptr;
    (void)unused;
    int count = 0;
    const dvec3 o(p), d(1.0, 1e-3, 2e-3);  // skewed to avoid edges
    for (const glm::uvec3& t : mesh.triangles) {
        const dvec3 a(mesh.positions[t.x]), e1 = dvec3(mesh.positions[t.y]) - a,
                                            e2 = dvec3(mesh.positions[t.z]) - a;
        const dvec3 q = glm::cross(d, e2);
        const double det = glm::dot(e1, q);
        if (std::abs(det) < 1e-20)
            continue;
        const dvec3 s = o - a;
        const double u = glm::dot(s, q) / det;
        const dvec3 r = glm::cross(s, e1);
        const double v = glm::dot(d, r) / det;
        const double h = glm::dot(e2, r) / det;
        count += u >= 0 && v >= 0 && u + v <= 1 && h > 0;
    }
    return count;
}

// Every bit of every volume's planes and faces, in order.
std::vector<double> volume_bits(const std::vector<bt::ObjectVolumes>& volumes) {
    std::vector<double> bits;
    auto add = [&](const bt::ConvexVolume& volume) {
        for (const bt::Plane& plane : volume.planes) {
            bits.insert(bits.end(), {plane.normal.x, plane.normal.y, plane.normal.z, plane.offset});
        }
        for (const bt::Polygon& face : volume.faces) {
            for (const dvec3& v : face.vertices) {
                bits.insert(bits.end(), {v.x, v.y, v.z});
            }
        }
    };
    for (const bt::ObjectVolumes& object : volumes) {
        add(object.outer);
        for (const bt::ConvexVolume& inner : object.inner) {
            add(inner);
        }
    }
    return bits;
}

// The volumes, and so the tree, are a function of the scene alone: building them again after
// the heap has been churned (other allocations move where CGAL's hull lands) gives the same
// bits, with the scene's plane budget and with full hulls. CGAL lists hull facets in an order
// that follows heap addresses and triangulates coplanar regions one way or another: before the
// facets, and then the merged planes, were made canonical, 'parallel' gave 1985 or 2005 nodes
// from one build to the next, and about 57,840 to 57,980 with full hulls.
TEST(BoundingVolumes, DoNotDependOnTheHeapLayout) {
    const Scene scene = load_canonical("parallel");
    for (const int max_outer_planes : {scene.bounds.max_outer_planes, 0}) {
        auto build = [&] {
            bt::VolumeLibrary library({.max_outer_planes = max_outer_planes,
                                       .automatic_inner = scene.bounds.automatic_inner});
            return library.build(scene, nullptr);
        };
        const std::vector<bt::ObjectVolumes> first = build();
        const std::vector<double> expected = volume_bits(first);
        const size_t nodes = bt::BeamTree(scene.light, first).stats().nodes;
        std::mt19937 random(7);
        for (int round = 0; round < 4; ++round) {
            // Fragment the heap: many blocks of random sizes, every other one kept while building.
            std::vector<std::vector<char>> blocks(4000);
            for (auto& block : blocks) {
                block.assign(std::uniform_int_distribution<size_t>(8, 4096)(random), char(round));
            }
            for (size_t i = 0; i < blocks.size(); i += 2) {
                std::vector<char>().swap(blocks[i]);
            }
            const std::vector<bt::ObjectVolumes> again = build();
            EXPECT_TRUE(volume_bits(again) == expected)
                << "planes " << max_outer_planes << " round " << round;
            EXPECT_EQ(bt::BeamTree(scene.light, again).stats().nodes, nodes)
                << "planes " << max_outer_planes << " round " << round;
        }
    }
}

// Automatic inner boxes lie inside their meshes (ray parity at random points of the box, and no
// crossing from its centre), and explicit boxes that stick out are rejected with an error.
TEST(BoundingVolumes, InnerBoxesAreInsideTheirMeshes) {
    std::mt19937 rng(3);
    for (const auto& mesh : {shapes().bunny, shapes().torus, shapes().sphere, shapes().box}) {
        const std::optional<Box> box = bt::inscribed_box(*mesh);
        ASSERT_TRUE(box.has_value());
        EXPECT_TRUE(bt::box_inside_mesh(*mesh, *box));
        for (int i = 0; i < 50; ++i) {
            const glm::vec3 f(uniform(rng, 0, 1), uniform(rng, 0, 1), uniform(rng, 0, 1));
            EXPECT_EQ(crossings(*mesh, box->min + f * (box->max - box->min)) % 2, 1);
        }
    }
    const Box outside{glm::vec3(-0.2f), glm::vec3(0.6f)};  // pokes out of the unit box
    EXPECT_FALSE(bt::box_inside_mesh(*shapes().box, outside));
    Scene scene = load_canonical("toplight");
    scene.objects[2].inner_boxes = {outside};
    bt::VolumeLibrary library;
    EXPECT_THROW(library.build(scene, nullptr), Error);
}

}  // namespace
}  // namespace sl::test

namespace sl::test {
namespace {

Mesh joined(const std::vector<Mesh>& parts) {
    Mesh out;
    for (const Mesh& part : parts) {
        const uint32_t base = uint32_t(out.positions.size());
        out.positions.insert(out.positions.end(), part.positions.begin(), part.positions.end());
        out.normals.insert(out.normals.end(), part.normals.begin(), part.normals.end());
        for (const glm::uvec3& t : part.triangles) {
            out.triangles.push_back(t + base);
        }
    }
    return out;
}

Mesh moved(Mesh mesh, glm::vec3 offset, float scale = 1.0f, bool inside_out = false) {
    for (glm::vec3& p : mesh.positions) {
        p = scale * p + offset;
    }
    if (inside_out) {
        for (glm::uvec3& t : mesh.triangles) {
            std::swap(t.y, t.z);
        }
    }
    return mesh;
}

// closed_surface (beamtree/closed_surface.h): which triangles may enter the tree only where they
// face the light, and each one's side: closed components oriented by their volumes' signs,
// inside-out ones and nested shells included, each on its own beside open components and
// components that cut themselves, whose triangles all stay (side 0).
TEST(ClosedSurface, OrientsClosedComponentsAndRefusesOpenOrSelfCuttingMeshes) {
    const Mesh box = make_box(glm::vec3(1.0f));
    auto signs = [](const bt::ClosedSurface& s) {
        return std::pair(std::count(s.outward.begin(), s.outward.end(), 1),
                         std::count(s.outward.begin(), s.outward.end(), -1));
    };
    const bt::ClosedSurface torus = bt::closed_surface(*shapes().torus);
    ASSERT_TRUE(torus.usable()) << torus.why_not;
    EXPECT_EQ(signs(torus).second, 0);
    const bt::ClosedSurface inverted = bt::closed_surface(moved(box, {}, 1.0f, true));
    ASSERT_TRUE(inverted.usable());
    EXPECT_EQ(signs(inverted), std::pair(0l, 12l));
    // Two boxes apart, one inside out: each component its own side.
    const bt::ClosedSurface apart =
        bt::closed_surface(joined({box, moved(box, {3, 0, 0}, 1.0f, true)}));
    ASSERT_TRUE(apart.usable()) << apart.why_not;
    EXPECT_EQ(signs(apart), std::pair(12l, 12l));
    // A hollow box: the cavity's shell wound inwards is a component of negative volume.
    const bt::ClosedSurface hollow = bt::closed_surface(joined({box, moved(box, {}, 0.5f, true)}));
    ASSERT_TRUE(hollow.usable()) << hollow.why_not;
    EXPECT_EQ(signs(hollow), std::pair(12l, 12l));
    EXPECT_EQ(hollow.outward.back(), -1);
    // Two boxes that cut each other: each is crossed in and out on its own.
    const bt::ClosedSurface overlapping =
        bt::closed_surface(joined({box, moved(box, {0.5f, 0.2f, 0.1f})}));
    ASSERT_TRUE(overlapping.whole()) << overlapping.why_not;
    EXPECT_EQ(signs(overlapping), std::pair(24l, 0l));
    // A box with a corner pulled through its opposite face cuts itself.
    Mesh pierced = box;
    for (glm::vec3& p : pierced.positions) {
        if (p == glm::vec3(0.5f)) {
            p = glm::vec3(-0.2f, -0.1f, -1.5f);
        }
    }
    EXPECT_FALSE(bt::closed_surface(pierced).usable());
    EXPECT_EQ(bt::closed_surface(pierced).why_not, "it cuts itself");
    Mesh open = box;
    open.triangles.pop_back();
    const bt::ClosedSurface opened = bt::closed_surface(open);
    EXPECT_FALSE(opened.usable());
    EXPECT_EQ(opened.why_not, "not closed and consistently wound");
    // Beside an open box and a pierced one, a closed box keeps its sides; theirs are 0.
    const bt::ClosedSurface mixed =
        bt::closed_surface(joined({moved(open, {3, 0, 0}), box, moved(pierced, {0, 6, 0})}));
    ASSERT_TRUE(mixed.usable());
    EXPECT_FALSE(mixed.whole());
    EXPECT_EQ(mixed.why_not, "not closed and consistently wound");
    ASSERT_EQ(mixed.outward.size(), 11u + 12u + 12u);
    EXPECT_EQ(std::count(mixed.outward.begin(), mixed.outward.begin() + 11, 0), 11);
    EXPECT_EQ(std::count(mixed.outward.begin() + 11, mixed.outward.begin() + 23, 1), 12);
    EXPECT_EQ(std::count(mixed.outward.begin() + 23, mixed.outward.end(), 0), 12);
}

// With [beamtree] occluders = triangles, a closed mesh's triangles come out wound outward in
// the world, also under a mirroring transform.
TEST(ClosedSurface, TrianglesComeOutWoundOutwardUnderAMirror) {
    Scene scene;
    scene.bounds.occluders = Occluders::triangles;
    scene.materials.push_back({});
    Object object;
    object.name = "box";
    object.mesh = std::make_shared<const Mesh>(make_box(glm::vec3(1.0f)));
    for (const float mirror : {1.0f, -1.0f}) {
        object.transform = glm::scale(glm::mat4(1.0f), glm::vec3(mirror, 1.0f, 1.0f));
        scene.objects = {object};
        bt::VolumeLibrary library(scene.bounds);
        library.set_caching(false);
        const std::vector<bt::ObjectVolumes> volumes = library.build(scene, nullptr);
        ASSERT_EQ(volumes.size(), 1u);
        EXPECT_TRUE(volumes[0].closed);
        for (const bt::Polygon& triangle : volumes[0].triangles) {
            const std::vector<dvec3>& v = triangle.vertices;
            const dvec3 normal = glm::cross(v[1] - v[0], v[2] - v[0]);
            EXPECT_GT(glm::dot(normal, (v[0] + v[1] + v[2]) / 3.0), 0.0) << "mirror " << mirror;
        }
    }
}

// Every outer face's and triangle's corners, in order: what a tree is built from.
std::vector<dvec3> corners_of(const std::vector<bt::ObjectVolumes>& volumes) {
    std::vector<dvec3> corners;
    for (const bt::ObjectVolumes& object : volumes) {
        for (const auto* polygons : {&object.outer.faces, &object.triangles}) {
            for (const bt::Polygon& polygon : *polygons) {
                corners.insert(corners.end(), polygon.vertices.begin(), polygon.vertices.end());
            }
        }
    }
    return corners;
}

// build_shared gives the faces of a point light one set of volumes, and builds anew (the same
// volumes build() gives) when an object moves, is renamed, stops casting shadows or the occluder
// setting changes. Fails if the memo ignores any of them.
TEST(VolumeLibrary, SharedVolumesLastAsLongAsTheirSceneState) {
    Scene scene;
    scene.bounds.occluders = Occluders::volumes;
    scene.materials.push_back({});
    for (int i = 0; i < 2; ++i) {
        Object object;
        object.name = i == 0 ? "left" : "right";
        object.mesh = std::make_shared<const Mesh>(make_box(glm::vec3(0.5f)));
        object.transform = glm::translate(glm::mat4(1.0f), glm::vec3(2.0f * float(i) - 1.0f, 0, 0));
        scene.objects.push_back(object);
    }
    PointLight bulb;
    bulb.position = glm::vec3(0.0f, 3.0f, 0.0f);
    scene.set_lights({bulb});
    ASSERT_EQ(scene.spot_lights().size(), 6u);

    bt::VolumeLibrary library(scene.bounds);
    const auto first = library.build_shared(scene.for_light(0));
    for (size_t face = 1; face < 6; ++face) {
        EXPECT_EQ(library.build_shared(scene.for_light(face)).get(), first.get()) << face;
    }
    EXPECT_EQ(corners_of(*first), corners_of(library.build(scene, nullptr)));

    // Each change is made to the state just answered, so only that change can tell them apart.
    auto expect_rebuilt = [&](const Scene& changed, const char* what) {
        const auto base = library.build_shared(scene);
        ASSERT_EQ(library.build_shared(scene).get(), base.get()) << what;
        const auto again = library.build_shared(changed);
        EXPECT_NE(again.get(), base.get()) << what;
        EXPECT_EQ(corners_of(*again), corners_of(library.build(changed, nullptr))) << what;
        ASSERT_EQ(again->size(), library.build(changed, nullptr).size()) << what;
        for (size_t i = 0; i < again->size(); ++i) {
            EXPECT_EQ((*again)[i].name, library.build(changed, nullptr)[i].name) << what;
        }
    };
    Scene moved = scene;
    moved.objects[1].transform = glm::translate(moved.objects[1].transform, glm::vec3(0, 0.25f, 0));
    expect_rebuilt(moved, "moved");
    Scene renamed = scene;
    renamed.objects[0].name = "port";
    expect_rebuilt(renamed, "renamed");
    Scene glass = scene;
    glass.materials.push_back({});
    glass.materials.back().casts_shadow = false;
    glass.objects[0].material = 1;
    ASSERT_FALSE(glass.casts_shadow(glass.objects[0]));
    expect_rebuilt(glass, "glass");
    Scene exact = scene;
    exact.bounds.occluders = Occluders::triangles;
    expect_rebuilt(exact, "triangles");

    library.set_caching(false);
    EXPECT_NE(library.build_shared(scene).get(), library.build_shared(scene).get());
}

}  // namespace
}  // namespace sl::test
