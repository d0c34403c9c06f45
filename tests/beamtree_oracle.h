#pragma once
// The beam tree against independent oracles (tests/beamtree_*_test.cpp): Embree ray casts through
// the bounding volumes (what the tree must agree with) and through the true meshes (what it must
// be sound against), points drawn around the light's cone and in the meshes' shadows, and the
// random-scene check that runs them all.

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "beamtree/beam_tree.h"
#include "beamtree/regions.h"
#include "tests/embree_oracle.h"
#include "tests/random_scenes.h"

namespace sl::test {

struct Oracles {
    EmbreeOccluder outer, inner, meshes;
};

// The scene's volumes and meshes into the oracles (committed).
void add_volumes(const std::vector<bt::ObjectVolumes>& volumes, const Scene& scene,
                 Oracles& oracles);

// One point: the tree's region, what ray casts through the volumes say (expected), and whether
// the answer is sound against the meshes (lit: no mesh between it and the light; unlit: one).
// Points within 10ε of a plane the answer depends on are not decided.
struct PointCheck {
    bool decided = false;
    bt::Region region = bt::Region::unlit, expected = bt::Region::unlit;
    bool sound = true;
    double margin = 0.0;  // distance to the nearest plane the answer depended on
};

PointCheck check_point(const bt::BeamTree& tree, const Oracles& oracles, const dvec3& light,
                       const dvec3& p);

// Where the ray casts for p start: the light's position, or for parallel beams (a directional
// light) a point back along p's beam, beyond the scene (four times the box's size away).
dvec3 light_for(const SpotLight& light, const dvec3& p);

// `count` random points around the light's cone, each checked; `on_point(p, check)` for those
// decided.
template <typename OnPoint>
void for_each_decided_point(const bt::BeamTree& tree, const Oracles& oracles,
                            const SpotLight& light, std::mt19937& rng, int count,
                            OnPoint on_point) {
    for (int i = 0; i < count; ++i) {
        const dvec3 p = random_point(rng, light);
        const PointCheck check = check_point(tree, oracles, light_for(light, p), p);
        if (check.decided) {
            on_point(p, check);
        }
    }
}

// Points in the shadows the meshes cast, where a lit answer is unsound: `count` random points
// on the scene's triangles (area-weighted), each moved away from the light by 10^-3 to 0.3 of
// the distance between them. Checked and passed to `on_point` as above.
template <typename OnPoint>
void for_each_decided_point_behind_a_surface(const bt::BeamTree& tree, const Oracles& oracles,
                                             const Scene& scene, std::mt19937& rng, int count,
                                             OnPoint on_point) {
    std::vector<std::array<dvec3, 3>> triangles;
    std::vector<double> cumulative;
    for (const Object& object : scene.objects) {
        const glm::dmat4 m(object.transform);
        for (const glm::uvec3& t : object.mesh->triangles) {
            std::array<dvec3, 3> w;
            for (int k = 0; k < 3; ++k) {
                w[size_t(k)] = dvec3(m * glm::dvec4(dvec3(object.mesh->positions[t[k]]), 1.0));
            }
            const double a = 0.5 * glm::length(glm::cross(w[1] - w[0], w[2] - w[0]));
            cumulative.push_back((cumulative.empty() ? 0.0 : cumulative.back()) + a);
            triangles.push_back(w);
        }
    }
    if (triangles.empty() || !(cumulative.back() > 0.0)) {
        return;
    }
    for (int i = 0; i < count; ++i) {
        const double pick = uniform(rng, 0.0, cumulative.back());
        const size_t k = size_t(std::lower_bound(cumulative.begin(), cumulative.end(), pick) -
                                cumulative.begin());
        const auto& w = triangles[std::min(k, triangles.size() - 1)];
        double r1 = uniform(rng, 0, 1), r2 = uniform(rng, 0, 1);
        if (r1 + r2 > 1.0) {
            r1 = 1.0 - r1;
            r2 = 1.0 - r2;
        }
        const dvec3 surface = w[0] + r1 * (w[1] - w[0]) + r2 * (w[2] - w[0]);
        const dvec3 light = light_for(scene.light, surface);
        // A triangle edge-on to the light (its plane through L) shadows nothing: the points
        // behind it would lie on its plane, where a ray cast decides by round-off.
        const dvec3 normal = glm::cross(w[1] - w[0], w[2] - w[0]);
        if (std::abs(glm::dot(glm::normalize(normal), glm::normalize(surface - light))) < 1e-3) {
            continue;
        }
        const dvec3 p =
            surface + std::exp(uniform(rng, std::log(1e-3), std::log(0.3))) * (surface - light);
        const PointCheck check = check_point(tree, oracles, light, p);
        if (check.decided) {
            on_point(p, check);
        }
    }
}

// Under ASan/UBSan (16 to 40 times slower than Release) an oracle checks every 8th seed (1, 9,
// 17, ...): the same code paths on seeds spread over the same range, within the sanitized
// suite's timeout. The Release suite (what CI runs) checks every seed.
#ifdef SHAFTLAB_SANITIZED
inline constexpr int kSanitizedSeedStride = 8;
#else
inline constexpr int kSanitizedSeedStride = 1;
#endif

// On `seeds` random scenes (seeds 1 to `seeds`, strided as above), 10^4 points around the
// light's cone and 10^4 in the shadows of the meshes each, away from every plane the answer
// depends on (10ε): classify() equals the ray-cast answer through the bounding volumes (agreement),
// lit points see the light past every true mesh and unlit points do not (soundness), and the
// regions tile the influence volume (conservation); and no convex piece reaches outside its mesh's
// hull by more than 10^-3 of its size (tightness). With triangles as occluders
// (options.occluders) no decided point is uncertain. With LightKind::point, a point light at the
// scene's light (its range) instead, each of its six pyramidal faces' trees checked (the points
// split among them); with LightKind::directional, a sun along the spot's axis whose box covers
// the scene (its default region and entry plane). Returns how many scenes had the light inside the
// hull of a whole object (which only its pieces allow).
enum class LightKind { spot, point, directional };
int check_random_scenes(Shapes kinds, BoundsSettings options, int seeds,
                        LightKind light = LightKind::spot);

// The directed edges of a float triangle mesh that no triangle meets in the opposite direction
// (zero-length edges left out). The faces of a region's pieces close up, so in a crack-free mesh
// every edge is met from both sides; a T-junction leaves the long edge and the short ones each
// without a partner.
size_t unmatched_edges(const bt::RegionMesh& mesh);

}  // namespace sl::test
