#pragma once
// Measuring frames (docs/harness.md, "What a cell measures"): the wall time of each frame, the
// median GPU time of each pass and volume section, and the medians of the method's counters.
// Shared by `shaftlab render`, `animate`, the viewer and the harness, so a cell in a sweep
// measures exactly what a single render reports.

#include <vector>

#include "core/statistics.h"
#include "frame/renderer.h"
#include "frame/volume_method.h"

namespace sl::methods {

// The GPU time of each pass over frames: add() one frame's, medians() each pass's median (and
// each volume section's), total_median() the median of the frames' sums.
class PassSeries {
public:
    void add(const frame::PassTimings& gpu);
    frame::PassTimings medians() const;
    double total_median() const;

private:
    std::vector<double> passes_[5], totals_;
    NamedSeries sections_;
};

struct FrameMeasurement {
    std::vector<double> frame_ms;        // wall time of each measured frame (CPU work + GPU wait)
    frame::PassTimings gpu;              // median GPU time of each pass and volume section
    double gpu_total_ms = 0.0;           // median of the frames' summed GPU time
    frame::MethodStatistics statistics;  // median of each method counter over the frames
    double frame_ms_median() const { return median(frame_ms); }
};

// `warmup` frames (shader compilation, first-use costs), then `frames` measured frames that read
// nothing back. The renderer holds the last frame for read_back().
FrameMeasurement measure_frames(frame::SceneRenderer& renderer, frame::VolumeMethod& method,
                                int warmup, int frames);

// A method's frames measured in pairs with a baseline's (`none`, set to the method's shadow map)
// in the same context on the same scene, so that what drifts over the run (clocks, the machine's
// other load, the driver's state) drifts in both: pair i draws the method then the baseline on
// even i and the other way round on odd i (ABBA), so a drift linear in time cancels too. A cost
// by difference is then the median of the per-pair differences (harness.md, "Paired").
struct PairedMeasurement {
    FrameMeasurement method;
    std::vector<double> baseline_ms;    // the baseline's frame of each pair
    std::vector<double> difference_ms;  // method - baseline, pair by pair
};
PairedMeasurement measure_paired_frames(frame::SceneRenderer& renderer, frame::VolumeMethod& method,
                                        frame::VolumeMethod& baseline, int warmup, int frames);

}  // namespace sl::methods
