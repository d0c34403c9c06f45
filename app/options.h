#pragma once
// The options the subcommands share, declared once: the scene (and --time into its animation),
// the method and its --set settings, the image size, the output directory, the shadow map, and
// the frames drawn before measuring. A command's arguments derive from CommonOptions, set their
// own defaults, and add the options they take.

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

#include "frame/volume_method.h"
#include "scenes/scene.h"

namespace sl::app {

struct CommonOptions {
    std::string scene;
    std::optional<double> time;  // seconds into the scene's [animation]
    std::string method = "none";
    std::vector<std::string> settings;  // NAME=VALUE for the method's parameters
    std::string size = "640x360";
    std::string out = "out";
    std::string shadow = "pcf";
    int pcf_radius = 1;
    int shadow_map_size = 2048;
    int warmup = 2;

    // The run's shadow map (--shadow, --pcf-radius, --shadow-map-size).
    frame::ShadowSettings shadow_settings() const;
};

// Which of the common options a command takes.
enum class Common : unsigned {
    scene = 1u << 0,   // --scene (required)
    time = 1u << 1,    // --time
    method = 1u << 2,  // --method and --set
    size = 1u << 3,    // --size
    out = 1u << 4,     // --out
    shadow = 1u << 5,  // --shadow, --pcf-radius, --shadow-map-size
    warmup = 1u << 6,  // --warmup
};
constexpr Common operator|(Common a, Common b) {
    return Common(unsigned(a) | unsigned(b));
}
constexpr bool operator&(Common a, Common b) {
    return (unsigned(a) & unsigned(b)) != 0;
}

// Adds the chosen options to `command`, bound to `options` (whose current values are the
// defaults shown by --help).
void add_common_options(CLI::App& command, CommonOptions& options, Common which);

// The scene by name or file, at `time` of its [animation] when one is given (--time): the still
// frame of a moving scene. Throws sl::Error when the scene has no animation or the time is out of
// its range.
Scene load_scene_at(const std::string& name, const std::optional<double>& time);

// Parses WIDTHxHEIGHT with both sides in 1..16384; errors name `option`.
void parse_size(const std::string& text, int& width, int& height, const char* option = "--size");

}  // namespace sl::app
