#pragma once
// Measuring one cell (DESIGN.md §6): frame timings over a protocol, the error of I_s against the
// reference, and the beam-tree region statistics of the view. Shared by `shaftlab render` and the
// harness, so a cell in a sweep measures exactly what a single render reports.

#include <array>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/metrics.h"
#include "gl/renderer.h"
#include "scenes/scene.h"

namespace sl::experiments {

// Milliseconds of wall time since `start`, for stage timings.
inline double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

// The method `name` with the run's shadow map as the default of its own `shadow` parameters
// (when it declares them), then each (name, value) setting applied; throws sl::Error naming the
// method and parameter on an unknown one or a bad value.
std::unique_ptr<gl::VolumeMethod> create_configured_method(
    const std::string& name, const gl::ShadowSettings& run,
    const std::vector<std::pair<std::string, std::string>>& settings);

// "NAME=VALUE" command-line settings split into pairs; throws sl::Error on one without '='.
std::vector<std::pair<std::string, std::string>> parse_settings(
    const std::vector<std::string>& name_value);

double median(std::vector<double> values);
// The p-th percentile (p in [0, 100]) with linear interpolation between order statistics.
double percentile(std::vector<double> values, double p);

// Named values per frame, each name's series in first-seen order: collect() appends one frame's
// values, medians() reduces each series.
using NamedSeries = std::vector<std::pair<std::string, std::vector<double>>>;
void collect(NamedSeries& series, const std::vector<std::pair<std::string, double>>& values);
std::vector<std::pair<std::string, double>> medians(const NamedSeries& series);

// The GPU time of each pass over frames: add() one frame's, medians() each pass's median (and
// each volume section's), total_median() the median of the frames' sums.
class PassSeries {
public:
    void add(const gl::PassTimings& gpu);
    gl::PassTimings medians() const;
    double total_median() const;

private:
    std::vector<double> passes_[5], totals_;
    NamedSeries sections_;
};

struct FrameMeasurement {
    std::vector<double> frame_ms;     // wall time of each measured frame (CPU work + GPU wait)
    gl::PassTimings gpu;              // median GPU time of each pass and volume section
    double gpu_total_ms = 0.0;        // median of the frames' summed GPU time
    gl::MethodStatistics statistics;  // median of each method counter over the frames
    double frame_ms_median() const { return median(frame_ms); }
};

// `warmup` frames (shader compilation, first-use costs), then `frames` measured frames that read
// nothing back. The renderer holds the last frame for read_back().
FrameMeasurement measure_frames(gl::SceneRenderer& renderer, gl::VolumeMethod& method, int warmup,
                                int frames);

// How the view's eye rays cross the beam-tree regions (DESIGN.md §6 "region statistics"), in two
// quantities with one name each everywhere (CSV, tables, viewer):
//   eye-ray fraction  of the eye-ray length inside the light's cone and range, in front of the
//                     first surface, the share in lit, uncertain and unlit regions (exact, from
//                     each ray's walk through the tree, on a grid of at most 160 rays across);
//   volume fraction   of the influence volume, the share of each region type.
// And what the region passes can at best cost, on the same rays:
//   lit crossings     per pixel, twice the maximal lit intervals of the whole eye ray (the
//                     fewest fragments an analytic pass that shades every face in front of the
//                     eye can: it enters and leaves each interval once), and of the eye ray up
//                     to the first surface (what a depth-tested pass could get down to);
//   uncertain span    the length from the first entry into the uncertain region to the last exit
//                     (up to the first surface), over the uncertain length itself: what marching
//                     one spanning interval per pixel walks for each metre of uncertain space.
struct RegionStatistics {
    std::array<double, 3> ray_fraction{};     // indexed by bt::Region
    std::array<double, 3> volume_fraction{};  // indexed by bt::Region
    double lit_crossings = 0.0;               // per pixel, whole eye ray
    double lit_crossings_visible = 0.0;       // per pixel, up to the first surface
    double uncertain_span_ratio = 0.0;        // spanning interval length / uncertain length
    size_t beams = 0;
    size_t region_faces = 0;  // faces of all region polyhedra
    double build_ms = 0.0;    // beam tree build + region extraction
    double ms = 0.0;          // the whole computation
};
RegionStatistics region_statistics(const Scene& scene, int width, int height);

}  // namespace sl::experiments
