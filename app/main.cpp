// shaftlab: a testbed for real-time volumetric light shafts. See docs/commands.md for the
// subcommands.

#include <cstdio>
#include <exception>
#include <map>

#include "app/commands.h"
#include "core/error.h"
#include "core/text.h"

int main(int argc, char** argv) {
    CLI::App app{"shaftlab: a testbed for real-time volumetric light shafts"};
    app.require_subcommand(1);
    std::map<CLI::App*, sl::app::Command> commands;
    auto add = [&](sl::app::Command (*make)(CLI::App&)) {
        const size_t before = app.get_subcommands({}).size();
        sl::app::Command command = make(app);
        commands[app.get_subcommands({})[before]] = std::move(command);
    };
    add(sl::app::add_render_command);
    add(sl::app::add_animate_command);
    add(sl::app::add_regions_command);
    add(sl::app::add_scenes_command);
    add(sl::app::add_methods_command);
    add(sl::app::add_compare_command);
    add(sl::app::add_bench_command);
    add(sl::app::add_merge_command);
    add(sl::app::add_view_command);
    add(sl::app::add_ibl_command);
    add(sl::app::add_sss_command);
    add(sl::app::add_gl_info_command);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "shaftlab: error: %s (see --help)\n", sl::printable(e.what()).c_str());
        return 2;
    }
    try {
        for (const auto& [subcommand, command] : commands) {
            if (subcommand->parsed()) {
                return command();
            }
        }
    } catch (const sl::Error& e) {
        std::fprintf(stderr, "shaftlab: error: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "shaftlab: error: %s\n", sl::printable(e.what()).c_str());
        return 1;
    }
    return 1;
}
