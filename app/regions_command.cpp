// `shaftlab regions`: the beam tree's lit / uncertain / unlit regions of a scene, as a PLY mesh,
// a JSON summary with timings, and a picture (Nilsson figure 5.4) seen from the scene camera.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "app/commands.h"
#include "beamtree/beam_tree.h"
#include "beamtree/region_picture.h"
#include "beamtree/regions.h"
#include "core/error.h"
#include "core/output_files.h"
#include "frame/renderer.h"
#include "gl/platform.h"
#include "methods/regions_summary.h"
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
    std::string occluders;  // empty: the scene's setting
    bool verbose = false;
    int light = -1;  // -1: the scene's one light
    bool all_lights = false;
};

// The scene as light `index` alone sees it (Scene::spot_lights' order): each light has its own
// tree and regions.
Scene one_light(const Scene& scene, int index) {
    const size_t lights = scene.spot_lights().size();
    if (index >= 0 && size_t(index) >= lights) {
        fail("--light {}: scene '{}' has {} light{} (0 to {})", index, scene.name, lights,
             lights == 1 ? "" : "s", lights - 1);
    }
    if (lights == 1) {
        return scene;
    }
    if (index < 0) {
        fail(
            "scene '{}' has {} lights, each with its own tree: choose one with --light 0 to {} "
            "(its [[lights]] in order, a point light as six: +x, -x, +y, -y, +z, -z)",
            scene.name, lights, lights - 1);
    }
    return scene.for_light(size_t(index));
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

// The objects without an automatic inner volume: one line for the scene, each object's behind
// --verbose (and in regions.json).
void warn_missing_inner(const Scene& scene, const std::vector<bt::MissingInner>& missing,
                        bool verbose) {
    const std::string summary = bt::missing_inner_summary(missing, scene.objects.size());
    if (summary.empty()) {
        return;
    }
    std::fprintf(stderr, "shaftlab: warning: %s: %s. %s\n", scene.name.c_str(), summary.c_str(),
                 verbose ? "Each one:" : "Each is listed in regions.json and with --verbose.");
    if (verbose) {
        for (const bt::MissingInner& m : missing) {
            std::fprintf(stderr, "shaftlab: warning: object '%s': no automatic inner volume: %s\n",
                         m.object.c_str(), m.reason.c_str());
        }
    }
}

// The regions of `loaded` (the scene as read, at --time) for the light args.light.
int run_regions(const RegionsArguments& args, const Scene& loaded) {
    int width = 0, height = 0;
    parse_size(args.size, width, height);
    Scene scene = one_light(loaded, args.light);
    for (const Occluders choice : kOccluders) {
        if (args.occluders == to_string(choice)) {
            scene.bounds.occluders = choice;
        }
    }
    const std::vector<dvec3> points =
        args.classify.empty() ? std::vector<dvec3>() : read_points(args.classify);
    methods::RegionsTimings timings;

    auto start = Clock::now();
    const int max_planes = args.max_planes >= 0 ? args.max_planes : scene.bounds.max_outer_planes;
    const bool pieces = scene.bounds.pieces && !args.no_pieces;
    if (pieces && max_planes > 0) {
        fail(
            "--max-planes {}: {} cuts its objects into convex pieces, which need full hulls; add "
            "--no-pieces to reduce whole hulls instead",
            max_planes, scene.name);
    }
    bt::VolumeLibrary library(
        {.max_outer_planes = max_planes,
         .automatic_inner = scene.bounds.automatic_inner && !args.no_automatic_inner,
         .pieces = pieces,
         .occluders = scene.bounds.occluders,
         .max_triangles = scene.bounds.max_triangles,
         .min_inner_fill = scene.bounds.min_inner_fill});
    std::vector<bt::MissingInner> missing_inner;
    const std::vector<bt::ObjectVolumes> volumes = library.build(scene, &missing_inner);
    timings.volumes_ms = ms_since(start);
    warn_missing_inner(scene, missing_inner, args.verbose);
    if (args.verbose) {
        for (const bt::ExactOccluders::Object& o : bt::exact_occluders(volumes).list) {
            std::fprintf(stderr, "shaftlab: object '%s': %zu triangles as occluders: %s\n",
                         o.name.c_str(), o.triangles, o.why.c_str());
        }
    }
    start = Clock::now();
    const bt::BeamTree tree(scene.light, volumes);
    timings.build_ms = ms_since(start);

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
    timings.extract_ms = ms_since(start);

    start = Clock::now();
    const auto platform = gl::create_headless_platform();
    frame::SceneRenderer renderer(scene, {.width = width, .height = height});
    const auto method = methods::create_volume_method("none");
    const frame::Frame frame = renderer.render(*method);
    timings.render_ms = ms_since(start);
    start = Clock::now();
    const std::vector<uint8_t> picture =
        bt::draw_regions(scene, tree, frame.depth, frame.display_srgb8, width, height);
    timings.picture_ms = ms_since(start);

    const methods::RegionsSummaryInputs summary{
        .scene = scene,
        .volumes = volumes,
        .tree = tree,
        .regions = regions,
        .eye_lengths = methods::eye_ray_lengths(scene, tree, frame.depth, width, height),
        .max_outer_planes = max_planes,
        .timings = timings,
        .missing_inner = missing_inner};
    start = Clock::now();
    OutputFiles outputs(args.out);
    outputs.add("regions.ply",
                [&](const std::filesystem::path& path) { bt::write_regions_ply(regions, path); });
    outputs.add_text("regions.json", methods::regions_summary_json(summary).dump(2) + "\n");
    outputs.add("regions.png", [&](const std::filesystem::path& path) {
        write_png(picture, width, height, path);
    });
    outputs.commit();
    fmt::print("{}", methods::regions_summary_text(summary, ms_since(start), args.out));
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
    command
        ->add_option("--occluders", args->occluders,
                     "What the objects enter the tree as: volumes, triangles or auto (default: "
                     "the scene's [beamtree] occluders)")
        ->check(CLI::IsMember({to_string(Occluders::volumes), to_string(Occluders::triangles),
                               to_string(Occluders::automatic)}));
    command
        ->add_option("--light", args->light,
                     "The light whose tree to build, for a scene of several ([[lights]] in order, "
                     "a point light as six faces: +x, -x, +y, -y, +z, -z)")
        ->check(CLI::Range(0, 1 << 20));
    command
        ->add_flag("--all-lights", args->all_lights,
                   "Every light's regions, each into DIR/light<N>/ for a scene of several (as "
                   "--light N); a scene of one light writes DIR/ as without it")
        ->excludes("--light")
        ->excludes("--classify");
    command->add_flag("--verbose", args->verbose,
                      "List each object without an automatic inner volume, not only the count, "
                      "and each object that entered the tree as triangles, with why");
    return [args] {
        const Scene loaded = load_scene_at(args->scene, args->time);
        const size_t lights = loaded.spot_lights().size();
        if (!args->all_lights || lights == 1) {
            return run_regions(*args, loaded);
        }
        for (size_t i = 0; i < lights; ++i) {
            RegionsArguments one = *args;
            one.light = int(i);
            one.out = (std::filesystem::path(args->out) / fmt::format("light{}", i)).string();
            if (const int code = run_regions(one, loaded); code != 0) {
                return code;
            }
        }
        return 0;
    };
}

}  // namespace sl::app
