// `shaftlab animate`: plays a scene's [animation] with one method, serial or pipelined
// (frame/frame_loop.h), and writes every frame's costs (docs/design.md §10).

#include <algorithm>
#include <cmath>
#include <memory>

#include <fmt/format.h>

#include "app/commands.h"
#include "core/error.h"
#include "core/image.h"
#include "core/output_files.h"
#include "core/statistics.h"
#include "frame/frame_loop.h"
#include "frame/renderer.h"
#include "gl/platform.h"
#include "methods/configured_method.h"
#include "scenes/animation.h"
#include "scenes/scene_file.h"

namespace sl::app {

namespace {

struct AnimateArguments : CommonOptions {
    std::string mode = "pipelined";
    int frames = 0;  // 0: the whole animation
};

// Frame 0 pays for the first build; the medians are over the frames after it.
template <class Get>
double median_after_first(const std::vector<frame::FrameRecord>& records, Get get) {
    std::vector<double> v;
    for (size_t i = records.size() > 1 ? 1 : 0; i < records.size(); ++i)
        v.push_back(get(records[i]));
    return sl::median(std::move(v));
}

// Plays the animation's first `frames` frames in one mode: its frames.csv and last picture into
// `outputs`, one summary line printed.
void play_mode(const Scene& scene, frame::VolumeMethod& method, const frame::RenderOptions& options,
               frame::FrameMode mode, int warmup, int frames, const gl::ContextInfo& context,
               OutputFiles& outputs) {
    const Animation& animation = *scene.animation;
    Scene live = scene_at(scene, animation.frame_time(0));
    frame::SceneRenderer renderer(live, options);
    method.set_view_aspect(options.aspect());
    method.prepare(live);
    for (int i = 0; i < warmup; ++i) {
        renderer.draw(method);  // shader compilation and first-use costs
    }
    std::vector<frame::FrameRecord> records;
    std::string csv =
        "frame,time_s,update_ms,update_on_worker,apply_ms,wait_ms,draw_ms,frame_ms,"
        "overlap_ms,critical_cpu_ms,gpu_ms\n";
    frame::FrameLoop loop(renderer, method, live, mode);
    loop.play(
        frames, [&](int k) { return scene_at(scene, animation.frame_time(k)); },
        [&](const frame::FrameRecord& r) {
            records.push_back(r);
            csv += fmt::format(
                "{},{:.6f},{:.4f},{},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},"
                "{:.4f}\n",
                r.frame, animation.frame_time(r.frame), r.update_ms, int(r.update_on_worker),
                r.apply_ms, r.wait_ms, r.draw_ms, r.frame_ms, r.overlap_ms, r.critical_cpu_ms(),
                r.gpu.total_ms());
        });
    const frame::Frame last = renderer.read_back();
    const std::string stem =
        fmt::format("{}.{}.{}", scene.name, method.name(), frame::to_string(mode));
    outputs.add_text(stem + ".frames.csv", csv);
    outputs.add(stem + ".last.png", [&](const std::filesystem::path& path) {
        write_png(last.display_srgb8, options.width, options.height, path);
    });
    fmt::print(
        "{} {} {} ({} frames, {}x{}, {}): median frame {:.2f} ms, CPU critical path {:.2f} "
        "ms, update {:.2f} ms, GPU {:.2f} ms, overlap {:.2f} ms\n",
        scene.name, method.name(), frame::to_string(mode), frames, options.width, options.height,
        context.renderer,
        median_after_first(records, [](const frame::FrameRecord& r) { return r.frame_ms; }),
        median_after_first(records,
                           [](const frame::FrameRecord& r) { return r.critical_cpu_ms(); }),
        median_after_first(records, [](const frame::FrameRecord& r) { return r.update_ms; }),
        median_after_first(records, [](const frame::FrameRecord& r) { return r.gpu.total_ms(); }),
        median_after_first(records, [](const frame::FrameRecord& r) { return r.overlap_ms; }));
}

int run_animate(const AnimateArguments& args) {
    frame::RenderOptions options;
    parse_size(args.size, options.width, options.height);
    options.shadow = args.shadow_settings();
    std::vector<frame::FrameMode> modes;
    if (args.mode == "both") {
        modes = {frame::FrameMode::serial, frame::FrameMode::pipelined};
    } else {
        modes = {frame::parse_frame_mode(args.mode)};
    }
    const std::unique_ptr<frame::VolumeMethod> method = methods::create_configured_method(
        args.method, options.shadow, methods::parse_settings(args.settings));
    const Scene scene = load_scene(args.scene, SceneSearchPaths::defaults());
    if (!scene.animation) {
        fail(
            "{}: the scene has no [animation] to play (scenes/animation.h; animated scenes: "
            "toplight-orbit, parallel-walk, multiple-moving)",
            args.scene);
    }
    const Animation& animation = *scene.animation;
    const int available = animation.frame_count();
    if (args.frames > available) {
        fail("--frames {}: the animation has {} frames ({} s to {} s at {} fps)", args.frames,
             available, animation.start, animation.end, animation.fps);
    }
    const int frames = args.frames > 0 ? args.frames : available;

    const auto platform = gl::create_headless_platform();
    const gl::ContextInfo context = platform->info();
    OutputFiles outputs(args.out);
    for (const frame::FrameMode mode : modes) {
        play_mode(scene, *method, options, mode, args.warmup, frames, context, outputs);
    }
    outputs.commit();
    fmt::print("  -> {}/{}.{}.<mode>.{{frames.csv,last.png}}\n", args.out, scene.name,
               method->name());
    return 0;
}

}  // namespace

Command add_animate_command(CLI::App& app) {
    CLI::App* command = app.add_subcommand(
        "animate",
        "Play a scene's [animation] with one method, serial or pipelined (the CPU update of frame "
        "k+1 beside the GPU's frame k): DIR/<scene>.<method>.<mode>.frames.csv");
    auto args = std::make_shared<AnimateArguments>();
    args->method = "beamtree";
    add_common_options(*command, *args,
                       Common::scene | Common::method | Common::size | Common::out |
                           Common::shadow | Common::warmup);
    command->add_option("--mode", args->mode, "serial, pipelined or both")
        ->check(CLI::IsMember({"serial", "pipelined", "both"}))
        ->capture_default_str();
    command->add_option("--frames", args->frames, "Frames to play (0: the whole animation)")
        ->check(CLI::Range(0, 1000000))
        ->capture_default_str();
    return [args] { return run_animate(*args); };
}

}  // namespace sl::app
