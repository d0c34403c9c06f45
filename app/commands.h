#pragma once
// The subcommands of the `shaftlab` executable. Each registers its options on the CLI11 app and
// returns the function that runs it once the command line is parsed.

#include <CLI/CLI.hpp>

#include <chrono>
#include <functional>
#include <optional>
#include <string>

#include "core/statistics.h"
#include "scenes/scene.h"

namespace sl::app {

using Command = std::function<int()>;

Command add_render_command(CLI::App& app);
Command add_animate_command(CLI::App& app);
Command add_scenes_command(CLI::App& app);
Command add_gl_info_command(CLI::App& app);
Command add_regions_command(CLI::App& app);
Command add_methods_command(CLI::App& app);
Command add_compare_command(CLI::App& app);
Command add_bench_command(CLI::App& app);
Command add_merge_command(CLI::App& app);
Command add_view_command(CLI::App& app);
Command add_ibl_command(CLI::App& app);
Command add_sss_command(CLI::App& app);

using Clock = std::chrono::steady_clock;

// Milliseconds of wall time since `start`, for the stage timings the commands report.
using sl::ms_since;

// The scene by name or file, at `time` of its [animation] when one is given (--time): the still
// frame of a moving scene. Throws sl::Error when the scene has no animation or the time is out of
// its range.
Scene load_scene_at(const std::string& name, const std::optional<double>& time);
// Adds --time to a command that loads a scene.
void add_time_option(CLI::App& command, std::optional<double>& time);

// "WxH" with both positive; throws sl::Error otherwise.
// Parses WIDTHxHEIGHT; errors name `option`.
void parse_size(const std::string& text, int& width, int& height, const char* option = "--size");

}  // namespace sl::app
