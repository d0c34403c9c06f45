#pragma once
// What `shaftlab regions` reports of a scene's beam tree: how its objects became convex pieces
// and outer volumes, what the tree and its regions hold, and how the eye rays of a rendered view
// cross the regions (the share a hybrid marches is the uncertain one).

#include <array>
#include <map>
#include <string>
#include <vector>

#include "beamtree/beam_tree.h"
#include "beamtree/bounding_volumes.h"
#include "beamtree/regions.h"
#include "methods/result_row.h"
#include "scenes/scene.h"

namespace sl::methods {

// The lengths of the eye rays (every other pixel in x and y, from the near plane up to the
// rasterized depth) inside the light's cone, by region (indexed by bt::Region).
std::array<double, 3> eye_ray_lengths(const Scene& scene, const bt::BeamTree& tree,
                                      const std::vector<float>& depth, int width, int height);

// The objects that cast shadows, counted by their number of convex pieces (glass has none).
std::map<int, int> objects_by_pieces(const std::vector<bt::ObjectVolumes>& volumes);

// The milliseconds of each step of the command, reported in the summary.
struct RegionsTimings {
    double volumes_ms = 0.0;
    double build_ms = 0.0;
    double extract_ms = 0.0;
    double render_ms = 0.0;
    double picture_ms = 0.0;
};

// Everything the summary is made of.
struct RegionsSummaryInputs {
    const Scene& scene;
    const std::vector<bt::ObjectVolumes>& volumes;
    const bt::BeamTree& tree;
    const bt::Regions& regions;
    std::array<double, 3> eye_lengths{};  // eye_ray_lengths()
    int max_outer_planes = 0;
    RegionsTimings timings;
    const std::vector<bt::MissingInner>& missing_inner;
};

// regions.json.
Row regions_summary_json(const RegionsSummaryInputs& in);

// The two lines printed at the end of the command (the files' timing and folder added).
std::string regions_summary_text(const RegionsSummaryInputs& in, double write_ms,
                                 const std::string& out);

}  // namespace sl::methods
