// `shaftlab bench EXPERIMENT.toml` and `shaftlab merge`: the harness's command line
// (experiments/bench.h has the outputs).

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iostream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "core/error.h"
#include "core/output_files.h"
#include "experiments/baseline.h"
#include "experiments/bench.h"
#include "experiments/report.h"
#include "experiments/tables.h"
#include "scenes/toml_reader.h"

namespace sl::app {

namespace {

struct BenchArguments {
    std::string experiment;
    // A quick comparison without a file: one scene, methods, one size.
    std::string scene;
    std::vector<std::string> methods;
    std::string size = "320x180";
    std::string out;
    std::vector<std::string> presets;
    std::vector<std::string> settings;
    std::string shard = "1/1";
    std::string baseline;  // a committed run of the same experiment to print ratios against
    bool list = false;
    // Process isolation's child: one cell and repetition.
    std::string cell;
    int rep = 0;
};

std::string self_executable() {
    std::error_code ec;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) {
        fail("cannot find this executable (/proc/self/exe): {}", ec.message());
    }
    return self.string();
}

// The experiment of `bench --scene S --methods a,b --size WxH`: those cells against the reference
// at the default protocol, as a file would give them (validated the same way).
std::string quick_experiment(const BenchArguments& args) {
    auto quoted_list = [](const std::vector<std::string>& items) {
        std::string list;
        for (const std::string& item : items) {
            list += (list.empty() ? "" : ", ") + toml_quoted(item);
        }
        return "[" + list + "]";
    };
    return fmt::format(
        "name = \"quick\"\n"
        "description = \"A quick comparison from the command line: {} on {} at {}.\"\n"
        "[protocol]\nwarmup = 2\nframes = 6\n"
        "[sweep]\nscenes = {}\nmethods = {}\nsizes = {}\n"
        "[reference]\nmethod = \"reference\"\n",
        fmt::join(args.methods, ", "), args.scene, args.size, quoted_list({args.scene}),
        quoted_list(args.methods), quoted_list({args.size}));
}

int run_bench_command(const BenchArguments& args) {
    const bool quick = !args.scene.empty() || !args.methods.empty();
    if (quick == !args.experiment.empty()) {
        fail(
            "bench: give an experiment file, or --scene and --methods (a quick comparison), not "
            "both");
    }
    if (quick && (args.scene.empty() || args.methods.empty())) {
        fail("bench: a quick comparison needs both --scene and --methods");
    }
    const experiments::Experiment experiment =
        quick ? experiments::parse_experiment(quick_experiment(args), "bench --scene", args.presets,
                                              args.settings)
              : experiments::load_experiment(args.experiment, args.presets, args.settings);
    const std::filesystem::path out =
        args.out.empty() ? experiment.output_directory() : std::filesystem::path(args.out);
    if (!args.cell.empty()) {
        nlohmann::json cell;
        try {
            cell = nlohmann::json::parse(args.cell);
        } catch (const nlohmann::json::exception& e) {
            fail("--cell: not JSON: {}", e.what());
        }
        experiments::run_cell(experiment, out, cell, args.rep);
        return 0;
    }
    if (args.list) {
        const auto cells = experiment.cells();
        for (const experiments::Cell& cell : cells) {
            fmt::print("{}\n", cell.id());
        }
        fmt::print(stderr, "{}: {} cells × {} repetition(s)\n", experiment.name, cells.size(),
                   experiment.protocol.repetitions);
        return 0;
    }
    experiments::BenchOptions options;
    options.out = out;
    options.shard = experiments::parse_shard(args.shard);
    options.relaunch = {self_executable(), "bench"};
    if (quick) {
        options.relaunch.insert(
            options.relaunch.end(),
            {"--scene", args.scene, "--methods", fmt::format("{}", fmt::join(args.methods, ",")),
             "--size", args.size});
    } else {
        options.relaunch.push_back(args.experiment);
    }
    options.relaunch.insert(options.relaunch.end(), {"--out", out.string()});
    for (const std::string& preset : args.presets) {
        options.relaunch.insert(options.relaunch.end(), {"--preset", preset});
    }
    for (const std::string& setting : args.settings) {
        options.relaunch.insert(options.relaunch.end(), {"--set", setting});
    }
    if (!args.baseline.empty() && !std::filesystem::is_directory(args.baseline)) {
        fail("--baseline {}: not a directory", quote(args.baseline));
    }
    const int failed = experiments::run_bench(experiment, options);
    std::ifstream table(out / "table.md");
    std::cout << table.rdbuf() << std::flush;
    if (!args.baseline.empty()) {
        const std::string comparison =
            experiments::baseline_comparison(experiment, out, args.baseline);
        OutputFiles files(out);
        files.add_text("comparison.md", comparison);
        files.commit();
        std::cout << "\n" << comparison << std::flush;
    }
    fmt::print(stderr, "bench: results.csv, summary.json, table.md, env.json{} in {}\n",
               experiment.plots ? ", plots/" : "", out.string());
    return failed ? 1 : 0;
}

}  // namespace

Command add_bench_command(CLI::App& app) {
    CLI::App* command = app.add_subcommand(
        "bench",
        "Run an experiment (TOML): every cell's timings and error into DIR/results.csv, "
        "table.md, env.json, plots/, images/; resumes where a previous run stopped");
    auto args = std::make_shared<BenchArguments>();
    command->add_option("experiment", args->experiment,
                        "Experiment file (experiments/*.toml); or a quick comparison with "
                        "--scene and --methods");
    command->add_option("--scene", args->scene,
                        "Quick comparison: the scene (a name or a .toml file), no experiment file");
    command->add_option("--methods", args->methods, "Quick comparison: the methods, a,b,c")
        ->delimiter(',');
    command->add_option("--size", args->size, "Quick comparison: the image size, WxH")
        ->capture_default_str();
    command->add_option("--out", args->out,
                        "Output directory (default: the experiment's `out`, out/{name}, "
                        "git-ignored; committed runs go to results/NAME with --out)");
    command->add_option("--preset", args->presets, "Apply a preset of the file (repeatable)");
    command->add_option("--set", args->settings,
                        "Override a value, KEY.PATH=VALUE in TOML syntax, e.g. protocol.frames=3 "
                        "or sweep.sizes='[\"64x64\"]' (repeatable)");
    command
        ->add_option("--shard", args->shard,
                     "Run every n-th cell only, i/n (1 <= i <= n); join with `shaftlab merge`")
        ->capture_default_str();
    command->add_option("--baseline", args->baseline,
                        "After the run, print and write DIR/comparison.md: each cell's FPS here "
                        "beside this run of the same experiment (e.g. results/default: the "
                        "committed machine's), as ratios");
    command->add_flag("--list", args->list, "Print the cells of the sweep and exit");
    command->add_option("--cell", args->cell)->group("");  // process isolation's child
    command->add_option("--rep", args->rep)->group("");
    return [args] { return run_bench_command(*args); };
}

Command add_merge_command(CLI::App& app) {
    CLI::App* command = app.add_subcommand(
        "merge", "Join the output directories of `bench --shard` runs and write the summary");
    auto directories = std::make_shared<std::vector<std::string>>();
    auto out = std::make_shared<std::string>();
    command->add_option("shards", *directories, "Shard output directories")->required();
    command->add_option("--out", *out, "Merged output directory")->required();
    return [directories, out] {
        std::vector<std::filesystem::path> shards(directories->begin(), directories->end());
        experiments::merge_shards(shards, *out);
        std::ifstream table(std::filesystem::path(*out) / "table.md");
        std::cout << table.rdbuf() << std::flush;
        return 0;
    };
}

}  // namespace sl::app
