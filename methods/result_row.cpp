#include "methods/result_row.h"

#include <array>

#include <fmt/format.h>

#include "core/statistics.h"
#include "sss/subsurface_pass.h"

namespace sl::methods {

Row view_columns(const std::string& scene, const std::string& method, int width, int height,
                 const std::string& params) {
    return {{"scene", scene},
            {"method", method},
            {"width", width},
            {"height", height},
            {"params", params}};
}

void add_frame_times(Row& row, int frames, const std::vector<double>& frame_ms) {
    const double median_ms = median(frame_ms);
    row["frames"] = frames;
    row["fps"] = 1000.0 / median_ms;
    row["frame_ms_median"] = median_ms;
    row["frame_ms_p5"] = percentile(frame_ms, 5.0);
    row["frame_ms_p95"] = percentile(frame_ms, 95.0);
}

void add_gpu(Row& row, const frame::PassTimings& gpu, double total_ms) {
    row["gpu_ms_total"] = total_ms;
    row["gpu_ms_shadow"] = gpu.shadow_ms;
    row["gpu_ms_surface"] = gpu.surface_ms;
    row["gpu_ms_volume"] = gpu.volume_ms;
    row["gpu_ms_composite"] = gpu.composite_ms;
    row["gpu_ms_subsurface"] = gpu.subsurface_ms;
    for (const auto& [section, ms] : gpu.volume_sections) {
        row["gpu_ms_volume_" + section] = ms;
    }
}

double statistic(const frame::MethodStatistics& statistics, const std::string& name) {
    for (const auto& [key, value] : statistics) {
        if (key == name) {
            return value;
        }
    }
    return 0.0;
}

void add_regions(Row& row, const RegionStatistics& regions,
                 const frame::MethodStatistics& statistics) {
    for (const auto& [name, value] : statistics) {
        if (name.starts_with("cpu_ms_")) {
            row[name] = value;
        }
    }
    if (!regions.unavailable.empty()) {
        row["regions_unavailable"] = regions.unavailable;  // the columns below stay empty
        return;
    }
    row["cpu_ms_beamtree_regions"] = regions.build_ms;
    for (size_t r = 0; r < 3; ++r) {
        const char* region = std::array{"lit", "uncertain", "unlit"}[r];
        row[fmt::format("ray_frac_{}", region)] = regions.ray_fraction[r];
        row[fmt::format("volume_frac_{}", region)] = regions.volume_fraction[r];
    }
    row["lit_crossings"] = regions.lit_crossings;
    row["lit_crossings_visible"] = regions.lit_crossings_visible;
    row["uncertain_span_ratio"] = regions.uncertain_span_ratio;
    row["beams"] = regions.beams;
    row["region_faces"] = regions.region_faces;
}

void add_method(Row& row, const frame::VolumeMethod& method,
                const frame::MethodStatistics& statistics, const std::string& image) {
    Row samples_or_slices;
    for (const auto& [name, value] : statistics) {
        if (name == "slices") {
            samples_or_slices = value;
        }
    }
    if (samples_or_slices.is_null() && method.has_parameter("samples")) {
        samples_or_slices = method.find("samples").value;
    }
    row["samples_or_slices"] = samples_or_slices;
    row["image"] = image;
    for (const auto& [name, value] : statistics) {
        if (!name.starts_with("cpu_ms_")) {
            row["stat_" + name] = value;
        }
    }
    for (const frame::Parameter& p : method.parameters()) {
        row["param_" + p.name] = p.text();
    }
}

void add_context(Row& row, const frame::ShadowSettings& shadow, const gl::ContextInfo& context) {
    row["shadow"] = frame::to_string(shadow.filter);
    row["shadow_map_size"] = shadow.map_size;
    row["shadow_radius"] = shadow.radius;
    row["gl_vendor"] = context.vendor;
    row["gl_renderer"] = context.renderer;
    row["gl_version"] = context.version;
}

void add_subsurface(Row& row, const frame::SceneRenderer& renderer) {
    if (const sss::SubsurfacePass* pass = renderer.subsurface()) {
        if (!pass->materials().empty()) {
            row["sss_r_max_mm"] = pass->materials().front().r_max_mm;
        }
        row["sss_splat_draws"] = pass->stats().splat_draws;
        row["sss_grid_samples"] = pass->stats().grid_samples;
    }
}

}  // namespace sl::methods
