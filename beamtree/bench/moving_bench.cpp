// The per-frame CPU work of the region methods on moving scenes (issue "moving scenes",
// results/moving.md): one core (TBB limited to one thread; scripts/moving_bench.sh also pins the
// process with taskset). Writes Markdown to stdout.
//
//   1. A light move on toplight, parallel and multiple: the light circles 0.5 m about its place
//      over 24 frames. Per frame, the uncached path (a fresh VolumeLibrary: hulls, reduced
//      hulls and inner boxes recomputed, as build_scene_beam_tree did) against today's
//      (bt::build_frame_regions: cached volumes transformed, then tree, regions, meshes), each
//      stage timed, for what `beamtree` needs (the lit boundary) and what the hybrids need (lit
//      and uncertain boundaries and the GPU tree).
//   2. The canonical animations, every frame.
//   3. Scaling over multiple:N.
//   4. The static half: each mesh's volumes computed, and read back from the disk cache.
//   5. (`moving_bench lights [SCENE]`) A light move on the light scenes, every spot light and face
//      (only the rows whose name starts with SCENE when given, e.g. to profile one).

#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "beamtree/boundary.h"
#include "beamtree/frame_regions.h"
#include "scenes/animation.h"
#include "scenes/scene_file.h"
#include "scenes/scene_sections.h"

