// `shaftlab view`: the interactive viewer (viewer/viewer.h), or its scripted mode for tests and
// demos (--frames N --screenshot FILE, with a camera/light path).

#include "app/commands.h"
#include "core/error.h"
#include "frame/volume_method.h"
#include "viewer/viewer.h"

namespace sl::app {

namespace {

struct ViewArguments : CommonOptions {
    viewer::ViewerOptions options;
    bool no_ui = false;
};

int run_view(ViewArguments& args) {
    viewer::ViewerOptions& options = args.options;
    parse_size(args.size, options.width, options.height);
    options.scene = args.scene;
    options.method = args.method;
    options.settings = args.settings;
    options.shadow = args.shadow_settings();
    options.ui = !args.no_ui;
    const bool scripted_output = !options.screenshot.empty() || !options.in_scattering.empty() ||
                                 !options.path.empty() || options.orbit_degrees != 0.0f;
    if (scripted_output && options.frames == 0) {
        fail("--screenshot, --in-scattering, --path and --orbit need --frames N (scripted mode)");
    }
    return viewer::run_viewer(options);
}

}  // namespace

Command add_view_command(CLI::App& app) {
    CLI::App* command = app.add_subcommand(
        "view",
        "Interactive viewer: regions, methods and parameters live, buffers, timings, error view");
    auto args = std::make_shared<ViewArguments>();
    viewer::ViewerOptions& o = args->options;
    args->size = "1280x720";
    args->method = o.method;
    add_common_options(*command, *args,
                       Common::scene | Common::method | Common::size | Common::shadow);
    std::string layers;
    for (const std::string& name : viewer::layer_names())
        layers += (layers.empty() ? "" : ", ") + name;
    command->add_option("--light", o.light,
                        "Whose regions the overlays show: a spot light or point-light face, "
                        "0-based, as `regions --light N`");
    command->add_option("--layers", o.layers, "Layers shown at start, comma separated: " + layers)
        ->delimiter(',');
    command->add_option("--preview", o.preview,
                        "The buffer previewer's texture at start (by name)");
    command
        ->add_option(
            "--error-scale", o.error_scale,
            "Error view: full scale of the heat map, in units of the reference's RMS pixel")
        ->capture_default_str();
    command->add_flag("--no-ui", args->no_ui, "Hide the panels (F1 toggles them)");
    command->add_flag("--hidden", o.hidden, "No visible window (still needs a display)");
    command->add_option("--frames", o.frames, "Scripted mode: draw N frames, write outputs, exit")
        ->check(CLI::Range(1, 1000000));
    command->add_option("--path", o.path, "Scripted mode: camera/light path (TOML [[key]]s)");
    command->add_option("--orbit", o.orbit_degrees,
                        "Scripted mode: orbit the camera this many degrees over the frames");
    command->add_option("--screenshot", o.screenshot, "Scripted mode: PNG of the last frame");
    command->add_option("--in-scattering", o.in_scattering,
                        "Scripted mode: EXR of the last frame's I_s");
    command->add_option("--save-experiment", o.save_experiment,
                        "Scripted mode: save the last view as an experiment (FILE.toml and "
                        "FILE.scene.toml); interactively, the default file of the Save panel");
    return [args] { return run_view(*args); };
}

}  // namespace sl::app
