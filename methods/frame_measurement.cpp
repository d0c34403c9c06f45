#include "methods/frame_measurement.h"

namespace sl::methods {

void PassSeries::add(const frame::PassTimings& gpu) {
    passes_[0].push_back(gpu.shadow_ms);
    passes_[1].push_back(gpu.surface_ms);
    passes_[2].push_back(gpu.volume_ms);
    passes_[3].push_back(gpu.composite_ms);
    passes_[4].push_back(gpu.subsurface_ms);
    totals_.push_back(gpu.total_ms());
    collect(sections_, gpu.volume_sections);
}

frame::PassTimings PassSeries::medians() const {
    return {median(passes_[0]), median(passes_[1]),     median(passes_[2]),
            median(passes_[3]), sl::medians(sections_), median(passes_[4])};
}

double PassSeries::total_median() const {
    return median(totals_);
}

FrameMeasurement measure_frames(frame::SceneRenderer& renderer, frame::VolumeMethod& method,
                                int warmup, int frames) {
    for (int i = 0; i < warmup; ++i) {
        renderer.draw(method);
    }
    FrameMeasurement m;
    PassSeries passes;
    NamedSeries statistics;
    for (int i = 0; i < frames; ++i) {
        const frame::FrameTimings timings = renderer.draw(method);
        m.frame_ms.push_back(timings.cpu_ms);
        passes.add(timings.gpu);
        collect(statistics, method.statistics());
    }
    m.gpu = passes.medians();
    m.gpu_total_ms = passes.total_median();
    m.statistics = medians(statistics);
    return m;
}

}  // namespace sl::methods
