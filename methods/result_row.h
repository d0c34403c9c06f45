#pragma once
// The record of one measured method on one view: the columns every harness row and `shaftlab
// render`'s JSON share (docs/harness.md, "Columns"), written by the same functions so that a cell
// in a sweep and a single render report the same quantities under the same names. Each adds its
// columns in a fixed order (results.csv keeps the first row's order).

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "frame/renderer.h"
#include "frame/volume_method.h"
#include "gl/platform.h"
#include "methods/region_statistics.h"

namespace sl::methods {

using Row = nlohmann::ordered_json;

// scene, method, width, height, params (the settings as "a=1;b=x").
Row view_columns(const std::string& scene, const std::string& method, int width, int height,
                 const std::string& params);
// frames, fps (1000 / median), frame_ms_median, frame_ms_p5, frame_ms_p95.
void add_frame_times(Row& row, int frames, const std::vector<double>& frame_ms);
// gpu_ms_total and gpu_ms_<pass> for each pass and gpu_ms_volume_<section> for each section.
void add_gpu(Row& row, const frame::PassTimings& gpu, double total_ms);
// A named counter of the method's, 0 when it has none.
double statistic(const frame::MethodStatistics& statistics, const std::string& name);
// The region statistics of the view and the method's CPU stages (cpu_ms_*).
void add_regions(Row& row, const RegionStatistics& regions,
                 const frame::MethodStatistics& statistics);
// samples_or_slices, image (the picture's path, "" for none), stat_<counter>, param_<name> (by
// name: numbers, true/false, choices).
void add_method(Row& row, const frame::VolumeMethod& method,
                const frame::MethodStatistics& statistics, const std::string& image);
// shadow, shadow_map_size, shadow_radius, gl_vendor, gl_renderer, gl_version.
void add_context(Row& row, const frame::ShadowSettings& shadow, const gl::ContextInfo& context);
// The translucent objects' splatting (Rohat), when the scene has any: sss_r_max_mm of the first
// material, sss_splat_draws and sss_grid_samples of the last frame.
void add_subsurface(Row& row, const frame::SceneRenderer& renderer);

}  // namespace sl::methods
