#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "core/error.h"
#include "core/metrics.h"
#include "core/output_files.h"
#include "core/statistics.h"
#include "frame/renderer.h"
#include "gl/platform.h"
#include "methods/configured_method.h"
#include "methods/frame_measurement.h"
#include "methods/region_statistics.h"
#include "methods/registry.h"
#include "methods/result_row.h"
#include "reference/reference.h"
#include "scenes/animation.h"
#include "scenes/scene_file.h"

namespace sl::app {

namespace {

struct RenderArguments : CommonOptions {
    int frames = 5;
    std::string compare;  // "reference": score I_s against it
};

// One measured view of a method and what it is scored and reported with.
struct RenderedView {
    methods::FrameMeasurement measured;
    frame::Frame frame;  // the last measured frame, read back
    methods::RegionStatistics regions;
    std::optional<ErrorMetrics> error;     // against args.compare
    std::optional<Image> reference_image;  // the reference's I_s
    double load_ms = 0.0;
    double setup_ms = 0.0;
    double prepare_ms = 0.0;
    double regions_ms = 0.0;
};

// Prepares the method, measures its frames (warm-up frames absorb shader compilation and
// first-use costs; timings are medians over the measured frames, which read nothing back; the
// images are the last one's), and scores it.
void measure_view(const RenderArguments& args, const Scene& scene, frame::SceneRenderer& renderer,
                  frame::VolumeMethod& method, RenderedView& view) {
    auto start = Clock::now();
    method.set_view_aspect(renderer.options().aspect());
    method.prepare(scene);
    view.prepare_ms = ms_since(start);
    view.measured = methods::measure_frames(renderer, method, args.warmup, args.frames);
    view.frame = renderer.read_back();
    view.frame.cpu_ms = view.measured.frame_ms_median();
    view.frame.gpu = view.measured.gpu;

    // The region statistics of the view, as a harness cell reports them.
    start = Clock::now();
    const int width = renderer.options().width, height = renderer.options().height;
    view.regions = methods::region_statistics(scene, width, height);
    view.regions_ms = ms_since(start);
    if (!view.regions.unavailable.empty()) {
        std::fprintf(stderr, "shaftlab: warning: no region statistics: %s\n",
                     view.regions.unavailable.c_str());
    }

    // Error against the reference on the I_s buffer, rendered by the same renderer (and cached).
    if (!args.compare.empty()) {
        const auto reference = methods::create_volume_method(args.compare);
        view.reference_image = renderer.render(*reference).in_scattering;
        const std::vector<uint8_t> scored =
            reference::same_surface_pixels(scene, width, height, view.frame.depth);
        view.error = compare_images(view.frame.in_scattering, *view.reference_image, &scored);
    }
}

// One row in the harness's columns (methods/result_row.h), so that a render and a cell of a
// sweep report the same quantities under the same names.
methods::Row view_row(const RenderArguments& args, const Scene& scene,
                      const frame::SceneRenderer& renderer, const frame::VolumeMethod& method,
                      const gl::ContextInfo& context, const RenderedView& view) {
    const methods::FrameMeasurement& measured = view.measured;
    const std::optional<ErrorMetrics>& error = view.error;
    const std::string stem = fmt::format("{}.{}", scene.name, method.name());
    std::string params;
    for (const std::string& setting : args.settings) {
        params += (params.empty() ? "" : ";") + setting;
    }
    methods::Row json = methods::view_columns(scene.name, method.name(), renderer.options().width,
                                              renderer.options().height, params);
    json["scene_file"] = scene.source.string();
    methods::add_frame_times(json, args.frames, measured.frame_ms);
    methods::add_gpu(json, measured.gpu, measured.gpu_total_ms);
    json["volume_cost_ms"] =
        measured.gpu.volume_ms + methods::statistic(measured.statistics, "cpu_ms_frame");
    json["cpu_ms_scene_load"] = view.load_ms;
    json["cpu_ms_gl_setup"] = view.setup_ms;
    json["cpu_ms_prepare"] = view.prepare_ms;
    json["cpu_ms_region_statistics"] = view.regions_ms;
    // JSON has no infinity: an exact match has psnr null; no comparison, all three null.
    json["rel_rmse"] = error ? methods::Row(error->rel_rmse) : methods::Row();
    json["max_abs"] = error ? methods::Row(error->max_abs) : methods::Row();
    json["psnr"] = error && std::isfinite(error->psnr) ? methods::Row(error->psnr) : methods::Row();
    json["unscored_pixels"] = error ? methods::Row(error->unscored) : methods::Row();
    methods::add_regions(json, view.regions, measured.statistics);
    methods::add_method(json, method, measured.statistics, stem + ".png");
    methods::add_context(json, renderer.shadow(), context);
    json["reference"] = args.compare;
    json["warmup"] = args.warmup;
    methods::add_subsurface(json, renderer);
    json["objects"] = scene.objects.size();
    json["triangles"] = scene.triangle_count();
    if (args.time) {
        json["time_s"] = *args.time;  // the still frame of the scene's [animation]
    }
    std::vector<std::string> files = {stem + ".png", stem + ".exr", stem + ".inscatter.exr",
                                      stem + ".json"};
    if (!args.compare.empty() && args.compare != method.name()) {
        files.push_back(fmt::format("{}.{}.inscatter.exr", scene.name, args.compare));
    }
    json["files"] = files;
    return json;
}

void write_view(const RenderArguments& args, const Scene& scene, const frame::VolumeMethod& method,
                const RenderedView& view, const methods::Row& json) {
    const std::string stem = fmt::format("{}.{}", scene.name, method.name());
    const frame::Frame& frame = view.frame;
    OutputFiles outputs(args.out);
    outputs.add(stem + ".png", [&](const std::filesystem::path& path) {
        write_png(frame.display_srgb8, frame.radiance.width, frame.radiance.height, path);
    });
    outputs.add(stem + ".exr",
                [&](const std::filesystem::path& path) { write_exr(frame.radiance, path); });
    outputs.add(stem + ".inscatter.exr",
                [&](const std::filesystem::path& path) { write_exr(frame.in_scattering, path); });
    if (view.reference_image && args.compare != method.name()) {
        // The reference's I_s beside the outputs, so that `shaftlab compare` has it to read.
        outputs.add(
            fmt::format("{}.{}.inscatter.exr", scene.name, args.compare),
            [&](const std::filesystem::path& path) { write_exr(*view.reference_image, path); });
    }
    outputs.add_text(stem + ".json", json.dump(2) + "\n");
    outputs.commit();
    fmt::print(
        "{}: {}x{} {} in {:.1f} ms GPU ({:.1f} ms CPU) -> {}/{}.{{png,exr,inscatter.exr,json}}\n",
        scene.name, frame.radiance.width, frame.radiance.height, method.name(),
        view.measured.gpu_total_ms, frame.cpu_ms, args.out, stem);
    if (view.error) {
        fmt::print(
            "  against {} ({}/{}.{}.inscatter.exr): rel_rmse {:.3g}, max_abs {:.3g}, psnr "
            "{:.1f} dB\n",
            args.compare, args.out, scene.name, args.compare, view.error->rel_rmse,
            view.error->max_abs, view.error->psnr);
    }
}

int run_render(const RenderArguments& args) {
    frame::RenderOptions options;
    parse_size(args.size, options.width, options.height);
    options.shadow = args.shadow_settings();
    // Fail on an unknown method or setting before any expensive work. The run's shadow
    // options are the defaults of a method's own `shadow` parameters.
    const std::unique_ptr<frame::VolumeMethod> method = methods::create_configured_method(
        args.method, options.shadow, methods::parse_settings(args.settings));
    if (!args.compare.empty() && args.compare != "reference") {
        fail("--compare {}: only 'reference' can be compared against", quote(args.compare));
    }
    RenderedView view;
    auto start = Clock::now();
    const Scene scene = load_scene_at(args.scene, args.time);
    view.load_ms = ms_since(start);

    start = Clock::now();
    const auto platform = gl::create_headless_platform();
    const gl::ContextInfo context = platform->info();
    frame::SceneRenderer renderer(scene, options);
    view.setup_ms = ms_since(start);

    measure_view(args, scene, renderer, *method, view);
    write_view(args, scene, *method, view, view_row(args, scene, renderer, *method, context, view));
    return 0;
}

}  // namespace

Command add_render_command(CLI::App& app) {
    CLI::App* command = app.add_subcommand(
        "render",
        "Render one frame of a scene with one method: DIR/<scene>.<method>.{png,exr,json}");
    auto args = std::make_shared<RenderArguments>();
    add_common_options(*command, *args,
                       Common::scene | Common::time | Common::method | Common::size | Common::out |
                           Common::shadow | Common::warmup);
    command->add_option("--frames", args->frames, "Measured frames (timings are medians)")
        ->check(CLI::Range(1, 10000))
        ->capture_default_str();
    command->add_option("--compare", args->compare,
                        "Score I_s against this method (reference): rel_rmse, max_abs, psnr in the "
                        "JSON");
    return [args] { return run_render(*args); };
}

}  // namespace sl::app
