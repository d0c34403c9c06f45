// The harness: experiment files expand into the right cells, overrides and presets
// apply, bad files give one clear error, the equal-error bisection finds the cheapest parameter,
// and `shaftlab bench` runs smoke.toml end to end, resumes after a kill, shards and merges.

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include "core/error.h"
#include "core/statistics.h"
#include "experiments/baseline.h"
#include "experiments/bench.h"
#include "experiments/equal_error.h"
#include "experiments/equal_error_report.h"
#include "experiments/experiment.h"
#include "experiments/report.h"
#include "experiments/tables.h"

#include "tests/gl_support.h"

extern char** environ;

namespace sl::test {
namespace {

namespace fs = std::filesystem;
using experiments::Cell;
using experiments::Experiment;
using experiments::parse_experiment;

const char* const kSweep = R"(
name = "t"
[sweep]
scenes = ["toplight", "parallel"]
methods = ["beamtree", "planes", "march"]
sizes = ["32x16", 64]
[sweep.params]
dz = [0.5, 0.25]
[sweep.params.march]
samples = [4, 8]
)";

std::string read_file(const fs::path& path) {
    std::ifstream file(path, std::ios::binary);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

// The message of the sl::Error that parsing `text` throws ("" when it parses).
std::string parse_error(const std::string& text, const std::vector<std::string>& overrides = {}) {
    try {
        parse_experiment(text, "bad.toml", {}, overrides);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

// Rows of a CSV file (header first), split at commas outside quotes.
std::vector<std::vector<std::string>> read_csv(const fs::path& path) {
    std::vector<std::vector<std::string>> rows;
    std::ifstream file(path);
    for (std::string line; std::getline(file, line);) {
        std::vector<std::string> fields(1);
        bool quoted = false;
        for (const char c : line) {
            if (c == '"') {
                quoted = !quoted;
            } else if (c == ',' && !quoted) {
                fields.emplace_back();
            } else {
                fields.back() += c;
            }
        }
        rows.push_back(std::move(fields));
    }
    return rows;
}

TEST(Experiment, SweepIsTheCartesianProductOfWhatEachMethodDeclares) {
    const Experiment x = parse_experiment(kSweep, "t.toml");
    const std::vector<Cell> cells = x.cells();
    // 2 scenes × 2 sizes × (beamtree 1 + planes 2 dz + march 2 samples).
    ASSERT_EQ(cells.size(), 20u);
    std::set<std::string> ids;
    for (const Cell& cell : cells) {
        ids.insert(cell.id());
        if (cell.method == "beamtree") {
            EXPECT_TRUE(cell.settings.empty()) << cell.id();
        } else if (cell.method == "planes") {
            EXPECT_TRUE(cell.setting("dz") && !cell.setting("samples")) << cell.id();
        } else {
            EXPECT_TRUE(cell.setting("samples") && !cell.setting("dz")) << cell.id();
        }
    }
    EXPECT_EQ(ids.size(), cells.size()) << "cell ids must be unique";
    EXPECT_EQ(cells.front().size(), "32x16");
    EXPECT_EQ(cells[3].size(), "32x16");
    EXPECT_EQ(cells[5].size(), "64x64") << "a bare number is a square size";
}

TEST(Experiment, ExclusionsRemoveOnlyCellsMatchingEveryKey) {
    const std::string text = std::string(kSweep) + R"(
[[exclude]]
dz = 0.25
[[exclude]]
method = "march"
scene = "parallel"
size = ["64x64"]
)";
    const std::vector<Cell> cells = parse_experiment(text, "t.toml").cells();
    // dz 0.25 removes 4 planes cells (beamtree has no dz and stays); the second removes the 2
    // march cells of parallel at 64².
    EXPECT_EQ(cells.size(), 14u);
    for (const Cell& cell : cells) {
        EXPECT_FALSE(cell.setting("dz") && *cell.setting("dz") == "0.25") << cell.id();
        EXPECT_FALSE(cell.method == "march" && cell.scene == "parallel" && cell.width == 64);
    }
}

TEST(Experiment, SetAndPresetsOverrideValuesAndAreRecorded) {
    const std::string text = std::string(kSweep) + R"(
[protocol]
frames = 3
[presets.small]
"sweep.sizes" = ["8x4"]
protocol.warmup = 0
)";
    const Experiment x = parse_experiment(text, "t.toml", {"small"},
                                          {"protocol.frames=7", "sweep.scenes=toplight",
                                           "sweep.params.dz=[0.125]", "render.shadow=vsm"});
    EXPECT_EQ(x.protocol.frames, 7);
    EXPECT_EQ(x.protocol.warmup, 0);
    EXPECT_EQ(x.render.shadow, "vsm") << "a bare word is a string";
    ASSERT_EQ(x.scenes, std::vector<std::string>{"toplight"});
    ASSERT_EQ(x.sizes.size(), 1u);
    EXPECT_EQ(x.sizes[0], std::pair(8, 4));
    EXPECT_EQ(x.cells().size(), 1u + 1u + 2u);
    EXPECT_EQ(x.overrides.size(), 5u);
    EXPECT_NE(x.effective.find("frames = 7"), std::string::npos) << x.effective;
    EXPECT_NE(parse_error(text, {"protocol.frames=0"}).find("frames"), std::string::npos);
    try {
        parse_experiment(text, "t.toml", {"large"});
        FAIL() << "an unknown preset must be an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("small"), std::string::npos) << e.what();
    }
}

TEST(Experiment, BadFilesGiveOneErrorNamingTheFileAndKey) {
    const std::string base =
        "name = \"t\"\n[sweep]\nscenes = [\"toplight\"]\n"
        "methods = [\"planes\"]\nsizes = [\"32x16\"]\n";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {base + "[protocol]\nfraems = 3\n", "fraems: unknown key"},
        {base + "colour = 1\n", "colour: unknown key"},
        {base + "[sweep.params]\ndz = -1\n", "dz"},
        {base + "[sweep.params]\nsamplez = 8\n", "samplez"},
        {base + "[sweep.params.plains]\ndz = 0.5\n", "plains"},
        {base + "[sweep.params.planes]\nsamples = 8\n", "samples"},
        {base + "[[exclude]]\nfoo = 1\n", "foo"},
        {base + "[protocol]\nisolation = \"thread\"\n", "isolation"},
        {base + "[protocol]\nkind = \"animation\"\npaired = true\n",
         "paired: only for kind = \"still\""},
        {base + "[protocol]\npaired = 1\n", "paired: expected true or false"},
        {base + "[table]\nmetric = \"ssim\"\n", "metric"},
        {base + "[equal_error]\ntargets = [2.0]\n", "targets"},
        {base + "[equal_error]\ntargets = [0.01]\nbaselines = [\"march\"]\n", "baselines"},
        {"name = \"t\"\n[sweep]\nscenes = [\"nowhere\"]\nmethods = [\"planes\"]\n"
         "sizes = [\"32x16\"]\n",
         "nowhere"},
        {"name = \"t\"\n[sweep]\nscenes = [\"toplight\"]\nmethods = [\"plains\"]\n"
         "sizes = [\"32x16\"]\n",
         "plains"},
        {"name = \"t\"\n[sweep]\nscenes = [\"toplight\"]\nmethods = [\"planes\"]\n"
         "sizes = [\"32by16\"]\n",
         "32by16"},
        {"name = \"t\"\n[sweep]\nscenes = []\nmethods = [\"planes\"]\nsizes = [1]\n", "scenes"},
        {"name = \"t\"\n", "sweep"},
        {"name = \"t\"\n[sweep\n", "bad.toml:2"},
    };
    for (const auto& [text, expected] : cases) {
        const std::string message = parse_error(text);
        EXPECT_NE(message.find("bad.toml"), std::string::npos) << text << "\n=> " << message;
        EXPECT_NE(message.find(expected), std::string::npos) << text << "\n=> " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    EXPECT_NE(parse_error(base, {"protocol.frmes=2"}).find("frmes: unknown key"),
              std::string::npos);
    EXPECT_NE(parse_error(base, {"protocol.frmes=2"}).find("command line"), std::string::npos);
    // A table row that is neither scene, size nor a parameter must be refused, not dropped.
    EXPECT_NE(parse_error(base, {"table.rows=[\"nope\"]"})
                  .find("[table] rows: unknown row 'nope': expected scene, size, a scene "
                        "variation or a method's parameter"),
              std::string::npos);
}

TEST(Experiment, PercentilesInterpolateBetweenOrderStatistics) {
    EXPECT_DOUBLE_EQ(sl::median({3.0, 1.0, 2.0}), 2.0);
    EXPECT_DOUBLE_EQ(sl::median({4.0, 1.0, 2.0, 3.0}), 2.5);
    EXPECT_DOUBLE_EQ(sl::percentile({0.0, 10.0}, 5.0), 0.5);
    EXPECT_DOUBLE_EQ(sl::percentile({0.0, 10.0, 20.0}, 95.0), 19.0);
}

// The bisection against synthetic monotone error models: the value it returns reaches the
// target, and one step cheaper (within the tolerance) does not.
TEST(EqualError, BisectionFindsTheCheapestParameterReachingTheTarget) {
    const std::string text = R"(
name = "t"
[sweep]
scenes = ["toplight"]
methods = ["planes", "march", "beamtree"]
sizes = ["32x16"]
[equal_error]
targets = [0.01]
baselines = ["planes"]
tolerance = 0.02
[equal_error.search.march]
parameter = "samples"
cheap = 2
expensive = 512
)";
    const Experiment x = parse_experiment(text, "t.toml");
    const std::vector<Cell> groups = experiments::search_groups(x);
    ASSERT_EQ(groups.size(), 3u);
    int measured = 0;
    const experiments::CellMeasure model =
        [&](const Cell& cell) -> std::optional<experiments::CellSummary> {
        ++measured;
        if (cell.method == "planes") {  // error ∝ dz, cost ∝ 1/dz
            const double dz = std::stod(*cell.setting("dz"));
            return experiments::CellSummary{0.04 * dz, 1.0 / dz};
        }
        if (cell.method == "march") {  // error ∝ 1/N, cost ∝ N
            const double n = std::stod(*cell.setting("samples"));
            return experiments::CellSummary{0.5 / n, n};
        }
        return experiments::CellSummary{0.02, 3.0};  // beamtree: fixed
    };
    const auto planes = experiments::search_equal_error(x, groups[0], 0.01, model);
    ASSERT_TRUE(planes.reached && planes.complete);
    EXPECT_EQ(planes.parameter, "dz");
    const double dz = std::stod(planes.value);
    EXPECT_LE(0.04 * dz, 0.01);
    EXPECT_GT(dz, 0.25 / 1.03) << "the cheapest dz reaching 1% is 0.25";
    EXPECT_LE(planes.probes.size(), 12u);

    const auto march = experiments::search_equal_error(x, groups[1], 0.01, model);
    ASSERT_TRUE(march.reached);
    EXPECT_EQ(march.value, "50") << "smallest N with 0.5/N <= 1%";

    const auto beamtree = experiments::search_equal_error(x, groups[2], 0.01, model);
    EXPECT_TRUE(beamtree.parameter.empty());
    EXPECT_FALSE(beamtree.reached) << "a fixed 2% never reaches 1%";

    const auto unreachable = experiments::search_equal_error(x, groups[1], 1e-4, model);
    EXPECT_FALSE(unreachable.reached);
    EXPECT_EQ(unreachable.value, "512") << "reports the most expensive value tried";
    EXPECT_GT(measured, 0);
}

// The equal-error headline faces the best region method with the cheapest method without regions
// at the target (here epipolar, not march) and with the plain method (march), names each row's
// baselines, and measures the volume cost as the frame time less `none`'s with its interval,
// flagging a method whose timer lies outside it.
TEST(Report, EqualErrorHeadlineFacesTheBestMethodWithoutRegionsAndThePlainOne) {
    const Experiment x = parse_experiment(R"(
name = "t"
[sweep]
scenes = ["toplight"]
methods = ["march", "epipolar", "beamtree", "none"]
sizes = ["32x16"]
[reference]
method = "reference"
[equal_error]
targets = [0.01]
baselines = ["march", "epipolar"]
plain = "march"
tolerance = 0.02
[equal_error.search.march]
parameter = "samples"
cheap = 2
expensive = 512
[equal_error.search.epipolar]
parameter = "max_step"
cheap = 64
expensive = 1
)",
                                          "t.toml");
    // Frame times: none 100 ms; march 100 + N/4 (error 0.5/N: N = 50 reaches 1%, 112.5 ms);
    // epipolar 100 + 40/max_step (error max_step/800: 8 reaches 1%, 105 ms); beamtree 103 ms at
    // 0.5%, its timer 20 ms (outside its difference's interval [2.5, 3.5]).
    std::vector<experiments::StoredRow> rows;
    const auto add = [&](const Cell& cell, double ms, double error, double timer) {
        rows.push_back({cell,
                        0,
                        {{"frame_ms_median", ms},
                         {"frame_ms_samples", {ms - 0.25, ms, ms + 0.25}},
                         {"rel_rmse", error},
                         {"volume_cost_ms", timer}}});
    };
    for (const Cell& group : experiments::search_groups(x)) {
        if (group.method == "march") {
            for (int n = 2; n <= 512; ++n) {
                const double ms = 100.0 + n / 4.0;
                add(experiments::with_setting(group, "samples", std::to_string(n)), ms, 0.5 / n,
                    ms - 100.0);
            }
        } else if (group.method == "epipolar") {
            for (int step = 1; step <= 64; ++step) {
                const double ms = 100.0 + 40.0 / step;
                add(experiments::with_setting(group, "max_step", std::to_string(step)), ms,
                    step / 800.0, ms - 100.0);
            }
        } else if (group.method == "beamtree") {
            add(group, 103.0, 0.005, 20.0);
        } else {
            add(group, 100.0, 1.0, 0.0);
        }
    }
    const std::string md = experiments::equal_error_report(x, rows).first;
    EXPECT_NE(md.find("| toplight | 32x16 | samples=50:"), std::string::npos) << md;
    EXPECT_NE(md.find(" epipolar · epipolar |"), std::string::npos) << "row's baselines\n" << md;
    EXPECT_EQ(md.find("| none |"), std::string::npos) << "none is no column\n" << md;
    // beamtree's timer lies outside its difference's interval: no ratio by difference.
    EXPECT_NE(md.find("volume cost (frame − none) **beamtree** 3.0 ms [2.5–3.5]: against "
                      "**epipolar** 5.0 ms [4.5–5.5]: not resolved (beamtree's timer and "
                      "difference disagree); against **march** 12.5 ms [12.0–13.0]: not resolved"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("(Fixed passes: `none`'s frame 100.0 ms, its shadow map 0.0 ms.)"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| 1% | toplight | 32x16 | beamtree |  | 20.0 ms | 3.0 ms [2.5–3.5] | "
                      "**disagree** |"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| 1% | toplight | 32x16 | epipolar | max_step=8 | 5.0 ms | 5.0 ms "
                      "[4.5–5.5] | |"),
              std::string::npos)
        << md;
}

// Paired cells (harness.md, "Paired"): the volume cost by difference is the median of the
// pooled per-pair differences with their bootstrap interval, a ratio only where both intervals
// lie above zero and each timer inside its interval; an interval holding zero is not resolved.
TEST(Report, PairedDifferencesGiveARatioOnlyWhereTheyAreResolved) {
    const Experiment x = parse_experiment(R"(
name = "t"
[protocol]
paired = true
[sweep]
scenes = ["toplight"]
methods = ["epipolar", "beamtree", "none"]
sizes = ["32x16"]
[reference]
method = "reference"
[equal_error]
targets = [0.01]
baselines = ["epipolar"]
plain = "epipolar"
tolerance = 0.02
[equal_error.search.epipolar]
parameter = "max_step"
cheap = 64
expensive = 1
)",
                                          "t.toml");
    ASSERT_TRUE(x.protocol.paired);
    // Frames as in the test above; each paired cell's differences d - 0.25, d, d + 0.25 about its
    // frame less none's, its timer d. beamtree's differences: `spread` about 3 ms.
    auto report = [&](double spread) {
        std::vector<experiments::StoredRow> rows;
        const auto add = [&](const Cell& cell, double ms, double error, double d, double s) {
            nlohmann::ordered_json row = {{"frame_ms_median", ms},
                                          {"frame_ms_samples", {ms - 0.25, ms, ms + 0.25}},
                                          {"rel_rmse", error},
                                          {"volume_cost_ms", d}};
            if (cell.method != "none") {
                row["paired_difference_ms_samples"] = {d - s, d, d + s};
            }
            rows.push_back({cell, 0, row});
        };
        for (const Cell& group : experiments::search_groups(x)) {
            if (group.method == "epipolar") {
                for (int step = 1; step <= 64; ++step) {
                    const double ms = 100.0 + 40.0 / step;
                    add(experiments::with_setting(group, "max_step", std::to_string(step)), ms,
                        step / 800.0, ms - 100.0, 0.25);
                }
            } else if (group.method == "beamtree") {
                add(group, 103.0, 0.005, 3.0, spread);
            } else {
                add(group, 100.0, 1.0, 0.0, 0.0);
            }
        }
        return experiments::equal_error_report(x, rows).first;
    };
    const std::string resolved = report(0.25);
    EXPECT_NE(resolved.find("volume cost (frame − none, paired) **beamtree** 3.0 ms [2.8–3.2]: "
                            "×1.67 against **epipolar** 5.0 ms [4.8–5.2] (epipolar is the plain "
                            "method)."),
              std::string::npos)
        << resolved;
    const std::string noisy = report(4.0);
    EXPECT_NE(noisy.find("**beamtree** 3.0 ms [-1.0–7.0]: against **epipolar** 5.0 ms [4.8–5.2]: "
                         "not resolved (beamtree's interval holds zero)"),
              std::string::npos)
        << noisy;
}

