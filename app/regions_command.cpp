// `shaftlab regions`: the beam tree's lit / uncertain / unlit regions of a scene, as a PLY mesh,
// a JSON summary with timings, and a picture (Nilsson figure 5.4) seen from the scene camera.

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "beamtree/beam_tree.h"
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

struct RegionsArguments {
    std::string scene;
    std::string out = "out";
    std::string size = "960x540";
    std::string classify;
    int max_planes = -1;  // -1: the scene's setting
    bool no_automatic_inner = false;
    std::optional<double> time;  // seconds into the scene's [animation]
};

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

// A pixel's eye ray from the near plane to its first surface, clipped to the influence pyramid,
// with the regions along it (t in metres from the near-plane point).
struct PixelRegions {
    bool inside = false;  // the ray meets the influence pyramid
    double end = 0.0;     // the clipped segment's far end
    std::vector<bt::RegionInterval> intervals;
};

PixelRegions trace_pixel(const bt::BeamTree& tree, const PixelUnprojector& pixels,
                         const frame::Frame& frame, int width, int x, int y) {
    PixelRegions result;
    const double depth = 2.0 * double(frame.depth[size_t(y) * width + x]) - 1.0;
    const dvec3 origin = pixels.point(x, y, -1.0);
    const dvec3 end = pixels.point(x, y, std::min(depth, 1.0));
    double t0 = 0.0, t1 = 1.0;
    for (const bt::Plane& plane : tree.influence_planes()) {
        const double d0 = plane.distance(origin), d1 = plane.distance(end);
        if (d0 > 0.0 && d1 > 0.0) {
            return result;
        }
        if (d0 > 0.0)
            t0 = std::max(t0, d0 / (d0 - d1));
        if (d1 > 0.0)
            t1 = std::min(t1, d0 / (d0 - d1));
    }
    const double length = glm::length(end - origin);
    if (t1 <= t0 || !(length > 0.0)) {
        return result;
    }
    result.inside = true;
    result.end = t1 * length;
    tree.trace(origin, (end - origin) / length, t0 * length, t1 * length, result.intervals);
    return result;
}

// The regions seen from the camera (Nilsson figure 5.4's colours): every pixel's ray, up to the
// first surface, composited front to back through the influence volume with lit yellow,
// uncertain grey and unlit black, over the rendered scene. Rays are traced through the tree
// (BeamTree::trace) at every other pixel in x and y; a pixel between traced ones whose
// neighbours cross the same sequence of regions and reach nearly the same depth takes the mean
// of their interval ends (they are smooth in the pixel there; the difference is below the 8-bit
// output), any other pixel is traced itself.
std::vector<unsigned char> draw_regions(const Scene& scene, const bt::BeamTree& tree,
                                        const frame::Frame& frame, int width, int height) {
    const PixelUnprojector pixels(scene.camera, width, height);
    const double far = double(scene.light.far);
    const glm::dvec3 colors[3] = {{1.0, 0.82, 0.1}, {0.55, 0.55, 0.55}, {0.0, 0.0, 0.0}};
    // Uncertain and unlit absorb 8x more than lit so that thin shadow volumes show through the
    // lit air in front of them.
    const double extinction[3] = {1.5 / far, 12.0 / far, 12.0 / far};
    const int coarse_width = (width + 1) / 2, coarse_height = (height + 1) / 2;
    std::vector<PixelRegions> coarse(size_t(coarse_width) * coarse_height);
    tbb::parallel_for(0, coarse_height, [&](int j) {
        for (int i = 0; i < coarse_width; ++i) {
            coarse[size_t(j) * coarse_width + i] =
                trace_pixel(tree, pixels, frame, width, 2 * i, 2 * j);
        }
    });
    std::vector<unsigned char> image = frame.display_srgb8;
    tbb::parallel_for(0, height, [&](int y) {
        std::vector<const PixelRegions*> neighbours;
        PixelRegions mean, own;
        for (int x = 0; x < width; ++x) {
            neighbours.clear();
            for (const int cy : {y / 2, (y + 1) / 2}) {
                for (const int cx : {x / 2, (x + 1) / 2}) {
                    if (cx < coarse_width && cy < coarse_height) {
                        const PixelRegions* n = &coarse[size_t(cy) * coarse_width + cx];
                        if (std::find(neighbours.begin(), neighbours.end(), n) == neighbours.end())
                            neighbours.push_back(n);
                    }
                }
            }
            const bool traced = x % 2 == 0 && y % 2 == 0;
            bool alike = !traced && neighbours.size() == size_t((x % 2 + 1) * (y % 2 + 1));
            for (const PixelRegions* n : neighbours) {
                const PixelRegions& first = *neighbours.front();
                alike = alike && n->inside == first.inside &&
                        n->intervals.size() == first.intervals.size() &&
                        std::abs(n->end - first.end) <= 0.01 * first.end;
                for (size_t k = 0; alike && k < n->intervals.size(); ++k) {
                    alike = n->intervals[k].region == first.intervals[k].region;
                }
            }
            const PixelRegions* regions = nullptr;
            if (traced) {
                regions = neighbours.front();
            } else if (alike) {
                mean = *neighbours.front();
                for (size_t k = 0; k < mean.intervals.size(); ++k) {
                    double begin = 0.0, end = 0.0;
                    for (const PixelRegions* n : neighbours) {
                        begin += n->intervals[k].begin;
                        end += n->intervals[k].end;
                    }
                    mean.intervals[k].begin = begin / double(neighbours.size());
                    mean.intervals[k].end = end / double(neighbours.size());
                }
                regions = &mean;
            } else {
                own = trace_pixel(tree, pixels, frame, width, x, y);
                regions = &own;
            }
            if (!regions->inside) {
                continue;
            }
            dvec3 color(0.0);
            double transparency = 1.0;
            for (const bt::RegionInterval& interval : regions->intervals) {
                const auto region = size_t(interval.region);
                const double alpha =
                    1.0 - std::exp(-extinction[region] * (interval.end - interval.begin));
                color += transparency * alpha * colors[region];
                transparency *= 1.0 - alpha;
            }
            for (int c = 0; c < 3; ++c) {
                unsigned char& pixel = image[(size_t(y) * width + x) * 3 + c];
                pixel = static_cast<unsigned char>(
                    std::lround(transparency * pixel + 255.0 * std::min(1.0, color[c])));
            }
        }
    });
    return image;
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
         .automatic_inner = scene.bounds.automatic_inner && !args.no_automatic_inner});
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
    const std::vector<unsigned char> picture = draw_regions(scene, tree, frame, width, height);
    const double picture_ms = ms_since(start);

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
    command->add_option("--scene", args->scene, "Canonical name, multiple:N, or a .toml file")
        ->required();
    command->add_option("--out", args->out, "Output directory")->capture_default_str();
    command->add_option("--size", args->size, "Picture size WIDTHxHEIGHT")->capture_default_str();
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
    add_time_option(*command, args->time);
    return [args] { return run_regions(*args); };
}

}  // namespace sl::app
