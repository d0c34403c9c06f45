#include "beamtree/frame_regions.h"

#include <chrono>
#include <optional>

#include "beamtree/boundary.h"

namespace sl::bt {

namespace {

using Clock = std::chrono::steady_clock;

double ms_between(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

}  // namespace

std::vector<std::pair<std::string, double>> RegionStageTimes::named() const {
    return {{"volumes", volumes},          {"tree", tree},
            {"regions", regions},          {"lit mesh", lit},
            {"uncertain mesh", uncertain}, {"gpu tree", gpu_tree}};
}

FrameRegions build_frame_regions(const Scene& scene, const RegionRequest& request) {
    FrameRegions out;
    Clock::time_point t = Clock::now();
    auto lap = [&](double& stage) {
        const Clock::time_point now = Clock::now();
        stage = ms_between(t, now);
        t = now;
    };
    VolumeLibrary& library = VolumeLibrary::shared(scene.bounds);
    const std::shared_ptr<const std::vector<ObjectVolumes>> shared = library.build_shared(scene);
    const std::vector<ObjectVolumes>& volumes = *shared;
    out.exact = exact_occluders(volumes);
    lap(out.ms.volumes);
    const std::optional<ViewWindow> window =
        request.view_dependent(scene) ? view_window(scene.light, scene.camera, request.view_aspect)
                                      : std::nullopt;
    // A view that misses the sun's box sees none of its light: the whole box stands in for it.
    auto tree = std::make_shared<const BeamTree>(scene.light, volumes, TreeBuild{}, window);
    lap(out.ms.tree);
    if (request.lit || request.uncertain || request.pieces) {
        auto pieces = std::make_shared<const Regions>(extract_regions(*tree));
        const Regions& regions = *pieces;
        lap(out.ms.regions);
        if (request.pieces) {
            out.regions = pieces;
        }
        if (request.lit) {
            out.lit = request.cells
                          ? regions.mesh(Region::lit)
                          : boundary_mesh(*tree, regions, Region::lit, nullptr, request.shape);
            lap(out.ms.lit);
        }
        if (request.uncertain) {
            out.uncertain =
                boundary_mesh(*tree, regions, Region::uncertain, nullptr, request.shape);
            lap(out.ms.uncertain);
        }
    }
    if (request.gpu_tree) {
        out.gpu = tree->gpu_tree(request.layout);
        lap(out.ms.gpu_tree);
    }
    out.tree = std::move(tree);
    return out;
}

}  // namespace sl::bt
