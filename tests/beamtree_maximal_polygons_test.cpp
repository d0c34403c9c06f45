// Maximal polygons (beamtree/maximal_polygons.h): the union of conforming coplanar polygons,
// triangulated anew, against independent oracles — the covered points of a fine grid (the union
// covers a point once where one input polygon covers it, never where none does) and the directed
// edges (the result's unmatched edges are exactly the inputs' unmatched edges).

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "beamtree/conforming.h"
#include "beamtree/maximal_polygons.h"

namespace sl::test {
namespace {

using bt::dvec3;
using bt::Polygon;

Polygon rectangle(double x0, double y0, double x1, double y1) {
    return Polygon({{x0, y0, 0.0}, {x1, y0, 0.0}, {x1, y1, 0.0}, {x0, y1, 0.0}});
}

std::vector<const Polygon*> pointers(const std::vector<Polygon>& polygons) {
    std::vector<const Polygon*> out;
    for (const Polygon& p : polygons) {
        out.push_back(&p);
    }
    return out;
}

// Directed edges met from one side only, as (from, to) positions with their multiplicity.
using Edge = std::pair<std::array<double, 3>, std::array<double, 3>>;
std::map<Edge, int> unmatched(const std::vector<std::vector<dvec3>>& loops) {
    std::map<Edge, int> balance;
    for (const std::vector<dvec3>& loop : loops) {
        for (size_t k = 0; k < loop.size(); ++k) {
            const dvec3 &p = loop[k], &q = loop[(k + 1) % loop.size()];
            const std::array<double, 3> a{p.x, p.y, p.z}, b{q.x, q.y, q.z};
            if (a < b) {
                ++balance[{a, b}];
            } else if (b < a) {
                --balance[{b, a}];
            }
        }
    }
    std::erase_if(balance, [](const auto& entry) { return entry.second == 0; });
    return balance;
}

std::vector<std::vector<dvec3>> loops_of(const std::vector<Polygon>& polygons) {
    std::vector<std::vector<dvec3>> loops;
    for (const Polygon& p : polygons) {
        loops.push_back(p.vertices);
    }
    return loops;
}

std::vector<std::vector<dvec3>> loops_of(const bt::MaximalTriangulation& t) {
    std::vector<std::vector<dvec3>> loops;
    for (const glm::uvec3& tri : t.triangles) {
        loops.push_back({t.vertices[tri.x], t.vertices[tri.y], t.vertices[tri.z]});
    }
    return loops;
}

// How many times the loops cover p (in their plane, seen along +normal), counting each loop
// that winds around p counter-clockwise once: strict insides only, for points off every edge.
int coverage(const std::vector<std::vector<dvec3>>& loops, const dvec3& p, const dvec3& u,
             const dvec3& v) {
    int count = 0;
    for (const std::vector<dvec3>& loop : loops) {
        int winding = 0;
        for (size_t k = 0; k < loop.size(); ++k) {
            const dvec3 a = loop[k] - p, b = loop[(k + 1) % loop.size()] - p;
            const double ay = glm::dot(a, v), by = glm::dot(b, v);
            const double cross = glm::dot(a, u) * by - ay * glm::dot(b, u);
            if (ay <= 0.0 && by > 0.0 && cross > 0.0) {
                ++winding;
            } else if (ay > 0.0 && by <= 0.0 && cross < 0.0) {
                --winding;
            }
        }
        count += winding;
    }
    return count;
}

double signed_area(const std::vector<std::vector<dvec3>>& loops, const dvec3& normal) {
    double a = 0.0;
    for (const std::vector<dvec3>& loop : loops) {
        a += glm::dot(bt::area_vector(Polygon(loop)), normal);
    }
    return a;
}

TEST(MaximalPolygons, TwoSquaresSharingAnEdgeBecomeOneRectangle) {
    const std::vector<Polygon> squares = {rectangle(0, 0, 1, 1), rectangle(1, 0, 2, 1)};
    const auto t = bt::triangulate_union(pointers(squares), {0, 0, 1});
    ASSERT_TRUE(t);
    // Six vertices on the outline (the shared edge's ends stay: a neighbour may meet them).
    EXPECT_EQ(t->vertices.size(), 6u);
    EXPECT_EQ(t->triangles.size(), 4u);
    EXPECT_EQ(t->boundary_edges, 6u);
    EXPECT_DOUBLE_EQ(signed_area(loops_of(*t), {0, 0, 1}), 2.0);
    EXPECT_EQ(unmatched(loops_of(*t)), unmatched(loops_of(squares)));
}

TEST(MaximalPolygons, ARingKeepsItsHole) {
    std::vector<Polygon> cells;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            if (i != 1 || j != 1) {
                cells.push_back(rectangle(i, j, i + 1, j + 1));
            }
        }
    }
    const auto t = bt::triangulate_union(pointers(cells), {0, 0, 1});
    ASSERT_TRUE(t);
    // 12 outer and 4 hole vertices: n + 2h - 2 = 16 triangles.
    EXPECT_EQ(t->triangles.size(), 16u);
    const auto loops = loops_of(*t);
    EXPECT_EQ(coverage(loops, {1.5, 1.5, 0.0}, {1, 0, 0}, {0, 1, 0}), 0);
    EXPECT_EQ(coverage(loops, {0.5, 1.5, 0.0}, {1, 0, 0}, {0, 1, 0}), 1);
    EXPECT_DOUBLE_EQ(signed_area(loops, {0, 0, 1}), 8.0);
}

