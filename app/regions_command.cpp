// `shaftlab regions`: the beam tree's lit / uncertain / unlit regions of a scene, as a PLY mesh,
// a JSON summary with timings, and a picture (Nilsson figure 5.4) seen from the scene camera.

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <numeric>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "analytic/in_scattering.h"
#include "app/commands.h"
#include "beamtree/beam_tree.h"
#include "beamtree/region_picture.h"
#include "beamtree/regions.h"
#include "core/error.h"
#include "core/output_files.h"
#include "frame/renderer.h"
#include "gl/platform.h"
#include "methods/registry.h"
#include "scenes/scene_file.h"

namespace sl::app {

namespace {

using glm::dvec3;

struct RegionsArguments : CommonOptions {
    std::string classify;
    int max_planes = -1;  // -1: the scene's setting
    bool no_automatic_inner = false;
    bool no_pieces = false;
};

// The length of the eye rays (every other pixel in x and y, up to the first surface) inside the
// light's cone, by the region the tree gives it: what a hybrid marches is the uncertain share.
std::array<double, 3> eye_ray_lengths(const Scene& scene, const bt::BeamTree& tree,
                                      const std::vector<float>& depth, int width, int height) {
    const PixelUnprojector pixels(scene.camera, width, height);
    std::array<double, 3> lengths{};
    std::vector<bt::RegionInterval> intervals;
    for (int y = 0; y < height; y += 2) {
        for (int x = 0; x < width; x += 2) {
            const double ndc = 2.0 * double(depth[size_t(y) * size_t(width) + size_t(x)]) - 1.0;
            const dvec3 origin = pixels.point(x, y, -1.0);
            const dvec3 end = pixels.point(x, y, std::min(ndc, 1.0));
            const double length = glm::length(end - origin);
            if (!(length > 0.0)) {
                continue;
            }
            const analytic::EyeRay ray{origin, (end - origin) / length};
            const analytic::Interval cone = analytic::light_interval(ray, scene.light, length);
            if (cone.empty()) {
                continue;
            }
            intervals.clear();
            tree.trace(ray.origin, ray.direction, cone.begin, cone.end, intervals);
            for (const bt::RegionInterval& interval : intervals) {
                lengths[size_t(interval.region)] += interval.end - interval.begin;
            }
        }
    }
    return lengths;
}

std::vector<dvec3> read_points(const std::string& path) {
    std::ifstream in(path);
    if (!in) {
        fail("{}: cannot read points file", path);
    }
    std::vector<dvec3> points;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        if (line.find_first_not_of(" \t\r") == std::string::npos) {
            continue;
        }
        std::istringstream fields(line);
        dvec3 p;
        std::string rest;
        if (!(fields >> p.x >> p.y >> p.z) || (fields >> rest)) {
            fail("{}:{}: expected three numbers 'x y z'", path, number);
        }
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            fail("{}:{}: coordinate is not finite", path, number);
        }
        points.push_back(p);
    }
    return points;
}