namespace sl::bt {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double quantile(std::vector<double> v, double q) {
    if (v.empty())
        return 0.0;
    std::sort(v.begin(), v.end());
    const double x = q * double(v.size() - 1);
    const size_t i = size_t(x);
    return i + 1 < v.size() ? v[i] + (x - double(i)) * (v[i + 1] - v[i]) : v[i];
}

// Per-stage samples over frames.
struct StageSamples {
    std::vector<RegionStageTimes> frames;
    std::vector<double> column(double RegionStageTimes::*stage) const {
        std::vector<double> v;
        for (const RegionStageTimes& t : frames)
            v.push_back(t.*stage);
        return v;
    }
    std::vector<double> totals() const {
        std::vector<double> v;
        for (const RegionStageTimes& t : frames)
            v.push_back(t.total());
        return v;
    }
};

const RegionRequest kBeamtree{.lit = true};
const RegionRequest kHybrids{.lit = true, .uncertain = true, .gpu_tree = true};
// The walk route (analytic/gpu_tree.h): every region method needs the tree and nothing else.
const RegionRequest kWalk{.gpu_tree = true};
// The walk route as the methods ask for it at the main job's 640×360: a sun's tree fitted to the
// camera's view (RegionRequest::view_aspect).
const RegionRequest kWalkInView{.gpu_tree = true, .view_aspect = 640.0f / 360.0f};

Scene light_moved(const Scene& scene, int frame, int frames) {
    Scene s = scene;
    const double a = 2.0 * M_PI * frame / frames;
    s.light.position +=
        glm::vec3(0.5 * std::cos(a), 0.0, 0.5 * std::sin(a)) - glm::vec3(0.5f, 0.0f, 0.0f);
    return s;
}

StageSamples play(const std::vector<Scene>& states, const RegionRequest& request) {
    StageSamples samples;
    build_frame_regions(states.front(), request);  // the static half, before timing
    for (const Scene& s : states) {
        samples.frames.push_back(build_frame_regions(s, request).ms);
    }
    return samples;
}

// The uncached per-frame path: volumes from a fresh library (nothing cached), then the same
// stages.
double first_round_frame(const Scene& scene, const RegionRequest& request) {
    const Clock::time_point start = Clock::now();
    VolumeLibrary library(scene.bounds);
    library.set_caching(false);
    const BeamTree tree(scene.light, library.build(scene, nullptr));
    const Regions regions = extract_regions(tree);
    if (request.lit)
        boundary_mesh(tree, regions, Region::lit);
    if (request.uncertain)
        boundary_mesh(tree, regions, Region::uncertain);
    if (request.gpu_tree)
        tree.gpu_tree();
    return ms_since(start);
}

std::string stage_cells(const StageSamples& s) {
    std::string row;
    for (double RegionStageTimes::*stage :
         {&RegionStageTimes::volumes, &RegionStageTimes::tree, &RegionStageTimes::regions,
          &RegionStageTimes::lit, &RegionStageTimes::uncertain, &RegionStageTimes::gpu_tree}) {
        row += fmt::format(" {:.2f} |", quantile(s.column(stage), 0.5));
    }
    const std::vector<double> totals = s.totals();
    return row +
           fmt::format(" **{:.2f}** | {:.2f} |", quantile(totals, 0.5), quantile(totals, 0.95));
}

constexpr const char* kStageHeader =
    " volumes | tree | regions | lit mesh | uncertain mesh | GPU tree | total (median) | p95 |";
constexpr const char* kStageRule = "---:|---:|---:|---:|---:|---:|---:|---:|";

constexpr int kFrames = 24;  // of a light move

// 1. A light move on each still scene: the uncached path against the cached one, per route.
void light_move_table(const std::vector<std::string>& stills, const SceneSearchPaths& paths,
                      bool real) {
    constexpr double kBudget = 2.0;
    fmt::print("## A light move on the {} scenes\n\n", real ? "real" : "canonical");
    fmt::print(
        "The light circles 0.5 m about its place over {} frames; milliseconds per frame, one "
        "core, medians over the frames (p95 beside the total). *First round*: what a light move "
        "cost before the static/dynamic split (a fresh `VolumeLibrary` each frame, median of 3 "
        "frames). Budget {} ms.\n\n",
        kFrames, kBudget);
    fmt::print("| scene | needs | first round | {} budget |\n|---|---|---:|{}---|\n", kStageHeader,
               kStageRule);
    for (const std::string& name : stills) {
        const Scene scene = load_scene(name, paths);
        std::vector<Scene> states;
        for (int k = 0; k < kFrames; ++k)
            states.push_back(light_moved(scene, k, kFrames));
        for (const auto& [label, request] :
             {std::pair{"mesh route: beamtree (lit)", kBeamtree},
              std::pair{"mesh route: hybrids (lit, uncertain, tree)", kHybrids},
              std::pair{"walk route: all four (tree)", kWalk}}) {
            std::vector<double> before;
            for (int k = 0; k < 3; ++k)
                before.push_back(first_round_frame(states[size_t(k)], request));
            const StageSamples after = play(states, request);
            const double total = quantile(after.totals(), 0.5);
            fmt::print("| {} | {} | {:.1f} |{} {} |\n", name, label, quantile(before, 0.5),
                       stage_cells(after),
                       total <= kBudget ? "met" : fmt::format("{:.1f}x over", total / kBudget));
        }
        std::fflush(stdout);
    }
}

// 2. Every frame of each animation, per route.
void animations_table(const std::vector<std::string>& animations, const SceneSearchPaths& paths,
                      bool real) {
    fmt::print("\n## The {} animations, every frame\n\n", real ? "real" : "canonical");
    fmt::print("| scene | route | frames | {} worst |\n|---|---|---:|{}---:|\n", kStageHeader,
               kStageRule);
    for (const std::string& name : animations) {
        const Scene scene = load_scene(name, paths);
        std::vector<Scene> states;
        for (int k = 0; k < scene.animation->frame_count(); ++k)
            states.push_back(scene_at(scene, scene.animation->frame_time(k)));
        for (const auto& [route, request] :
             {std::pair{"mesh (hybrids)", kHybrids}, std::pair{"walk", kWalk}}) {
            const StageSamples s = play(states, request);
            const std::vector<double> totals = s.totals();
            fmt::print("| {} | {} | {} |{} {:.2f} |\n", name, route, states.size(), stage_cells(s),
                       *std::max_element(totals.begin(), totals.end()));
            std::fflush(stdout);
        }
    }
}

// 3. A light move on multiple:N for growing N, with the fitted exponent of the total.
void scaling_table(const char* route, const RegionRequest& request, const SceneSearchPaths& paths) {
    fmt::print("\n## Scaling: a light move on multiple:N ({})\n\n", route);
    fmt::print("| N | triangles | light-facing polygons | {}\n|---:|---:|---:|{}\n", kStageHeader,
               kStageRule);
    std::vector<std::pair<double, double>> fit;
    for (const int n : {4, 8, 16, 32, 64, 128, 256}) {
        const Scene scene = load_scene(fmt::format("multiple:{}", n), paths);
        std::vector<Scene> states;
        const int frames = request.lit ? (n <= 64 ? 12 : 6) : 24;
        for (int k = 0; k < frames; ++k)
            states.push_back(light_moved(scene, k, frames));
        const StageSamples s = play(states, request);
        const BeamTreeStats stats = build_frame_regions(scene, request).tree->stats();
        fit.emplace_back(std::log(double(n)), std::log(quantile(s.totals(), 0.5)));
        fmt::print("| {} | {} | {} |{}\n", n, scene.triangle_count(),
                   stats.outer_polygons + stats.stopper_polygons + stats.exact_polygons,
                   stage_cells(s));
        std::fflush(stdout);
    }
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (const auto& [x, y] : fit) {
        sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    const double k = (double(fit.size()) * sxy - sx * sy) / (double(fit.size()) * sxx - sx * sx);
    fmt::print("\nFitted exponent (total ∝ N^k): **k = {:.2f}**.\n", k);
}

// 4. Each still scene's local volumes computed from scratch, and read back from the disk.
void static_half_table(const std::vector<std::string>& stills, const SceneSearchPaths& paths) {
    fmt::print("\n## The static half, once per mesh\n\n");
    fmt::print(
        "Each scene's local volumes (hulls, reduced hulls, inner boxes and their verification) "
        "computed from scratch, and read back from the disk cache by a fresh library, one "
        "core.\n\n| scene | meshes | computed ms | from disk ms |\n|---|---:|---:|---:|\n");
    for (const std::string& name : stills) {
        const Scene scene = load_scene(name, paths);
        const BoundsSettings options = scene.bounds;
        Clock::time_point start = Clock::now();
        VolumeLibrary cold(options);
        cold.set_caching(false);
        cold.build(scene, nullptr);
        const double computed = ms_since(start);
        VolumeLibrary warm_up(options);
        warm_up.build(scene, nullptr);  // make sure the disk holds them
        // A fresh process finds nothing in memory: time the disk path alone.
        VolumeLibrary::forget_process_volumes();
        start = Clock::now();
        size_t meshes = 0;
        {
            VolumeLibrary fresh(options);
            for (const Object& o : scene.objects) {
                fresh.local(o.mesh);
            }
            meshes = fresh.stats().memory + fresh.stats().disk + fresh.stats().computed;
        }
        const double disk = ms_since(start);
        fmt::print("| {} | {} | {:.1f} | {:.2f} |\n", name, meshes, computed, disk);
    }
}

// 5. A light move on the light scenes: every light circles 0.5 m about its place, and
//    each of the scene's spot lights (a point light's six faces) gets its tree on the walk route;
//    per frame, the sum over them.
void lights_move_table(const SceneSearchPaths& paths, const std::string& only) {
    fmt::print("## A light move on the light scenes, walk route\n\n");
    fmt::print(
        "Every light circles 0.5 m about its place over {} frames (a sun swings its direction "
        "5° about the vertical and back; an animated scene plays its own animation over the frames "
        "instead); per frame, each spot light (a point light: its six "
        "faces) gets its tree and GPU tree (the walk route: what all four region methods need); "
        "milliseconds per frame summed over the lights, one core, medians over the frames (p95 "
        "beside); and the wall time of the same frame with the lights on parallel tasks over every "
        "core, as a method's update runs them. A sun's tree covers the part of its box the camera "
        "sees at 640×360, as the methods build it (scenes/view_window.h); *whole box*: the total "
        "of the same frames with the tree over the whole box. Issue 47's budget: 4 ms for a point "
        "light (six faces), 2 ms per spot light or sun.\n\n",
        kFrames);
    fmt::print(
        "| scene | lights | spot lights | volumes | tree | GPU tree | total (median) | p95 | per "
        "spot light | {} cores, wall | whole box | budget "
        "|\n|---|---:|---:|---:|---:|---:|---:|---:|"
        "---:|---:|---:|---|\n",
        tbb::info::default_concurrency());
    // The light scenes, and the canonical scenes with their spot light replaced by a sun along
    // its axis over the scene's default region (the sun's budget is for the canonical scenes).
    std::vector<std::pair<std::string, Scene>> scenes;
    for (const std::string& name : light_scene_names()) {
        if (name.starts_with(only)) {
            scenes.emplace_back(name, load_scene(name, paths));
        }
    }
    for (const std::string& name : canonical_scene_names()) {
        if (!(name + " (sun)").starts_with(only)) {
            continue;
        }
        Scene scene = load_scene(name, paths);
        DirectionalLight sun;
        sun.direction = scene.light.direction();
        sun.irradiance = scene.light.intensity / (scene.light.far * scene.light.far);
        sun.entry = glm::vec3(std::numeric_limits<float>::quiet_NaN());
        resolve_directional_light(sun, scene, name);
        scene.set_lights({sun});
        scenes.emplace_back(name + " (sun)", std::move(scene));
    }
    for (const auto& [name, scene] : scenes) {
        std::vector<Scene> states;
        for (int k = 0; k < kFrames; ++k) {
            if (scene.animation) {  // an animated light scene plays its own animation
                const Animation& animation = *scene.animation;
                states.push_back(scene_at(
                    scene, animation.start + (animation.end - animation.start) * k / kFrames));
                continue;
            }
            const double a = 2.0 * M_PI * k / kFrames;
            const glm::vec3 offset =
                glm::vec3(0.5 * std::cos(a), 0.0, 0.5 * std::sin(a)) - glm::vec3(0.5f, 0.0f, 0.0f);
            std::vector<LightSource> sources = scene.light_sources();
            for (LightSource& source : sources) {
                if (auto* sun = std::get_if<DirectionalLight>(&source)) {
                    // A sun swings its direction 5° about the vertical and back.
                    const float turn = glm::radians(5.0f) * float(std::sin(a));
                    sun->direction =
                        glm::vec3(glm::rotate(glm::mat4(1.0f), turn, glm::vec3(0, 1, 0)) *
                                  glm::vec4(sun->direction, 0.0f));
                    continue;
                }
                if (auto* spot = std::get_if<SpotLight>(&source)) {
                    spot->position += offset;
                } else {
                    std::get<PointLight>(source).position += offset;
                }
            }
            Scene moved = scene;
            moved.set_lights(std::move(sources));
            states.push_back(std::move(moved));
        }
        const size_t spots = scene.spot_lights().size();
        for (size_t i = 0; i < spots; ++i) {
            build_frame_regions(scene.for_light(i), kWalk);  // the static half, before timing
        }
        std::vector<double> volumes, tree, gpu_tree, totals, walls, whole;
        {
            const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
            for (const Scene& state : states) {
                RegionStageTimes sum;
                for (size_t i = 0; i < spots; ++i) {
                    const RegionStageTimes t =
                        build_frame_regions(state.for_light(i), kWalkInView).ms;
                    sum.volumes += t.volumes;
                    sum.tree += t.tree;
                    sum.gpu_tree += t.gpu_tree;
                    sum.regions += t.regions;
                }
                volumes.push_back(sum.volumes);
                tree.push_back(sum.tree);
                gpu_tree.push_back(sum.gpu_tree);
                totals.push_back(sum.total());
                double box = 0.0;
                for (size_t i = 0; i < spots; ++i) {
                    box += build_frame_regions(state.for_light(i), kWalk).ms.total();
                }
                whole.push_back(box);
            }
        }
        // The same work as a method's cpu_update() does it: the lights on parallel tasks over
        // every core, wall time per frame.
        for (const Scene& state : states) {
            const Clock::time_point start = Clock::now();
            tbb::parallel_for(size_t(0), spots, [&](size_t i) {
                build_frame_regions(state.for_light(i), kWalkInView);
            });
            walls.push_back(ms_since(start));
        }
        // Issue 47's budgets: 4 ms per point light (its six faces), 2 ms per spot light or sun.
        const bool point = std::holds_alternative<PointLight>(scene.light_sources().front());
        const double budget =
            point ? 4.0 * double(scene.light_sources().size()) : 2.0 * double(spots);
        const double total = quantile(totals, 0.5);
        constexpr const char* row =
            "| {} | {} | {} | {:.2f} | {:.2f} | {:.2f} | **{:.2f}** | {:.2f} | {:.2f} | {:.2f} | "
            "{:.2f} | {} |\n";
        fmt::print(row, name, scene.light_sources().size(), spots, quantile(volumes, 0.5),
                   quantile(tree, 0.5), quantile(gpu_tree, 0.5), total, quantile(totals, 0.95),
                   total / double(spots), quantile(walls, 0.5), quantile(whole, 0.5),
                   total <= budget ? fmt::format("met ({} ms)", budget)
                                   : fmt::format("{:.1f}x over {} ms", total / budget, budget));
        std::fflush(stdout);
    }
}

// real: the same tables for the real scenes (house, house-sweep; the game level arena,
// arena-sweep) instead of the canonical ones,
// without the scaling runs.
int run(bool real) {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    const SceneSearchPaths paths = SceneSearchPaths::defaults();
    const std::vector<std::string> stills =
        real ? std::vector<std::string>{"house", "arena"} : canonical_scene_names();
    const std::vector<std::string> animations =
        real ? std::vector<std::string>{"house-sweep", "arena-sweep"} : animated_scene_names();
    light_move_table(stills, paths, real);
    animations_table(animations, paths, real);
    if (!real) {
        scaling_table("mesh route, what the hybrids need", kHybrids, paths);
        scaling_table("walk route, what all four need", kWalk, paths);
    }
    static_half_table(stills, paths);
    return 0;
}

}  // namespace
}  // namespace sl::bt

int main(int argc, char** argv) {
    try {
        if (argc > 1 && std::string(argv[1]) == "lights") {
            sl::bt::lights_move_table(sl::SceneSearchPaths::defaults(), argc > 2 ? argv[2] : "");
            return 0;
        }
        return sl::bt::run(argc > 1 && std::string(argv[1]) == "real");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "moving_bench: %s\n", e.what());
        return 1;
    }
}