TEST(Report, TableRepeatsParameterlessMethodsInEveryRowInListedOrder) {
    const Experiment x = parse_experiment(R"(
name = "t"
[sweep]
scenes = ["toplight"]
methods = ["beamtree", "planes"]
sizes = ["32x16"]
[sweep.params]
dz = [0.5, 0.1]
)",
                                          "t.toml");
    std::vector<experiments::StoredRow> rows;
    for (const Cell& cell : x.cells()) {
        const double ms = cell.method == "beamtree" ? 10.0 : std::stod(*cell.setting("dz")) * 40;
        rows.push_back(
            {cell,
             0,
             {{"frame_ms_median", ms}, {"frame_ms_samples", {ms, ms, ms}}, {"rel_rmse", 0.01}}});
    }
    const std::string table = experiments::sweep_table(x, rows);
    const size_t first = table.find(
        "| 0.5 | toplight | 32x16 | **100.0 [100.0–100.0]** (1.00%) | 50.0 [50.0–50.0] (1.00%) |");
    const size_t second = table.find(
        "| 0.1 | toplight | 32x16 | 100.0 [100.0–100.0] (1.00%) | **250.0 [250.0–250.0]** (1.00%) "
        "|");
    EXPECT_NE(first, std::string::npos) << table;
    EXPECT_NE(second, std::string::npos) << table;
    EXPECT_LT(first, second) << "dz rows in the file's order";
}

