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
#include "methods/registry.h"
#include "scenes/animation.h"
#include "scenes/scene_file.h"

namespace sl::app {

namespace {

struct RenderArguments : CommonOptions {
    int frames = 5;
    std::string compare;  // "reference": score I_s against it
};

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

    auto start = Clock::now();
    const Scene scene = load_scene_at(args.scene, args.time);
    const double load_ms = ms_since(start);

    start = Clock::now();
    const auto platform = gl::create_headless_platform();
    const gl::ContextInfo context = platform->info();
    frame::SceneRenderer renderer(scene, options);
    const double setup_ms = ms_since(start);

    start = Clock::now();
    method->prepare(scene);
    const double prepare_ms = ms_since(start);
    // Warm-up frames absorb shader compilation and first-use costs; timings are medians over
    // the measured frames, which read nothing back; the images are the last one's.
    const methods::FrameMeasurement measured =
        methods::measure_frames(renderer, *method, args.warmup, args.frames);
    frame::Frame frame = renderer.read_back();
    frame.cpu_ms = measured.frame_ms_median();
    frame.gpu = measured.gpu;
    const double frame_gpu_ms = measured.gpu_total_ms;
    const frame::ShadowSettings shadow = renderer.shadow();

    // Error against the reference on the I_s buffer, rendered by the same renderer (and cached).
    std::optional<ErrorMetrics> error;
    std::optional<Image> reference_image;
    if (!args.compare.empty()) {
        const auto reference = methods::create_volume_method(args.compare);
        reference_image = renderer.render(*reference).in_scattering;
        error = compare_images(frame.in_scattering, *reference_image);
    }

    const std::string stem = fmt::format("{}.{}", scene.name, method->name());
    nlohmann::ordered_json json = {
        {"scene", scene.name},
        {"scene_file", scene.source.string()},
        {"method", method->name()},
        {"parameters",
         [&] {
             nlohmann::ordered_json parameters = nlohmann::ordered_json::object();
             for (const frame::Parameter& p : method->parameters())
                 parameters[p.name] = p.type == frame::Parameter::Type::choice
                                          ? nlohmann::ordered_json(p.text())
                                      : p.type == frame::Parameter::Type::boolean
                                          ? nlohmann::ordered_json(p.value != 0.0)
                                          : nlohmann::ordered_json(p.value);
             return parameters;
         }()},
        {"width", options.width},
        {"height", options.height},
        {"shadow",
         {{"filter", frame::to_string(shadow.filter)},
          {"radius", shadow.radius},
          {"map_size", shadow.map_size}}},
        {"protocol",
         {{"warmup_frames", args.warmup},
          {"measured_frames", args.frames},
          {"statistic", "median"}}},
        {"gl",
         {{"renderer", context.renderer},
          {"version", context.version},
          {"vendor", context.vendor}}},
        {"stats", {{"objects", scene.objects.size()}, {"triangles", scene.triangle_count()}}},
        {"timings_ms",
         {{"scene_load", load_ms},
          {"gl_setup", setup_ms},
          {"method_prepare", prepare_ms},
          {"frame_cpu", frame.cpu_ms},
          {"gpu",
           {{"shadow", frame.gpu.shadow_ms},
            {"surface", frame.gpu.surface_ms},
            {"volume", frame.gpu.volume_ms},
            {"composite", frame.gpu.composite_ms},
            {"subsurface", frame.gpu.subsurface_ms},
            {"total", frame_gpu_ms},
            {"volume_sections",
             [&] {
                 nlohmann::ordered_json sections = nlohmann::ordered_json::object();
                 for (const auto& [name, ms] : frame.gpu.volume_sections)
                     sections[name] = ms;
                 return sections;
             }()}}}}},
        {"method_statistics",
         [&] {
             // Medians over the measured frames.
             nlohmann::ordered_json values = nlohmann::ordered_json::object();
             for (const auto& [name, value] : measured.statistics)
                 values[name] = value;
             return values;
         }()},
        {"files",
         [&] {
             std::vector<std::string> files = {stem + ".png", stem + ".exr",
                                               stem + ".inscatter.exr", stem + ".json"};
             if (!args.compare.empty() && args.compare != method->name()) {
                 files.push_back(fmt::format("{}.{}.inscatter.exr", scene.name, args.compare));
             }
             return files;
         }()},
    };

    if (args.time) {
        json["time_s"] = *args.time;  // the still frame of the scene's [animation]
    }
    if (error) {
        // JSON has no infinity: an exact match has psnr null.
        json["error"] = {
            {"against", args.compare},
            {"rel_rmse", error->rel_rmse},
            {"max_abs", error->max_abs},
            {"psnr", std::isfinite(error->psnr) ? nlohmann::json(error->psnr) : nlohmann::json()}};
    }
    OutputFiles outputs(args.out);
    outputs.add(stem + ".png", [&](const std::filesystem::path& path) {
        write_png(frame.display_srgb8, options.width, options.height, path);
    });
    outputs.add(stem + ".exr",
                [&](const std::filesystem::path& path) { write_exr(frame.radiance, path); });
    outputs.add(stem + ".inscatter.exr",
                [&](const std::filesystem::path& path) { write_exr(frame.in_scattering, path); });
    if (reference_image && args.compare != method->name()) {
        // The reference's I_s beside the outputs, so that `shaftlab compare` has it to read.
        outputs.add(fmt::format("{}.{}.inscatter.exr", scene.name, args.compare),
                    [&](const std::filesystem::path& path) { write_exr(*reference_image, path); });
    }
    outputs.add_text(stem + ".json", json.dump(2) + "\n");
    outputs.commit();
    fmt::print(
        "{}: {}x{} {} in {:.1f} ms GPU ({:.1f} ms CPU) -> {}/{}.{{png,exr,inscatter.exr,json}}\n",
        scene.name, options.width, options.height, method->name(), frame_gpu_ms, frame.cpu_ms,
        args.out, stem);
    if (error) {
        fmt::print(
            "  against {} ({}/{}.{}.inscatter.exr): rel_rmse {:.3g}, max_abs {:.3g}, psnr "
            "{:.1f} dB\n",
            args.compare, args.out, scene.name, args.compare, error->rel_rmse, error->max_abs,
            error->psnr);
    }
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
