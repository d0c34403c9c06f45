// The beam tree's geometry kernel (beamtree/geometry.h): splits and clips conserve area and
// volume, clipped polyhedra share their edges exactly, and convex polygons on a plane survive
// round-off.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include "beamtree/geometry.h"
#include "tests/random_scenes.h"

namespace sl::test {
namespace {

TEST(Geometry, SplitConservesArea) {
    std::mt19937 rng(1);
    for (int i = 0; i < 2000; ++i) {
        const bt::Polygon polygon =
            random_convex_polygon(rng, dvec3(uniform(rng, -5, 5)), uniform(rng, 0.01, 3));
        bt::Plane plane{random_unit(rng), 0.0};
        plane.offset =
            -glm::dot(plane.normal, bt::centroid(polygon) + uniform(rng, -1, 1) * random_unit(rng));
        const double epsilon = 1e-9;
        const bt::Split parts = bt::split(polygon, plane, epsilon);
        ASSERT_FALSE(parts.coplanar);
        const double total = bt::area(parts.front) + bt::area(parts.back);
        EXPECT_NEAR(total, bt::area(polygon), 1e-9 * bt::area(polygon) + 1e-15);
        for (const dvec3& v : parts.front.vertices)
            EXPECT_GE(plane.distance(v), -epsilon);
        for (const dvec3& v : parts.back.vertices)
            EXPECT_LE(plane.distance(v), epsilon);
    }
    // A polygon on the plane is reported coplanar, with both sides empty.
    const bt::Polygon square({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    const bt::Split on = bt::split(square, {{0, 0, 1}, 0.0}, 1e-9);
    EXPECT_TRUE(on.coplanar);
    EXPECT_TRUE(on.front.empty() && on.back.empty());
}

// Clipping keeps a polyhedron watertight to the last bit: every edge of every face is the reverse
// of an edge of another face with bitwise-equal endpoints (the two faces cut a shared edge at the
// same point), so the rasterized region meshes have no cracks.
TEST(Geometry, ClippedPolyhedraShareTheirEdgesExactly) {
    std::mt19937 rng(11);
    int checked = 0;
    for (int trial = 0; trial < 200; ++trial) {
        std::vector<bt::Plane> planes;
        for (int k = 0; k < 8; ++k) {
            planes.push_back({random_unit(rng), -uniform(rng, 0.5, 1.5)});
        }
        const bt::Polyhedron cell = bt::polyhedron_from_planes(planes, 4.0, 1e-9);
        if (cell.empty())
            continue;
        std::map<std::pair<std::array<double, 3>, std::array<double, 3>>, int> edges;
        auto key = [](const dvec3& v) { return std::array<double, 3>{v.x, v.y, v.z}; };
        for (const bt::Polygon& face : cell.faces) {
            for (size_t i = 0; i < face.size(); ++i) {
                const dvec3& a = face.vertices[i];
                const dvec3& b = face.vertices[(i + 1) % face.size()];
                ++edges[{key(a), key(b)}];
            }
        }
        size_t unmatched = 0;
        for (const auto& [edge, count] : edges) {
            const auto reverse = edges.find({edge.second, edge.first});
            unmatched += reverse == edges.end() || reverse->second != count;
        }
        EXPECT_EQ(unmatched, 0u) << "trial " << trial;
        ++checked;
    }
    EXPECT_GT(checked, 100);
}

// The convex polygon of points on a plane keeps exactly the corners and the area of its hull when
// the points also lie along its edges, repeat with last-bit differences, or fill its inside, and
// when its edges run along the plane's basis axes (cut points of clipped cells do all of this).
TEST(Geometry, ConvexPolygonOnPlaneIsRobustToRoundOff) {
    std::mt19937 rng(3);
    auto ulps = [&](double x) {
        const int k = int(rng() % 7) - 3;
        for (int i = 0; i < std::abs(k); ++i)
            x = std::nextafter(x, k > 0 ? INFINITY : -INFINITY);
        return x;
    };
    const double epsilon = 2.4e-8;
    for (int i = 0; i < 3000; ++i) {
        // A rectangle (often a sliver), in an axis plane or a random one, centred far from the
        // origin, so that every coordinate carries round-off.
        const bool axis_plane = i % 2 == 0;
        const dvec3 normal = axis_plane ? dvec3(0, 1, 0) : random_unit(rng);
        const bt::Plane plane{normal, 0.0};
        const dvec3 a = glm::normalize(
            axis_plane
                ? dvec3(1, 0, 0)
                : glm::cross(normal, std::abs(normal.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 1, 0)));
        const dvec3 b = glm::cross(normal, a);
        const double w = uniform(rng, 0.1, 2.0), h = w * std::pow(10.0, uniform(rng, -4.0, 0.0));
        const dvec3 origin = glm::dot(dvec3(uniform(rng, -20, 20)), a) * a +
                             glm::dot(dvec3(uniform(rng, -20, 20)), b) * b;
        const dvec3 corners[4] = {origin, origin + w * a, origin + w * a + h * b, origin + h * b};
        std::vector<dvec3> points;
        for (int c = 0; c < 4; ++c) {
            const dvec3& p = corners[c];
            const dvec3& q = corners[(c + 1) % 4];
            for (int k = int(rng() % 3); k >= 0; --k)  // the corner, repeated
                points.emplace_back(ulps(p.x), ulps(p.y), ulps(p.z));
            for (int k = int(rng() % 3); k > 0; --k) {  // on the edge
                const dvec3 e = p + uniform(rng, 0.05, 0.95) * (q - p);
                points.emplace_back(ulps(e.x), ulps(e.y), ulps(e.z));
            }
        }
        for (int k = int(rng() % 4); k > 0; --k)  // inside
            points.push_back(origin + uniform(rng, 0.1, 0.9) * w * a +
                             uniform(rng, 0.1, 0.9) * h * b);
        std::shuffle(points.begin(), points.end(), rng);
        const bt::Polygon polygon = bt::convex_polygon_on_plane(points, plane, epsilon);
        ASSERT_EQ(polygon.size(), 4u) << "case " << i << ": " << w << " x " << h;
        EXPECT_NEAR(bt::area(polygon), w * h, 1e-9 * w * h) << "case " << i;
        EXPECT_GT(glm::dot(bt::area_vector(polygon), normal), 0.0) << "counter-clockwise";
    }
}

// The descent's shortcut: where a polygon's bounding ball says a plane leaves the whole polygon
// on one side, split_straddling() says so too, vertex by vertex. The planes are put at the tie,
// the center's distance exactly the ball's radius plus ε (and within a few ulps of it), for
// polygons from 1 fm to 3 m across, near the origin and a kilometre away, and planes whose
// offsets are large (through a light far off).
TEST(Geometry, BallDecidesOnlyWhereEveryVertexDoes) {
    std::mt19937 rng(5);
    int decided = 0, agreed = 0;
    for (int i = 0; i < 20000; ++i) {
        const double scale = std::pow(10.0, uniform(rng, -15, 0.5));
        const double far = i % 2 ? 0.0 : 1000.0;
        const bt::Polygon polygon =
            random_convex_polygon(rng, dvec3(uniform(rng, -5, 5)) + far * random_unit(rng), scale);
        const bt::Ball ball = bt::bounding_ball(polygon);
        const double epsilon = std::pow(10.0, uniform(rng, -15, -5));
        bt::Plane plane{random_unit(rng), 0.0};
        const double side_sign = i % 4 < 2 ? 1.0 : -1.0;
        const int ulps = int(uniform(rng, -4, 4));
        double target = ball.radius + epsilon;
        for (int u = 0; u < std::abs(ulps); ++u) {
            target = std::nextafter(target, ulps > 0 ? 2.0 * target : 0.0);
        }
        plane.offset = side_sign * target - glm::dot(plane.normal, ball.center);
        const bt::Side by_ball = ball.side(plane, epsilon);
        if (by_ball == bt::Side::straddling) {
            continue;
        }
        ++decided;
        bt::Polygon front, back;
        const bt::Side by_vertex = bt::split_straddling(polygon, plane, epsilon, true, front, back);
        agreed += by_vertex == by_ball;
        ASSERT_EQ(by_vertex, by_ball) << "polygon " << i << " across " << scale << " m, epsilon "
                                      << epsilon << ", " << ulps << " ulps from the tie";
        EXPECT_TRUE(front.empty() && back.empty());
    }
    EXPECT_EQ(agreed, decided);
    // Away from the tie the ball decides: a plane a radius beyond it leaves every polygon whole.
    for (int i = 0; i < 1000; ++i) {
        const bt::Polygon polygon = random_convex_polygon(rng, dvec3(uniform(rng, -5, 5)), 1.0);
        const bt::Ball ball = bt::bounding_ball(polygon);
        const bt::Plane plane{random_unit(rng), 0.0};
        const bt::Plane beyond{plane.normal,
                               2.0 * ball.radius - glm::dot(plane.normal, ball.center)};
        ASSERT_EQ(ball.side(beyond, 1e-9), bt::Side::front);
        ASSERT_EQ(ball.side(beyond.flipped(), 1e-9), bt::Side::back);
        for (const dvec3& v : polygon.vertices) {
            ASSERT_LE(glm::length(v - ball.center), ball.radius);
        }
    }
}

// Clipping a convex polyhedron by a plane and by its flip conserves the volume.
TEST(Geometry, ClipConservesVolume) {
    std::mt19937 rng(2);
    const bt::ConvexVolume box =
        bt::box_volume({glm::vec3(-1.0f, -2.0f, -0.5f), glm::vec3(1.0f, 1.0f, 2.0f)});
    bt::Polyhedron cube;
    cube.faces = box.faces;
    EXPECT_NEAR(bt::volume(cube), 2.0 * 3.0 * 2.5, 1e-12);
    for (int i = 0; i < 500; ++i) {
        bt::Plane plane{random_unit(rng), uniform(rng, -1.5, 1.5)};
        const double v = bt::volume(bt::clip(cube, plane, 1e-12)) +
                         bt::volume(bt::clip(cube, plane.flipped(), 1e-12));
        EXPECT_NEAR(v, 15.0, 1e-10);
    }
}

}  // namespace
}  // namespace sl::test
