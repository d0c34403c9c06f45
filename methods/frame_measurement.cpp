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
        collect(statistics, method.frame_statistics());
    }
    m.gpu = passes.medians();
    m.gpu_total_ms = passes.total_median();
    m.statistics = medians(statistics);
    return m;
}

PairedMeasurement measure_paired_frames(frame::SceneRenderer& renderer, frame::VolumeMethod& method,
                                        frame::VolumeMethod& baseline, int warmup, int frames) {
    for (int i = 0; i < warmup; ++i) {
        renderer.draw(method);
        renderer.draw(baseline);
    }
    PairedMeasurement m;
    PassSeries passes;
    NamedSeries statistics;
    auto draw_method = [&] {
        const frame::FrameTimings timings = renderer.draw(method);
        passes.add(timings.gpu);
        collect(statistics, method.frame_statistics());
        m.method.frame_ms.push_back(timings.cpu_ms);
    };
    for (int i = 0; i < frames; ++i) {
        if (i % 2 == 0) {
            draw_method();
            m.baseline_ms.push_back(renderer.draw(baseline).cpu_ms);
        } else {
            m.baseline_ms.push_back(renderer.draw(baseline).cpu_ms);
            draw_method();
        }
        m.difference_ms.push_back(m.method.frame_ms.back() - m.baseline_ms.back());
    }
    // The renderer holds the method's frame for read_back(), as measure_frames leaves it.
    renderer.draw(method);
    m.method.gpu = passes.medians();
    m.method.gpu_total_ms = passes.total_median();
    m.method.statistics = medians(statistics);
    return m;
}

}  // namespace sl::methods