int run_regions(const RegionsArguments& args) {
    int width = 0, height = 0;
    parse_size(args.size, width, height);
    const Scene scene = load_scene_at(args.scene, args.time);
    const std::vector<dvec3> points =
        args.classify.empty() ? std::vector<dvec3>() : read_points(args.classify);

    auto start = Clock::now();
    const int max_planes = args.max_planes >= 0 ? args.max_planes : scene.bounds.max_outer_planes;
    bt::VolumeLibrary library(
        {.max_outer_planes = max_planes,
         .automatic_inner = scene.bounds.automatic_inner && !args.no_automatic_inner,
         .pieces = scene.bounds.pieces && !args.no_pieces});
    std::vector<std::string> warnings;
    const std::vector<bt::ObjectVolumes> volumes = library.build(scene, &warnings);
    const double volumes_ms = ms_since(start);
    for (const std::string& warning : warnings) {
        std::fprintf(stderr, "shaftlab: warning: %s\n", warning.c_str());
    }
    start = Clock::now();
    const bt::BeamTree tree(scene.light, volumes);
    const double build_ms = ms_since(start);

    if (!args.classify.empty()) {
        std::string out;
        for (const dvec3& p : points) {
            out += bt::to_string(tree.classify(p));
            out += '\n';
        }
        std::fputs(out.c_str(), stdout);
        return 0;
    }

    start = Clock::now();
    const bt::Regions regions = bt::extract_regions(tree);
    const double extract_ms = ms_since(start);

    start = Clock::now();
    const auto platform = gl::create_headless_platform();
    frame::SceneRenderer renderer(scene, {.width = width, .height = height});
    const auto method = methods::create_volume_method("none");
    const frame::Frame frame = renderer.render(*method);
    const double render_ms = ms_since(start);
    start = Clock::now();
    const std::vector<uint8_t> picture =
        bt::draw_regions(scene, tree, frame.depth, frame.display_srgb8, width, height);
    const double picture_ms = ms_since(start);
    const std::array<double, 3> lengths = eye_ray_lengths(scene, tree, frame.depth, width, height);
    const double eye_length = lengths[0] + lengths[1] + lengths[2];
    auto share = [&](bt::Region r) {
        return eye_length > 0.0 ? lengths[size_t(r)] / eye_length : 0.0;
    };
    // Objects by their number of convex pieces (glass, which casts no shadow, has none).
    std::map<int, int> objects_by_pieces;
    {
        std::map<int, int> pieces_of;
        for (const bt::ObjectVolumes& v : volumes) {
            pieces_of[v.object] = v.pieces;
        }
        for (const auto& [object, count] : pieces_of) {
            ++objects_by_pieces[count];
        }
    }
    nlohmann::ordered_json pieces_json = nlohmann::ordered_json::object();
    for (const auto& [count, objects] : objects_by_pieces) {
        pieces_json[std::to_string(count)] = objects;
    }

    const bt::BeamTreeStats stats = tree.stats();
    size_t inner_volumes = 0, outer_faces = 0;
    for (const bt::ObjectVolumes& v : volumes) {
        inner_volumes += v.inner.size();
        outer_faces += v.outer.faces.size();
    }
    nlohmann::ordered_json json = {
        {"scene", scene.name},
        {"epsilon", tree.epsilon()},
        {"objects", scene.objects.size()},
        {"outer_volume_faces", outer_faces},
        {"outer_volumes", volumes.size()},
        {"objects_by_pieces", pieces_json},
        {"eye_ray_share",
         {{"lit", share(bt::Region::lit)},
          {"uncertain", share(bt::Region::uncertain)},
          {"unlit", share(bt::Region::unlit)},
          {"length", eye_length}}},
        {"inner_volumes", inner_volumes},
        {"max_outer_planes", max_planes},
        {"beams", regions.beam_count},
        {"tree",
         {{"nodes", stats.nodes},
          {"max_depth", stats.max_depth},
          {"open_leaves", stats.open_leaves},
          {"solid_leaves", stats.solid_leaves},
          {"blocker_leaves", stats.blocker_leaves},
          {"outer_polygons", stats.outer_polygons},
          {"stopper_polygons", stats.stopper_polygons}}},
        {"regions",
         {{"lit",
           {{"pieces", regions.pieces[0].size()},
            {"faces", regions.face_count(bt::Region::lit)},
            {"volume", regions.volume[0]}}},
          {"uncertain",
           {{"pieces", regions.pieces[1].size()},
            {"faces", regions.face_count(bt::Region::uncertain)},
            {"volume", regions.volume[1]}}},
          {"unlit",
           {{"pieces", regions.pieces[2].size()},
            {"faces", regions.face_count(bt::Region::unlit)},
            {"volume", regions.volume[2]}}}}},
        {"influence_volume", regions.influence_volume},
        {"volumes_ms", volumes_ms},
        {"build_ms", build_ms},
        {"extract_ms", extract_ms},
        {"render_ms", render_ms},
        {"picture_ms", picture_ms},
        {"warnings", warnings},
    };
    start = Clock::now();
    OutputFiles outputs(args.out);
    outputs.add("regions.ply",
                [&](const std::filesystem::path& path) { bt::write_regions_ply(regions, path); });
    outputs.add_text("regions.json", json.dump(2) + "\n");
    outputs.add("regions.png", [&](const std::filesystem::path& path) {
        write_png(picture, width, height, path);
    });
    outputs.commit();
    const double write_ms = ms_since(start);
    std::string by_pieces;
    for (const auto& [count, objects] : objects_by_pieces) {
        by_pieces += fmt::format("{}{} x {}", by_pieces.empty() ? "" : ", ", objects, count);
    }
    fmt::print(
        "{}: {} objects casting shadows in {} convex pieces ({} objects x pieces); eye "
        "rays in the cone: {:.1f}% lit, {:.1f}% uncertain, {:.1f}% unlit\n",
        scene.name,
        objects_by_pieces.empty()
            ? 0
            : std::accumulate(objects_by_pieces.begin(), objects_by_pieces.end(), 0,
                              [](int sum, const auto& entry) { return sum + entry.second; }),
        volumes.size(), by_pieces, 100.0 * share(bt::Region::lit),
        100.0 * share(bt::Region::uncertain), 100.0 * share(bt::Region::unlit));
    fmt::print(
        "{}: {} beams ({} lit, {} uncertain, {} unlit pieces); volumes {:.0f} ms, tree {:.0f} "
        "ms, regions {:.0f} ms, scene render {:.0f} ms, picture {:.0f} ms, files {:.0f} ms -> "
        "{}/regions.{{ply,json,png}}\n",
        scene.name, regions.beam_count, regions.pieces[0].size(), regions.pieces[1].size(),
        regions.pieces[2].size(), volumes_ms, build_ms, extract_ms, render_ms, picture_ms, write_ms,
        args.out);
    return 0;
}

}  // namespace

Command add_regions_command(CLI::App& app) {
    CLI::App* command = app.add_subcommand(
        "regions", "Beam-tree regions of a scene: DIR/regions.{ply,json,png}, or classify points");
    auto args = std::make_shared<RegionsArguments>();
    args->size = "960x540";
    add_common_options(*command, *args, Common::scene | Common::time | Common::size | Common::out);
    command->add_option(
        "--classify", args->classify,
        "File of points 'x y z', one per line: print lit, uncertain or unlit for each");
    command
        ->add_option("--max-planes", args->max_planes,
                     "Reduce each outer hull to at most K planes (0: full hull; default: the "
                     "scene's [beamtree] max_outer_planes)")
        ->check(CLI::Range(0, 100000) & !CLI::Range(1, 7));
    command->add_flag("--no-auto-inner", args->no_automatic_inner,
                      "Use only explicit inner boxes from the scene file");
    command->add_flag("--no-pieces", args->no_pieces,
                      "One convex hull per object, not convex pieces where the hull is loose");
    return [args] { return run_regions(*args); };
}

}  // namespace sl::app
