#pragma once
// The subcommands of the `shaftlab` executable. Each registers its options on the CLI11 app and
// returns the function that runs it once the command line is parsed.

#include <CLI/CLI.hpp>

#include <chrono>
#include <functional>
#include <optional>
#include <string>

#include "app/options.h"
#include "core/statistics.h"

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

}  // namespace sl::app