// A scene file in a sweep appears in the table by its stem ("toplight-hg"), not by its path.
TEST(Report, TableNamesSceneFilesByTheirStem) {
    const std::string file =
        std::string(SHAFTLAB_SOURCE_DIR) + "/experiments/toplight-hg.scene.toml";
    const Experiment x = parse_experiment(fmt::format(R"(
name = "t"
[sweep]
scenes = ["toplight", "{}"]
methods = ["beamtree"]
sizes = ["32x16"]
)",
                                                      file),
                                          "t.toml");
    std::vector<experiments::StoredRow> rows;
    for (const Cell& cell : x.cells()) {
        rows.push_back({cell, 0, {{"frame_ms_median", 10.0}, {"rel_rmse", 0.01}}});
    }
    const std::string table = experiments::sweep_table(x, rows);
    EXPECT_NE(table.find("| toplight-hg | 32x16 |"), std::string::npos) << table;
    EXPECT_EQ(table.find("experiments/"), std::string::npos) << table;
}

TEST(Bench, BadExperimentFileIsOneErrorAndWritesNothing) {
    TempDir dir;
    write_text(dir.path() / "bad.toml",
               "name = \"bad\"\n[sweep]\nscenes = [\"toplight\"]\n"
               "methods = [\"planes\"]\nsizes = [\"32x16\"]\nfoo = 1\n");
    const CommandResult run = run_shaftlab("bench " + (dir.path() / "bad.toml").string() +
                                           " --out " + (dir.path() / "out").string());
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_NE(run.output.find("foo: unknown key"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(dir.path() / "out"));
    EXPECT_NE(
        run_shaftlab("bench " + std::string(SHAFTLAB_SOURCE_DIR) +
                     "/experiments/smoke.toml --shard 3/2 --out " + (dir.path() / "out").string())
            .exit_code,
        0);
}

// [sweep.scene] sweeps variations of every scene (scenes/variations.h) for every method, named in
// the cells like parameters; an unknown variation or a value it does not take is one error that
// names the file, the key and what is allowed.
TEST(Experiment, SceneVariationsAreSweptForEveryMethodAndChecked) {
    const std::string text = R"(
name = "t"
[sweep]
scenes = ["sss-bunny"]
methods = ["none", "march"]
sizes = ["32x16"]
[sweep.scene]
sss_grid = ["8x8", "16x12"]
camera_distance = [1, 2]
[sweep.params.march]
samples = [4, 8]
)";
    const std::vector<Cell> cells = parse_experiment(text, "t.toml").cells();
    ASSERT_EQ(cells.size(), 4u + 8u);  // none: 2 x 2; march: 2 x 2 x 2
    EXPECT_NE(cells.front().id().find("sss_grid=8x8"), std::string::npos) << cells.front().id();
    EXPECT_NE(cells.front().id().find("camera_distance=1"), std::string::npos);
    const std::string unknown = parse_error(text, {"sweep.scene.sss_gird=\"8x8\""});
    EXPECT_NE(unknown.find("bad.toml"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("sss_gird' (did you mean 'sss_grid'?)"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("sss_grid, sss_model"), std::string::npos) << unknown;
    const std::string grid = parse_error(text, {"sweep.scene.sss_grid=\"8by8\""});
    EXPECT_NE(grid.find("NxM"), std::string::npos) << grid;
    const std::string distance = parse_error(text, {"sweep.scene.camera_distance=0"});
    EXPECT_NE(distance.find("camera_distance"), std::string::npos) << distance;
    const std::string model = parse_error(text, {"sweep.scene.sss_model=\"tripole\""});
    EXPECT_NE(model.find("dipole or multipole"), std::string::npos) << model;
}

// The splatting study (experiments/sss_splats.toml, Rohat's tables as presets) runs in the one
// harness: each grid is a cell of its own, measured on the scene the variation made (more grid
// samples for the larger grid), with the subsurface pass's GPU time in its row.
TEST(Bench, SceneVariationsChangeTheMeasuredScene) {
    TempDir dir;
    const std::string file = std::string(SHAFTLAB_SOURCE_DIR) + "/experiments/sss_splats.toml";
    const CommandResult run =
        run_shaftlab("bench " + file + " --preset tiny --out " + dir.path().string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const auto csv = read_csv(dir.path() / "results.csv");
    ASSERT_EQ(csv.size(), 3u);
    const auto column = [&](const std::string& name) {
        const auto at = std::find(csv[0].begin(), csv[0].end(), name);
        EXPECT_NE(at, csv[0].end()) << name;
        return size_t(at - csv[0].begin());
    };
    const size_t samples = column("sss_grid_samples"), subsurface = column("gpu_ms_subsurface");
    EXPECT_LT(std::stod(csv[1][samples]), std::stod(csv[2][samples]));
    EXPECT_GE(std::stod(csv[1][subsurface]), 0.0);
    EXPECT_NE(csv[1][column("params")].find("sss_grid=8x8"), std::string::npos);
    // A scene without translucent objects cannot take an sss_ variation: the cell fails, naming
    // why.
    const CommandResult wrong = run_shaftlab("bench " + file +
                                             " --preset tiny --set 'sweep.scenes=[\"toplight\"]' "
                                             "--out " +
                                             (dir.path() / "wrong").string());
    EXPECT_NE(wrong.exit_code, 0);
    EXPECT_NE(wrong.output.find("has no translucent object"), std::string::npos) << wrong.output;
}

// smoke.toml end to end: every output, every required column, one row per cell.
TEST(Bench, SmokeExperimentWritesEveryOutput) {
    TempDir dir;
    const std::string smoke = std::string(SHAFTLAB_SOURCE_DIR) + "/experiments/smoke.toml";
    const CommandResult run = run_shaftlab("bench " + smoke + " --out " + dir.path().string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const auto csv = read_csv(dir.path() / "results.csv");
    const Experiment x = experiments::load_experiment(smoke);
    ASSERT_EQ(csv.size(), 1 + x.cells().size());
    const std::vector<std::string>& header = csv[0];
    for (const char* column : {"scene",
                               "method",
                               "width",
                               "height",
                               "params",
                               "rep",
                               "frames",
                               "fps",
                               "frame_ms_median",
                               "frame_ms_p5",
                               "frame_ms_p95",
                               "gpu_ms_total",
                               "gpu_ms_volume",
                               "cpu_ms_prepare",
                               "rel_rmse",
                               "max_abs",
                               "psnr",
                               "ray_frac_lit",
                               "ray_frac_uncertain",
                               "ray_frac_unlit",
                               "volume_frac_lit",
                               "volume_frac_uncertain",
                               "volume_frac_unlit",
                               "beams",
                               "region_faces",
                               "samples_or_slices",
                               "image"}) {
        EXPECT_NE(std::find(header.begin(), header.end(), column), header.end()) << column;
    }
    auto column = [&](const std::string& name) {
        return size_t(std::find(header.begin(), header.end(), name) - header.begin());
    };
    std::set<std::string> cells;
    for (size_t r = 1; r < csv.size(); ++r) {
        ASSERT_EQ(csv[r].size(), header.size()) << "row " << r;
        cells.insert(csv[r][column("cell")]);
        const double fps = std::stod(csv[r][column("fps")]);
        const double error = std::stod(csv[r][column("rel_rmse")]);
        const double lit = std::stod(csv[r][column("ray_frac_lit")]);
        const double uncertain = std::stod(csv[r][column("ray_frac_uncertain")]);
        const double unlit = std::stod(csv[r][column("ray_frac_unlit")]);
        EXPECT_GT(fps, 0.0);
        EXPECT_TRUE(error >= 0.0 && error < 0.5) << csv[r][column("cell")] << " " << error;
        EXPECT_NEAR(lit + uncertain + unlit, 1.0, 1e-9);
        EXPECT_GT(lit, 0.5) << "most of these beams is lit";
        EXPECT_LE(std::stod(csv[r][column("frame_ms_p5")]),
                  std::stod(csv[r][column("frame_ms_p95")]));
        EXPECT_TRUE(fs::exists(dir.path() / csv[r][column("image")])) << csv[r][column("image")];
    }
    EXPECT_EQ(cells.size(), x.cells().size());
    const std::string table = read_file(dir.path() / "table.md");
    EXPECT_NE(table.find("| dz | scene | size | beamtree | planes | hybrid2 | march | hybrid3 |"),
              std::string::npos)
        << table;
    EXPECT_NE(run.output.find("| dz | scene | size |"), std::string::npos) << "printed";
    const auto env = nlohmann::json::parse(read_file(dir.path() / "env.json"));
    EXPECT_EQ(env["experiment"]["text"].get<std::string>(), read_file(smoke)) << "verbatim";
    for (const char* key : {"cpu", "gl", "compiler", "libraries", "git"}) {
        EXPECT_TRUE(env.contains(key)) << key;
    }
    EXPECT_FALSE(env["gl"]["renderer"].get<std::string>().empty());
    for (const char* plot : {"fps_vs_resolution_toplight.png", "error_vs_time_parallel.png"}) {
        EXPECT_GT(fs::file_size(dir.path() / "plots" / plot), 1000u) << plot;
    }
}

// Kill a run after some rows exist; the rerun keeps every finished row untouched (no cell
// measured twice) and completes the rest.
TEST(Bench, ResumeAfterKillLosesAndDuplicatesNothing) {
    TempDir dir;
    const std::string smoke = std::string(SHAFTLAB_SOURCE_DIR) + "/experiments/smoke.toml";
    const std::string out = (dir.path() / "out").string();
    std::vector<std::string> args = {SHAFTLAB_BINARY,      "bench", smoke,
                                     "--preset",           "tiny",  "--set",
                                     "protocol.frames=12", "--out", out};
    std::vector<char*> argv;
    for (std::string& a : args) {
        argv.push_back(a.data());
    }
    argv.push_back(nullptr);
    pid_t pid = 0;
    ASSERT_EQ(posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ), 0);
    auto rows = [&] {
        std::map<std::string, std::string> found;
        if (fs::is_directory(dir.path() / "out" / "cells")) {
            for (const auto& e : fs::directory_iterator(dir.path() / "out" / "cells")) {
                const std::string name = e.path().filename().string();
                if (!name.starts_with(".")) {
                    found[name] = read_file(e.path());
                }
            }
        }
        return found;
    };
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(3);
    while (rows().size() < 2 && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the run finished before it could be killed";
    const auto before = rows();
    const size_t total = experiments::load_experiment(smoke, {"tiny"}).cells().size();
    ASSERT_GE(before.size(), 2u);
    ASSERT_LT(before.size(), total);

    const CommandResult rerun =
        run_shaftlab("bench " + smoke + " --preset tiny --set protocol.frames=12 --out " + out);
    ASSERT_EQ(rerun.exit_code, 0) << rerun.output;
    const auto after = rows();
    EXPECT_EQ(after.size(), total);
    for (const auto& [name, text] : before) {
        ASSERT_TRUE(after.contains(name));
        EXPECT_EQ(after.at(name), text) << name << " was measured again";
    }
    const auto csv = read_csv(dir.path() / "out" / "results.csv");
    EXPECT_EQ(csv.size(), 1 + total);
    for (const auto& e : fs::directory_iterator(dir.path() / "out" / "cells")) {
        EXPECT_FALSE(e.path().filename().string().starts_with(".")) << "temporary left behind";
    }
    // Different overrides into the same directory are refused.
    EXPECT_NE(run_shaftlab("bench " + smoke + " --preset tiny --out " + out).exit_code, 0);
}

// Two shards cover the sweep between them, and merge joins them into one complete result.
TEST(Bench, ShardsMergeIntoTheWholeSweep) {
    TempDir dir;
    const std::string smoke = std::string(SHAFTLAB_SOURCE_DIR) + "/experiments/smoke.toml";
    const std::string common = "bench " + smoke + " --preset tiny --set protocol.frames=1 ";
    const std::string a = (dir.path() / "a").string(), b = (dir.path() / "b").string();
    ASSERT_EQ(run_shaftlab(common + "--shard 1/2 --out " + a).exit_code, 0);
    ASSERT_EQ(run_shaftlab(common + "--shard 2/2 --out " + b).exit_code, 0);
    const size_t total =
        experiments::load_experiment(smoke, {"tiny"}, {"protocol.frames=1"}).cells().size();
    const size_t rows_a = read_csv(dir.path() / "a" / "results.csv").size() - 1;
    const size_t rows_b = read_csv(dir.path() / "b" / "results.csv").size() - 1;
    EXPECT_EQ(rows_a + rows_b, total);
    EXPECT_GT(rows_b, 0u);
    const CommandResult merge =
        run_shaftlab("merge " + a + " " + b + " --out " + (dir.path() / "m").string());
    ASSERT_EQ(merge.exit_code, 0) << merge.output;
    const auto csv = read_csv(dir.path() / "m" / "results.csv");
    std::set<std::string> cells;
    for (size_t r = 1; r < csv.size(); ++r) {
        cells.insert(csv[r][1]);
    }
    EXPECT_EQ(cells.size(), total);
    EXPECT_EQ(csv.size(), 1 + total);
    EXPECT_TRUE(fs::exists(dir.path() / "m" / "table.md"));
}

// docs/harness.md's GNU parallel one-liner and the Slurm array job (its scripts run as Slurm would
// run them, one task per shard, then the merge) each give every cell of the sweep exactly once.
TEST(Bench, GnuParallelAndSlurmShardsMergeIntoTheWholeSweep) {
    TempDir dir;
    const std::string source = SHAFTLAB_SOURCE_DIR;
    const std::string build = fs::path(SHAFTLAB_BINARY).parent_path().string();
    const std::string smoke = source + "/experiments/smoke.toml";
    const size_t total = experiments::load_experiment(smoke, {"tiny"}).cells().size();
    auto rows_of = [&](const fs::path& merged) {
        const auto csv = read_csv(merged / "results.csv");
        std::set<std::string> cells;
        for (size_t r = 1; r < csv.size(); ++r) {
            cells.insert(csv[r][1]);
        }
        EXPECT_EQ(csv.size(), 1 + total) << "one row per cell";
        return cells.size();
    };
    // The one-liner exactly as docs/harness.md has it, with its folders under the test's own.
    const std::string out = (dir.path() / "p").string();
    const CommandResult parallel =
        run_command("cd " + source + " && parallel " + build +
                    "/shaftlab bench experiments/smoke.toml --preset tiny --shard {}/2 --out " +
                    out + "/shard-{} ::: 1 2 && " + build + "/shaftlab merge " + out + "/shard-1 " +
                    out + "/shard-2 --out " + out + "/merged");
    ASSERT_EQ(parallel.exit_code, 0) << parallel.output;
    EXPECT_EQ(rows_of(fs::path(out) / "merged"), total);

    const std::string slurm = "SLURM_SUBMIT_DIR=" + source + " SHAFTLAB_BUILD_DIR=" + build +
                              " SHAFTLAB_OUT=" + (dir.path() / "s").string() + " ";
    for (const char* task : {"1", "2"}) {
        const CommandResult run =
            run_command(slurm + "SLURM_ARRAY_TASK_ID=" + task + " SLURM_ARRAY_TASK_COUNT=2 bash " +
                        source + "/scripts/slurm/sweep.sbatch " + smoke + " --preset tiny");
        ASSERT_EQ(run.exit_code, 0) << run.output;
    }
    const CommandResult merge =
        run_command(slurm + "bash " + source + "/scripts/slurm/merge.sbatch " + smoke);
    ASSERT_EQ(merge.exit_code, 0) << merge.output;
    EXPECT_EQ(rows_of(dir.path() / "s" / "merged"), total);
}

// `--baseline DIR` puts every cell beside the same cell of an earlier run: FPS here and there,
// their ratio, and a cell only one run has is marked.
TEST(Bench, BaselineComparisonListsEveryCellWithItsRatio) {
    TempDir dir;
    const std::string smoke = std::string(SHAFTLAB_SOURCE_DIR) + "/experiments/smoke.toml";
    const std::string a = (dir.path() / "a").string(), b = (dir.path() / "b").string();
    ASSERT_EQ(
        run_shaftlab("bench " + smoke +
                     " --preset tiny --set 'sweep.methods=[\"hybrid2\", \"march\"]' --out " + a)
            .exit_code,
        0);
    const CommandResult run = run_shaftlab(
        "bench " + smoke + " --preset tiny --set 'sweep.methods=[\"march\", \"planes\"]' --out " +
        b + " --baseline " + a);
    ASSERT_EQ(run.exit_code, 0) << run.output;
    std::ifstream file(dir.path() / "b" / "comparison.md");
    std::stringstream text;
    text << file.rdbuf();
    const std::string md = text.str();
    EXPECT_NE(run.output.find(md.substr(0, 40)), std::string::npos) << "printed too";
    EXPECT_NE(md.find("| toplight.march.32x16.samples=16 | "), std::string::npos) << md;
    EXPECT_TRUE(md.find("x | ") != std::string::npos || md.find("x * | ") != std::string::npos)
        << "a ratio: " << md;
    EXPECT_NE(md.find(" ["), std::string::npos) << "FPS with its interval: " << md;
    EXPECT_NE(md.find("(none)"), std::string::npos) << "cells of one run only: " << md;
    EXPECT_NE(md.find("llvmpipe"), std::string::npos) << "the machines named: " << md;
    EXPECT_NE(run_shaftlab("bench " + smoke + " --preset tiny --out " + b + " --baseline " +
                           (dir.path() / "absent").string())
                  .exit_code,
              0);
}

// The main job measures this machine afresh into out/ (a second run too, not "from an earlier
// run"), prints its table, and leaves the working tree exactly as it was.
TEST(MainJob, MeasuresAfreshAndLeavesTheWorkingTreeAsItWas) {
    TempDir dir;
    const std::string source = SHAFTLAB_SOURCE_DIR;
    const std::string status = "git -C " + source + " status --porcelain --ignored=no";
    const CommandResult before = run_command(status);
    ASSERT_EQ(before.exit_code, 0) << before.output;
    const std::string command =
        "SHAFTLAB_PREBUILT=" + fs::path(SHAFTLAB_BINARY).parent_path().string() +
        " SHAFTLAB_OUT=" + dir.path().string() + " " + source + "/scripts/run.sh --experiment " +
        source + "/experiments/smoke.toml --preset tiny";
    for (int run = 0; run < 2; ++run) {
        const CommandResult main_job = run_command(command);
        ASSERT_EQ(main_job.exit_code, 0) << main_job.output;
        EXPECT_EQ(main_job.output.find("from an earlier run"), std::string::npos)
            << "run " << run << " measured nothing:\n"
            << main_job.output;
        EXPECT_NE(main_job.output.find("| toplight"), std::string::npos) << "the table printed";
        EXPECT_TRUE(fs::exists(dir.path() / "smoke" / "results.csv"));
    }
    EXPECT_EQ(run_command(status).output, before.output) << "the working tree changed";
}

// Process isolation: each repetition runs in a child process of its own and lands as its own row.
TEST(Bench, ProcessIsolationWritesOneRowPerRepetition) {
    TempDir dir;
    const std::string smoke = std::string(SHAFTLAB_SOURCE_DIR) + "/experiments/smoke.toml";
    const CommandResult run =
        run_shaftlab("bench " + smoke +
                     " --preset tiny --set protocol.isolation=process --set protocol.repetitions=2 "
                     "--set protocol.frames=1 --set 'sweep.methods=[\"beamtree\", \"planes\"]' "
                     "--set sweep.params.dz=0.5 --out " +
                     dir.path().string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const auto csv = read_csv(dir.path() / "results.csv");
    ASSERT_EQ(csv.size(), 1u + 2u * 2u);
    const auto& header = csv[0];
    const size_t isolation =
        size_t(std::find(header.begin(), header.end(), "isolation") - header.begin());
    const size_t rep = size_t(std::find(header.begin(), header.end(), "rep") - header.begin());
    ASSERT_LT(isolation, header.size());
    std::multiset<std::string> reps;
    for (size_t r = 1; r < csv.size(); ++r) {
        EXPECT_EQ(csv[r][isolation], "process");
        reps.insert(csv[r][rep]);
    }
    EXPECT_EQ(reps.count("0"), 2u);
    EXPECT_EQ(reps.count("1"), 2u);
}

}  // namespace
}  // namespace sl::test
