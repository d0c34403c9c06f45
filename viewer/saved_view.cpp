#include "viewer/saved_view.h"

#include <fmt/format.h>

#include <ctime>

#include "core/error.h"
#include "core/output_files.h"
#include "scenes/scene_file.h"
#include "scenes/toml_reader.h"

namespace sl::viewer {

namespace fs = std::filesystem;

SavedView save_view_as_experiment(const fs::path& experiment, const Scene& scene,
                                  const std::string& opened, const frame::VolumeMethod& method,
                                  int width, int height, const frame::ShadowSettings& shadow) {
    if (experiment.extension() != ".toml") {
        fail("{}: an experiment file must end in .toml", experiment.string());
    }
    const fs::path folder = fs::absolute(experiment).parent_path();
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (!fs::is_directory(folder, ec)) {
        fail("{}: cannot create the folder for the experiment", folder.string());
    }
    const std::string stem = experiment.stem().string();
    const std::string scene_file = stem + ".scene.toml";

    // The base as the scene file will find it: names stay names, files become relative to it.
    std::string base = opened;
    if (!opened.starts_with("multiple:") &&
        (fs::path(opened).extension() == ".toml" || opened.find('/') != std::string::npos)) {
        base = fs::relative(fs::absolute(opened), folder, ec).generic_string();
        if (ec || base.empty()) {
            base = fs::absolute(opened).generic_string();
        }
    }

    std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof(date), "%Y-%m-%d %H:%M", std::localtime(&now));
    std::string text = fmt::format(
        "# Saved by `shaftlab view` on {}: {} seen with {} at {}x{}.\n"
        "# Run it with `shaftlab bench {}`.\n\n",
        date, scene.name, method.name(), width, height, experiment.filename().string());
    text += fmt::format("name = {}\n", toml_quoted(stem));
    text += fmt::format("description = {}\n",
                        toml_quoted(fmt::format("The view of {} saved from the viewer: {} "
                                                "with its parameters as set there.",
                                                opened, method.name())));
    text += "out = \"out/{name}\"\n\n";
    text += "[protocol]\nwarmup = 2\nframes = 10\n\n";
    text +=
        fmt::format("[render]\nshadow = {}\nshadow_map_size = {}\npcf_radius = {}\n\n",
                    toml_quoted(frame::to_string(shadow.filter)), shadow.map_size, shadow.radius);
    text += fmt::format("[sweep]\nscenes = [{}]\nmethods = [{}]\nsizes = [\"{}x{}\"]\n",
                        toml_quoted(scene_file), toml_quoted(method.name()), width, height);
    if (!method.parameters().empty()) {
        text += fmt::format("\n[sweep.params.{}]\n", method.name());
        for (const frame::Parameter& p : method.parameters()) {
            // Numbers and flags as TOML numbers and booleans, choices as their names.
            const std::string value =
                p.type == frame::Parameter::Type::choice ? toml_quoted(p.text()) : p.text();
            text += fmt::format("{} = {}\n", p.name, value);
        }
    }
    text += "\n[reference]\nmethod = \"reference\"\n";

    const std::string scene_name = fmt::format("{} (saved view)", scene.name);
    OutputFiles outputs(folder);
    outputs.add_text(scene_file, scene_view_toml(scene, base, scene_name));
    outputs.add_text(experiment.filename().string(), text);
    outputs.commit();
    return {folder / experiment.filename(), folder / scene_file};
}

}  // namespace sl::viewer