TEST(MaximalPolygons, OverlapsAndWrongWindingsAreRefused) {
    const std::vector<Polygon> twice = {rectangle(0, 0, 1, 1), rectangle(0, 0, 1, 1)};
    EXPECT_FALSE(bt::triangulate_union(pointers(twice), {0, 0, 1}));
    // Wound clockwise around the normal given: inside would lie to the right of every edge.
    const std::vector<Polygon> squares = {rectangle(0, 0, 1, 1), rectangle(1, 0, 2, 1)};
    EXPECT_FALSE(bt::triangulate_union(pointers(squares), {0, 0, -1}));
    // Overlapping without a shared edge: the outlines cross.
    const std::vector<Polygon> crossing = {rectangle(0, 0, 2, 2), rectangle(1, 1, 3, 3)};
    EXPECT_FALSE(bt::triangulate_union(pointers(crossing), {0, 0, 1}));
}

// Random quadtree subdivisions of a square, made conforming as the boundary is (T-vertices
// inserted), a random subset of the leaves kept (holes, pinched corners, islands), placed on a
// random plane in space: the union covers exactly the points the kept leaves cover, keeps their
// unmatched edges, their area, and has fewer triangles than their fans.
TEST(MaximalPolygons, UnionOfRandomConformingLeavesCoversWhatTheyCover) {
    std::mt19937 rng(7);
    size_t merged = 0, triangles = 0, fanned = 0;
    for (int trial = 0; trial < 40; ++trial) {
        std::vector<Polygon> leaves;
        std::vector<std::array<double, 3>> work = {{0.0, 0.0, 8.0}};  // x, y, size
        while (!work.empty()) {
            const auto [x, y, size] = work.back();
            work.pop_back();
            if (size > 0.5 && std::uniform_real_distribution<>(0, 1)(rng) < 0.6) {
                const double h = size / 2;
                for (const auto& [dx, dy] : {std::pair{0.0, 0.0}, {h, 0.0}, {0.0, h}, {h, h}}) {
                    work.push_back({x + dx, y + dy, h});
                }
            } else {
                leaves.push_back(rectangle(x, y, x + size, y + size));
            }
        }
        std::vector<Polygon*> all;
        for (Polygon& p : leaves) {
            all.push_back(&p);
        }
        bt::make_conforming(all, 1e-9);
        std::vector<Polygon> kept;
        for (const Polygon& p : leaves) {
            if (std::uniform_real_distribution<>(0, 1)(rng) < 0.7) {
                kept.push_back(p);
            }
        }
        if (kept.size() < 2) {
            continue;
        }
        // Onto a random plane: rotated, then moved. Coordinates stay exact per shared vertex
        // (the same input gives the same output), which is all conforming needs.
        const dvec3 axis = glm::normalize(dvec3(std::normal_distribution<>()(rng),
                                                std::normal_distribution<>()(rng),
                                                std::normal_distribution<>()(rng)));
        const glm::dmat4 place =
            glm::translate(glm::dmat4(1.0), dvec3(3.0, -2.0, 5.0)) *
            glm::rotate(glm::dmat4(1.0), std::uniform_real_distribution<>(0, 6.28)(rng), axis);
        for (Polygon& p : kept) {
            for (dvec3& v : p.vertices) {
                v = dvec3(place * glm::dvec4(v, 1.0));
            }
        }
        const dvec3 normal = glm::normalize(dvec3(place * glm::dvec4(0, 0, 1, 0)));
        const dvec3 u = glm::normalize(dvec3(place * glm::dvec4(1, 0, 0, 0)));
        const dvec3 v = glm::cross(normal, u);
        const auto t = bt::triangulate_union(pointers(kept), normal);
        ASSERT_TRUE(t) << "trial " << trial;
        ++merged;
        const auto input = loops_of(kept), output = loops_of(*t);
        EXPECT_EQ(unmatched(output), unmatched(input)) << "trial " << trial;
        EXPECT_NEAR(signed_area(output, normal), signed_area(input, normal), 1e-9)
            << "trial " << trial;
        // Grid points off every edge (the leaves' corners lie on multiples of 1/64).
        for (double gx = 1.0 / 256; gx < 8.0; gx += 8.0 / 61) {
            for (double gy = 1.0 / 256; gy < 8.0; gy += 8.0 / 67) {
                const dvec3 p = dvec3(place * glm::dvec4(gx, gy, 0.0, 1.0));
                ASSERT_EQ(coverage(output, p, u, v), coverage(input, p, u, v))
                    << "trial " << trial << " at " << gx << ", " << gy;
            }
        }
        triangles += t->triangles.size();
        for (const Polygon& p : kept) {
            fanned += bt::has_collinear_vertex(p) ? p.size() : p.size() - 2;
        }
    }
    EXPECT_GT(merged, 20u);
    EXPECT_LT(triangles, fanned);
    std::printf("maximal polygons: %zu unions, %zu triangles where the fans have %zu\n", merged,
                triangles, fanned);
}

}  // namespace
}  // namespace sl::test
