// Beam-tree speed (issue targets, one core): build time against the number of light-facing
// outer-volume polygons (multiple:N, hulls reduced to 16 planes), and the time to partition 100
// view-aligned planes. Bounding volumes are computed outside the timed region: they are cached
// per mesh and do not change while a light moves.

#include <benchmark/benchmark.h>

#include <glm/geometric.hpp>

#include "beamtree/beam_tree.h"
#include "beamtree/boundary.h"
#include "beamtree/regions.h"
#include "scenes/scene_file.h"

namespace sl::bt {
namespace {

struct Prepared {
    Scene scene;
    std::vector<ObjectVolumes> volumes;
};

Prepared prepare(int objects) {
    Prepared p{load_scene("multiple:" + std::to_string(objects), SceneSearchPaths::defaults()), {}};
    VolumeLibrary library({.max_outer_planes = p.scene.bounds.max_outer_planes});
    p.volumes = library.build(p.scene, nullptr);
    return p;
}

void build_tree(benchmark::State& state) {
    const Prepared p = prepare(int(state.range(0)));
    for (auto _ : state) {
        const BeamTree tree(p.scene.light, p.volumes);
        benchmark::DoNotOptimize(&tree);
    }
    const BeamTreeStats stats = BeamTree(p.scene.light, p.volumes).stats();
    state.counters["polygons"] = double(stats.outer_polygons);
    state.counters["stoppers"] = double(stats.stopper_polygons);
    state.counters["nodes"] = double(stats.nodes);
    state.counters["depth"] = double(stats.max_depth);
}
// About 10, 100, 1k, 10k and 100k light-facing outer polygons.
BENCHMARK(build_tree)
    ->Arg(2)
    ->Arg(16)
    ->Arg(165)
    ->Arg(1650)
    ->Arg(16500)
    ->Unit(benchmark::kMillisecond);

// Exact occluders: the real scenes with every object as its triangles (coplanar neighbours joined
// into convex faces), each an occluder and a stopper at once; the time per light-facing face
// offered is the figure to read, beside the scene's triangles.
void build_tree_exact(benchmark::State& state, const char* name) {
    Scene scene = load_scene(name, SceneSearchPaths::defaults());
    scene.bounds.occluders = Occluders::triangles;
    VolumeLibrary library(scene.bounds);
    const std::vector<ObjectVolumes> volumes = library.build(scene, nullptr);
    for (auto _ : state) {
        const BeamTree tree(scene.light, volumes);
        benchmark::DoNotOptimize(&tree);
    }
    const BeamTreeStats stats = BeamTree(scene.light, volumes).stats();
    size_t triangles = 0;
    for (const ObjectVolumes& v : volumes) {
        triangles += v.mesh_triangles;
    }
    state.counters["triangles"] = double(triangles);
    // Every light-facing face the tree was offered: inserted, or left out as hidden.
    state.counters["polygons"] = double(stats.exact_polygons + stats.hidden_polygons);
    state.counters["hidden"] = double(stats.hidden_polygons);
    state.counters["nodes"] = double(stats.nodes);
    state.counters["depth"] = double(stats.max_depth);
}
BENCHMARK_CAPTURE(build_tree_exact, arena, "arena")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(build_tree_exact, house, "house")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(build_tree_exact, engine, "engine")->Unit(benchmark::kMillisecond);

// A sun's tree for one camera: the light scene's first light, its tree over the part of its box
// the scene's camera sees at 640x360 (scenes/view_window.h), as the region methods build it
// every frame the sun or the camera moves; the volumes are built before the timing.
void build_tree_sun(benchmark::State& state, const char* name) {
    const Scene scene = load_scene(name, SceneSearchPaths::defaults()).for_light(0);
    VolumeLibrary library(scene.bounds);
    const std::vector<ObjectVolumes> volumes = library.build(scene, nullptr);
    const std::optional<ViewWindow> window =
        view_window(scene.light, scene.camera, 640.0f / 360.0f);
    for (auto _ : state) {
        const BeamTree tree(scene.light, volumes, TreeBuild{}, window);
        benchmark::DoNotOptimize(&tree);
    }
    const BeamTreeStats stats = BeamTree(scene.light, volumes, TreeBuild{}, window).stats();
    state.counters["polygons"] = double(stats.exact_polygons + stats.hidden_polygons);
    state.counters["hidden"] = double(stats.hidden_polygons);
    state.counters["nodes"] = double(stats.nodes);
}
BENCHMARK_CAPTURE(build_tree_sun, house_morning, "house-morning")->Unit(benchmark::kMillisecond);

void extract_regions_bench(benchmark::State& state) {
    const Prepared p = prepare(int(state.range(0)));
    const BeamTree tree(p.scene.light, p.volumes);
    size_t faces = 0;
    for (auto _ : state) {
        const Regions regions = extract_regions(tree);
        faces = regions.face_count(Region::lit) + regions.face_count(Region::uncertain) +
                regions.face_count(Region::unlit);
        benchmark::DoNotOptimize(faces);
    }
    state.counters["faces"] = double(faces);
}
BENCHMARK(extract_regions_bench)->Arg(16)->Arg(165)->Unit(benchmark::kMillisecond);

// The GPU meshes of the lit and uncertain regions: welding, T-vertex insertion and fans
// (Regions::mesh, beamtree/conforming.h), once per tree in `beamtree` and the hybrids.
void region_meshes_bench(benchmark::State& state) {
    const Prepared p = prepare(int(state.range(0)));
    const Regions regions = extract_regions(BeamTree(p.scene.light, p.volumes));
    size_t triangles = 0;
    for (auto _ : state) {
        triangles = regions.mesh(Region::lit).triangles.size() +
                    regions.mesh(Region::uncertain).triangles.size();
        benchmark::DoNotOptimize(triangles);
    }
    state.counters["triangles"] = double(triangles);
}
BENCHMARK(region_meshes_bench)->Arg(16)->Arg(165)->Unit(benchmark::kMillisecond);

// The regions as surfaces: the closed boundary meshes of the lit and uncertain unions
// (beamtree/boundary.h: grouping by plane, cancellation, conforming, crack closing), what
// `beamtree` and the hybrids draw by default instead of the meshes above; second argument 0: the
// faces on each plane merged into maximal polygons (the default), 1: each face fanned.
void boundary_meshes_bench(benchmark::State& state) {
    const Prepared p = prepare(int(state.range(0)));
    const BeamTree tree(p.scene.light, p.volumes);
    const Regions regions = extract_regions(tree);
    const BoundaryShape shape =
        state.range(1) == 0 ? BoundaryShape::maximal : BoundaryShape::fragments;
    size_t triangles = 0;
    for (auto _ : state) {
        triangles =
            boundary_mesh(tree, regions, Region::lit, nullptr, shape).triangles.size() +
            boundary_mesh(tree, regions, Region::uncertain, nullptr, shape).triangles.size();
        benchmark::DoNotOptimize(triangles);
    }
    state.counters["triangles"] = double(triangles);
}
BENCHMARK(boundary_meshes_bench)
    ->Args({16, 0})
    ->Args({16, 1})
    ->Args({165, 0})
    ->Args({165, 1})
    ->Unit(benchmark::kMillisecond);

// 100 planes facing the camera, spaced evenly through the influence volume's depth range as
// the sampling-plane methods will place them, partitioned into lit / uncertain / unlit.
void partition_view_planes(benchmark::State& state) {
    const Prepared p = prepare(int(state.range(0)));
    const BeamTree tree(p.scene.light, p.volumes);
    const Camera& camera = p.scene.camera;
    const glm::dvec3 eye(camera.position),
        forward = glm::normalize(glm::dvec3(camera.target) - eye);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(camera.up)));
    const glm::dvec3 up = glm::cross(right, forward);
    std::vector<Polygon> planes;
    for (int i = 0; i < 100; ++i) {
        const double depth = 2.0 + 28.0 * i / 99.0;
        const double half = depth * 0.6;
        const glm::dvec3 c = eye + depth * forward;
        planes.emplace_back(
            std::vector<glm::dvec3>{c - half * right - half * up, c + half * right - half * up,
                                    c + half * right + half * up, c - half * right + half * up});
    }
    size_t pieces = 0;
    for (auto _ : state) {
        pieces = 0;
        for (const Polygon& plane : planes) {
            const BeamTree::Partition parts = tree.partition(plane);
            pieces += parts.lit.size() + parts.uncertain.size() + parts.unlit.size();
        }
        benchmark::DoNotOptimize(pieces);
    }
    state.counters["pieces"] = double(pieces);
    state.counters["polygons"] = double(tree.stats().outer_polygons);
}
BENCHMARK(partition_view_planes)->Arg(16)->Arg(165)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sl::bt

BENCHMARK_MAIN();
