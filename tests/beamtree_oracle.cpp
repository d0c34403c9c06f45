#include "tests/beamtree_oracle.h"

#include "scenes/scene_sections.h"

#include <gtest/gtest.h>

#include <map>

#include <glm/mat4x4.hpp>

namespace sl::test {

void add_volumes(const std::vector<bt::ObjectVolumes>& volumes, const Scene& scene,
                 Oracles& oracles) {
    for (const bt::ObjectVolumes& v : volumes) {
        // An exact occluder is both: crossing it puts a point in its shadow, for certain.
        for (const bt::Polygon& triangle : v.triangles) {
            oracles.outer.add(triangle);
            oracles.inner.add(triangle);
        }
        if (v.triangles.empty()) {
            for (const bt::Polygon& face : v.outer.faces)
                oracles.outer.add(face);
        }
        for (const bt::ConvexVolume& inner : v.inner) {
            for (const bt::Polygon& face : inner.faces)
                oracles.inner.add(face);
        }
        const Object& object = scene.objects[size_t(v.object)];
        std::vector<dvec3> world;
        for (const glm::vec3& p : object.mesh->positions) {
            world.emplace_back(glm::dmat4(object.transform) * glm::dvec4(dvec3(p), 1.0));
        }
        oracles.meshes.add(world, object.mesh->triangles);
    }
    oracles.outer.commit();
    oracles.inner.commit();
    oracles.meshes.commit();
}

PointCheck check_point(const bt::BeamTree& tree, const Oracles& oracles, const dvec3& light,
                       const dvec3& p) {
    PointCheck check;
    check.region = tree.classify(p, &check.margin);
    if (check.margin < 10.0 * tree.epsilon()) {
        return check;
    }
    check.decided = true;
    bool inside = true;
    for (const bt::Plane& plane : tree.influence_planes())
        inside &= plane.distance(p) < 0.0;
    check.expected = !inside                            ? bt::Region::unlit
                     : !oracles.outer.blocked(light, p) ? bt::Region::lit
                     : oracles.inner.blocked(light, p)  ? bt::Region::unlit
                                                        : bt::Region::uncertain;
    check.sound =
        check.region == bt::Region::uncertain ||
        (check.region == bt::Region::lit) == !(inside ? oracles.meshes.blocked(light, p) : true);
    return check;
}

dvec3 light_for(const SpotLight& light, const dvec3& p) {
    if (!light.parallel()) {
        return dvec3(light.position);
    }
    const double away = 4.0 * (double(light.far) + 2.0 * double(light.half_width));
    return p - away * glm::normalize(dvec3(light.direction()));
}

int check_random_scenes(Shapes kinds, BoundsSettings options, int seeds, LightKind kind) {
    bt::VolumeLibrary library(options);
    library.set_caching(false);  // random meshes: nothing to share with the disk
    size_t compared = 0, counts[3] = {0, 0, 0};
    int failures = 0, light_in_a_hull = 0;
    const int stride = kSanitizedSeedStride;
    for (int seed = 1; seed <= seeds; seed += stride) {
        RandomScene random = random_scene(seed, library, kinds);
        random.scene.bounds = options;  // its occluders too
        const Scene& scene = random.scene;
        // Tightness: no piece, grown as it is for the tree, reaches more than 10^-3 of the
        // mesh's size outside the mesh's own hull.
        for (const Object& object : scene.objects) {
            const bt::LocalVolumes& local = library.local(object.mesh);
            const double extent = glm::length(object.mesh->bounds().extent());
            for (const bt::LocalPiece& piece : local.pieces) {
                for (const bt::Polygon& face : piece.outer.faces) {
                    for (const dvec3& v : face.vertices) {
                        for (const bt::Plane& plane : local.outer.planes) {
                            EXPECT_LE(plane.distance(v), 1e-3 * extent)
                                << "scene " << seed << ": a piece of " << object.name;
                        }
                    }
                }
            }
        }
        for (const Object& object : scene.objects) {
            if (library.local(object.mesh)
                    .outer.transformed(glm::dmat4(object.transform))
                    .contains(dvec3(scene.light.position), 1e-3)) {
                ++light_in_a_hull;
                break;
            }
        }
        const std::vector<bt::ObjectVolumes> volumes = library.build(scene, nullptr);
        Oracles oracles;
        add_volumes(volumes, scene, oracles);
        std::mt19937 rng(1000 + seed);
        auto on_point = [&](const dvec3& p, const PointCheck& check) {
            const bt::Region region = check.region, expected = check.expected;
            const bool sound = check.sound;
            ++compared;
            ++counts[size_t(region)];
            if ((region != expected || !sound) && ++failures <= 10) {
                ADD_FAILURE() << "scene " << seed << " (kinds " << random.kinds << ") point ("
                              << p.x << ", " << p.y << ", " << p.z << "): tree "
                              << bt::to_string(region) << ", ray cast " << bt::to_string(expected)
                              << (sound ? "" : ", unsound against the meshes") << ", margin "
                              << check.margin;
            }
        };
        // The scene's spot light, or a point light in its place: each of its six faces' trees
        // (Scene::spot_lights), with the points split among them.
        Scene lit = scene;
        if (kind == LightKind::point) {
            PointLight point;
            point.position = scene.light.position;
            point.near = scene.light.near;
            point.far = scene.light.far;
            lit.set_lights({point});
        } else if (kind == LightKind::directional) {
            DirectionalLight sun;
            sun.direction = scene.light.direction();
            sun.entry = glm::vec3(std::numeric_limits<float>::quiet_NaN());  // the default
            resolve_directional_light(sun, scene, "random scene");
            lit.set_lights({sun});
        }
        const std::vector<SpotLight> lights = lit.spot_lights();
        const int points = 10000 / int(lights.size());
        for (const SpotLight& light : lights) {
            const bt::BeamTree tree(light, volumes);
            Scene view = scene;
            view.light = light;
            for_each_decided_point(tree, oracles, light, rng, points, on_point);
            for_each_decided_point_behind_a_surface(tree, oracles, view, rng, points, on_point);
            const bt::Regions regions = bt::extract_regions(tree);
            const double total = regions.volume[0] + regions.volume[1] + regions.volume[2];
            EXPECT_NEAR(total / regions.influence_volume, 1.0, 1e-6)
                << "scene " << seed << " (kinds " << random.kinds << "): lit " << regions.volume[0]
                << " uncertain " << regions.volume[1] << " unlit " << regions.volume[2];
        }
    }
    const size_t checked = size_t((seeds + stride - 1) / stride);
    EXPECT_EQ(failures, 0) << "of " << compared << " points";
    EXPECT_GT(compared, checked * 15000u);
    for (const bt::Region region : {bt::Region::lit, bt::Region::uncertain, bt::Region::unlit}) {
        const size_t count = counts[size_t(region)];
        if (region == bt::Region::uncertain && options.occluders == Occluders::triangles) {
            EXPECT_EQ(count, 0u) << "exact occluders leave no decided point uncertain";
        } else if (region == bt::Region::uncertain && options.occluders == Occluders::automatic &&
                   options.min_inner_fill > 0.0) {
            continue;  // the loose objects' triangles too: a few scenes may have none uncertain
        } else {
            EXPECT_GT(count, checked * 100u) << "every region type must be exercised";
        }
    }
    return light_in_a_hull;
}

size_t unmatched_edges(const bt::RegionMesh& mesh) {
    using Key = std::array<float, 6>;
    std::map<Key, int> balance;  // +1 per edge p→q, -1 per edge q→p, keyed by the (p, q) with p < q
    for (const glm::uvec3& t : mesh.triangles) {
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 p = mesh.positions[t[k]], q = mesh.positions[t[(k + 1) % 3]];
            const Key forward{p.x, p.y, p.z, q.x, q.y, q.z}, backward{q.x, q.y, q.z, p.x, p.y, p.z};
            if (forward < backward) {
                ++balance[forward];
            } else if (backward < forward) {
                --balance[backward];
            }
        }
    }
    size_t unmatched = 0;
    for (const auto& [edge, count] : balance) {
        unmatched += size_t(std::abs(count));
    }
    return unmatched;
}

}  // namespace sl::test
