#include "experiments/measure.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>

#include "analytic/in_scattering.h"
#include "beamtree/beam_tree.h"
#include "beamtree/regions.h"
#include "core/error.h"
#include "methods/registry.h"
#include "reference/reference.h"

namespace sl::experiments {

void collect(NamedSeries& series, const std::vector<std::pair<std::string, double>>& values) {
    for (const auto& [name, value] : values) {
        auto same = std::find_if(series.begin(), series.end(),
                                 [&](const auto& s) { return s.first == name; });
        if (same == series.end()) {
            series.emplace_back(name, std::vector<double>{value});
        } else {
            same->second.push_back(value);
        }
    }
}

std::vector<std::pair<std::string, double>> medians(const NamedSeries& series) {
    std::vector<std::pair<std::string, double>> out;
    for (const auto& [name, values] : series) {
        out.emplace_back(name, median(values));
    }
    return out;
}

std::vector<std::pair<std::string, std::string>> parse_settings(
    const std::vector<std::string>& name_value) {
    std::vector<std::pair<std::string, std::string>> settings;
    for (const std::string& setting : name_value) {
        const size_t equals = setting.find('=');
        if (equals == std::string::npos || equals == 0) {
            fail("--set {}: expected NAME=VALUE", quote(setting));
        }
        settings.emplace_back(setting.substr(0, equals), setting.substr(equals + 1));
    }
    return settings;
}

std::unique_ptr<gl::VolumeMethod> create_configured_method(
    const std::string& name, const gl::ShadowSettings& run,
    const std::vector<std::pair<std::string, std::string>>& settings) {
    std::unique_ptr<gl::VolumeMethod> method = methods::create_volume_method(name);
    if (method->has_parameter("shadow")) {
        method->set("shadow", gl::to_string(run.filter));
        method->set("shadow_size", std::to_string(run.map_size));
    }
    for (const auto& [parameter, value] : settings) {
        method->set(parameter, value);
    }
    return method;
}

double median(std::vector<double> values) {
    return percentile(std::move(values), 50.0);
}

double percentile(std::vector<double> values, double p) {
    if (values.empty()) {
        return 0.0;
    }
    std::sort(values.begin(), values.end());
    const double position = std::clamp(p, 0.0, 100.0) / 100.0 * double(values.size() - 1);
    const size_t below = size_t(std::floor(position));
    const size_t above = std::min(below + 1, values.size() - 1);
    return values[below] + (position - double(below)) * (values[above] - values[below]);
}

void PassSeries::add(const gl::PassTimings& gpu) {
    passes_[0].push_back(gpu.shadow_ms);
    passes_[1].push_back(gpu.surface_ms);
    passes_[2].push_back(gpu.volume_ms);
    passes_[3].push_back(gpu.composite_ms);
    passes_[4].push_back(gpu.subsurface_ms);
    totals_.push_back(gpu.total_ms());
    collect(sections_, gpu.volume_sections);
}

gl::PassTimings PassSeries::medians() const {
    return {median(passes_[0]),
            median(passes_[1]),
            median(passes_[2]),
            median(passes_[3]),
            experiments::medians(sections_),
            median(passes_[4])};
}

double PassSeries::total_median() const {
    return median(totals_);
}

FrameMeasurement measure_frames(gl::SceneRenderer& renderer, gl::VolumeMethod& method, int warmup,
                                int frames) {
    for (int i = 0; i < warmup; ++i) {
        renderer.draw(method);
    }
    FrameMeasurement m;
    PassSeries passes;
    NamedSeries statistics;
    for (int i = 0; i < frames; ++i) {
        const gl::FrameTimings timings = renderer.draw(method);
        m.frame_ms.push_back(timings.cpu_ms);
        passes.add(timings.gpu);
        collect(statistics, method.statistics());
    }
    m.gpu = passes.medians();
    m.gpu_total_ms = passes.total_median();
    m.statistics = medians(statistics);
    return m;
}

// Far enough along an eye ray to leave any influence volume (scenes are metres to a kilometre).
constexpr double kWholeRay = 1e7;

RegionStatistics region_statistics(const Scene& scene, int width, int height) {
    const auto start = std::chrono::steady_clock::now();
    RegionStatistics stats;
    const bt::BeamTree tree = bt::build_scene_beam_tree(scene);
    const bt::Regions regions = bt::extract_regions(tree);
    stats.build_ms = ms_since(start);
    stats.beams = regions.beam_count;
    for (const bt::Region region : {bt::Region::lit, bt::Region::uncertain, bt::Region::unlit}) {
        stats.region_faces += regions.face_count(region);
    }

    // A grid of eye rays with the image's aspect, at pixel centres of a scaled-down image.
    const int columns = std::min(width, 160);
    const int rows = std::max(1, int(std::lround(double(height) * columns / width)));
    const reference::ReferenceRenderer caster(scene);
    const PixelUnprojector pixels(scene.camera, columns, rows);
    const glm::dvec3 eye(scene.camera.position);
    struct Row {
        std::array<double, 3> lengths{0.0, 0.0, 0.0};
        double crossings = 0.0, crossings_visible = 0.0, span = 0.0;
    };
    std::vector<Row> row_sums(static_cast<size_t>(rows));
    tbb::parallel_for(0, rows, [&](int y) {
        std::vector<bt::RegionInterval> intervals;
        Row& sums = row_sums[size_t(y)];
        for (int x = 0; x < columns; ++x) {
            const glm::dvec3 far = pixels.point(x, y, 1.0);
            const analytic::EyeRay ray{eye, glm::normalize(far - eye)};
            const double t_max = caster.first_hit(ray, glm::length(far - eye));
            // The crossings along the whole eye ray (the analytic pass has no depth test and
            // clamps depth instead of clipping: it shades every face in front of the eye); the
            // lengths up to the first surface, inside the cone and range.
            const analytic::Interval cone = analytic::light_interval(ray, scene.light, t_max);
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
                continue;
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
    });
    std::array<double, 3> lengths{0.0, 0.0, 0.0};
    double span = 0.0;
    for (const Row& row : row_sums) {
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
    stats.uncertain_span_ratio = lengths[1] > 0.0 ? span / lengths[1] : 0.0;
    for (size_t r = 0; r < 3; ++r) {
        stats.volume_fraction[r] = regions.volume[r] / regions.influence_volume;
    }
    stats.ms = ms_since(start);
    return stats;
}

}  // namespace sl::experiments
