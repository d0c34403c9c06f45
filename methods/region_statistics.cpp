#include "methods/region_statistics.h"

#include <fmt/format.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "analytic/in_scattering.h"
#include "beamtree/beam_tree.h"
#include "beamtree/regions.h"
#include "core/error.h"
#include "core/statistics.h"
#include "reference/reference.h"

namespace sl::methods {

// Far enough along an eye ray to leave any influence volume (scenes are metres to a kilometre).
constexpr double kWholeRay = 1e7;

namespace {

// One eye ray's (or one row's) sums.
struct RaySums {
    std::array<double, 3> lengths{0.0, 0.0, 0.0};  // inside the cone, by region
    double crossings = 0.0, crossings_visible = 0.0, span = 0.0;
};

// Adds what the tree's walk along one eye ray gives: the crossings along the whole ray (the
// analytic pass has no depth test and clamps depth instead of clipping: it shades every face in
// front of the eye), then the lengths up to the first surface t_max, inside the cone and range,
// and the span from the first uncertain entry to the last exit.
void add_ray(const bt::BeamTree& tree, const SpotLight& light, const analytic::EyeRay& ray,
             double t_max, std::vector<bt::RegionInterval>& intervals, RaySums& sums) {
    const analytic::Interval cone = analytic::light_interval(ray, light, t_max);
    tree.trace(ray.origin, ray.direction, 0.0, kWholeRay, intervals);
    for (size_t k = 0; k < intervals.size(); ++k) {
        const bt::RegionInterval& interval = intervals[k];
        if (interval.region == bt::Region::lit &&
            (k == 0 || intervals[k - 1].region != bt::Region::lit)) {
            sums.crossings += 2.0;
            sums.crossings_visible += interval.begin < t_max ? 2.0 : 0.0;
        }
    }
    if (cone.empty()) {
        return;
    }
    // The same walk clipped to the cone interval (which ends at the surface).
    double first = 0.0, last = 0.0;
    bool any = false;
    for (const bt::RegionInterval& interval : intervals) {
        const double begin = std::max(interval.begin, cone.begin);
        const double end = std::min(interval.end, cone.end);
        if (!(end > begin)) {
            continue;
        }
        sums.lengths[size_t(interval.region)] += end - begin;
        if (interval.region == bt::Region::uncertain) {
            first = any ? first : begin;
            last = end;
            any = true;
        }
    }
    sums.span += any ? last - first : 0.0;
}

// The eye-ray statistics over a grid of rays with the image's aspect, at pixel centres of a
// scaled-down image (at most 160 columns), each up to the reference's first hit.
void add_eye_rays(const Scene& scene, const bt::BeamTree& tree, int width, int height,
                  RegionStatistics& stats) {
    const int columns = std::min(width, 160);
    const int rows = std::max(1, int(std::lround(double(height) * columns / width)));
    const reference::ReferenceRenderer caster(scene);
    const PixelUnprojector pixels(scene.camera, columns, rows);
    const glm::dvec3 eye(scene.camera.position);
    std::vector<RaySums> row_sums(static_cast<size_t>(rows));
    tbb::parallel_for(0, rows, [&](int y) {
        std::vector<bt::RegionInterval> intervals;
        for (int x = 0; x < columns; ++x) {
            const glm::dvec3 far = pixels.point(x, y, 1.0);
            const analytic::EyeRay ray{eye, glm::normalize(far - eye)};
            const double t_max = caster.first_hit(ray, glm::length(far - eye));
            add_ray(tree, scene.light, ray, t_max, intervals, row_sums[size_t(y)]);
        }
    });
    std::array<double, 3> lengths{0.0, 0.0, 0.0};
    double span = 0.0;
    for (const RaySums& row : row_sums) {
        for (size_t r = 0; r < 3; ++r) {
            lengths[r] += row.lengths[r];
        }
        stats.lit_crossings += row.crossings / double(columns * rows);
        stats.lit_crossings_visible += row.crossings_visible / double(columns * rows);
        span += row.span;
    }
    const double total = lengths[0] + lengths[1] + lengths[2];
    if (total > 0.0) {
        for (size_t r = 0; r < 3; ++r) {
            stats.ray_fraction[r] = lengths[r] / total;
        }
    }
    // Where nothing is uncertain but the planes' ε-thin slabs (exact occluders), the ratio of two
    // round-off lengths says nothing: 0, shown as none.
    stats.uncertain_span_ratio = lengths[1] > 1e-6 * total ? span / lengths[1] : 0.0;
}

}  // namespace

RegionStatistics region_statistics(const Scene& scene, int width, int height) {
    const auto start = std::chrono::steady_clock::now();
    RegionStatistics stats;
    if (scene.spot_lights().size() > 1) {
        stats.unavailable = fmt::format(
            "the scene has {} lights ([[lights]]): region statistics are per light (`shaftlab "
            "regions --light N`)",
            scene.spot_lights().size());
        return stats;
    }
    std::optional<bt::BeamTree> built;
    try {
        built.emplace(bt::build_scene_beam_tree(scene));
    } catch (const Error& e) {
        stats.unavailable = e.what();
        return stats;
    }
    const bt::BeamTree& tree = *built;
    const bt::Regions regions = bt::extract_regions(tree);
    stats.build_ms = ms_since(start);
    stats.beams = regions.beam_count;
    for (const bt::Region region : {bt::Region::lit, bt::Region::uncertain, bt::Region::unlit}) {
        stats.region_faces += regions.face_count(region);
    }
    add_eye_rays(scene, tree, width, height, stats);
    for (size_t r = 0; r < 3; ++r) {
        stats.volume_fraction[r] = regions.volume[r] / regions.influence_volume;
    }
    stats.ms = ms_since(start);
    return stats;
}

}  // namespace sl::methods
