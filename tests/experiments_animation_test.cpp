// The harness on moving scenes (docs/design.md §11): the bootstrap intervals of the
// medians, the "fastest" mark only where it is significant, the frames an animation cell plays,
// animation cells end to end (every frame measured, every stride-th frame scored, the temporal
// metrics, frames.csv), an interrupted animated cell resuming with nothing lost or repeated, and
// the report's sweep order and scene names.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include <glm/glm.hpp>

#include "core/error.h"
#include "core/statistics.h"
#include "experiments/baseline.h"
#include "experiments/bench.h"
#include "experiments/csv.h"
#include "experiments/experiment.h"
#include "experiments/report.h"
#include "experiments/sequence.h"
#include "experiments/statistics.h"
#include "experiments/tables.h"
#include "reference/cache.h"
#include "scenes/scene_file.h"

#include "tests/gl_support.h"

namespace sl::test {
namespace {

namespace fs = std::filesystem;
using experiments::Cell;
using experiments::Experiment;
using experiments::Interval;
using experiments::median_interval;
using experiments::parse_experiment;

std::vector<std::vector<double>> one(const std::vector<double>& group) {
    return {group};
}

std::string read_file(const fs::path& path) {
    std::ifstream file(path);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

// The interval covers the true median of a normal distribution about 95% of the time, and not
// much more (a too-wide interval would also "pass" a containment test).
TEST(Statistics, MedianIntervalCoversTheTrueMedianAtItsLevel) {
    std::mt19937_64 random(3);
    std::normal_distribution<double> frame(20.0, 2.0);
    int covered = 0;
    const int trials = 300;
    for (int t = 0; t < trials; ++t) {
        std::vector<double> samples(40);
        for (double& s : samples) {
            s = frame(random);
        }
        const Interval i = median_interval(one(samples), 0.95, 600, uint64_t(t) + 1);
        covered += i.low <= 20.0 && 20.0 <= i.high;
    }
    const double coverage = double(covered) / trials;
    EXPECT_GT(coverage, 0.88);
    EXPECT_LT(coverage, 0.995);
}

TEST(Statistics, MedianIntervalNarrowsWithMoreFramesAndIsDeterministic) {
    std::mt19937_64 random(5);
    std::normal_distribution<double> frame(10.0, 1.0);
    auto draw = [&](int n) {
        std::vector<double> v(static_cast<size_t>(n));
        for (double& s : v) {
            s = frame(random);
        }
        return v;
    };
    const auto few = draw(10), many = draw(400);
    const Interval a = median_interval(one(few)), b = median_interval(one(many));
    EXPECT_LT(b.high - b.low, 0.5 * (a.high - a.low));
    const Interval again = median_interval(one(many));
    EXPECT_EQ(again.low, b.low);
    EXPECT_EQ(again.high, b.high);
    // One value, or identical values: a point.
    const Interval point = median_interval(one({7.0, 7.0, 7.0}));
    EXPECT_EQ(point.low, 7.0);
    EXPECT_EQ(point.high, 7.0);
    EXPECT_EQ(median_interval({}).high, 0.0);
    EXPECT_THROW(median_interval(one(few), 1.5), Error);
}

// Repetitions that disagree (a context that ran slow) widen the interval beyond what the same
// frames pooled as if independent give: the resampling draws repetitions first.
TEST(Statistics, RepetitionsThatDisagreeWidenTheInterval) {
    std::mt19937_64 random(9);
    std::normal_distribution<double> jitter(0.0, 0.3);
    std::vector<std::vector<double>> reps;
    std::vector<double> pooled;
    for (const double level : {10.0, 11.0, 12.0}) {
        std::vector<double> rep;
        for (int f = 0; f < 60; ++f) {
            rep.push_back(level + jitter(random));
        }
        pooled.insert(pooled.end(), rep.begin(), rep.end());
        reps.push_back(rep);
    }
    const Interval grouped = median_interval(reps);
    const Interval flat = median_interval(one(pooled));
    EXPECT_GT(grouped.high - grouped.low, 2.0 * (flat.high - flat.low));
}

// The table marks the fastest only when its interval does not overlap the runner-up's.
TEST(Report, FastestIsMarkedOnlyWhenSignificant) {
    const Experiment x = parse_experiment(R"(
name = "t"
[sweep]
scenes = ["toplight", "parallel"]
methods = ["beamtree", "march"]
sizes = ["32x16"]
)",
                                          "t.toml");
    std::mt19937_64 random(1);
    std::vector<experiments::StoredRow> rows;
    for (const Cell& cell : x.cells()) {
        // toplight: beamtree 10 ms against march 20 ms, clearly apart; parallel: 10 against
        // 10.2 ms with 1 ms of noise, not.
        const double centre = cell.method == "beamtree"  ? 10.0
                              : cell.scene == "toplight" ? 20.0
                                                         : 10.2;
        std::normal_distribution<double> noise(centre, 1.0);
        std::vector<double> samples(30);
        for (double& s : samples) {
            s = noise(random);
        }
        rows.push_back({cell,
                        0,
                        {{"frame_ms_median", sl::median(samples)},
                         {"frame_ms_samples", samples},
                         {"rel_rmse", 0.01}}});
    }
    const std::string table = experiments::sweep_table(x, rows);
    std::istringstream lines(table);
    std::map<std::string, std::string> by_scene;
    for (std::string line; std::getline(lines, line);) {
        for (const char* scene : {"toplight", "parallel"}) {
            if (line.starts_with(fmt::format("| {} |", scene))) {
                by_scene[scene] = line;
            }
        }
    }
    ASSERT_EQ(by_scene.size(), 2u) << table;
    EXPECT_NE(by_scene["toplight"].find("**"), std::string::npos) << by_scene["toplight"];
    EXPECT_NE(by_scene["toplight"].find("["), std::string::npos) << "with its interval";
    EXPECT_EQ(by_scene["parallel"].find("**"), std::string::npos) << by_scene["parallel"];
    // Rows without their frames (written before they were kept) claim nothing either.
    for (auto& r : rows) {
        r.row.erase("frame_ms_samples");
    }
    EXPECT_EQ(experiments::sweep_table(x, rows).find("**"), std::string::npos);
}

TEST(Sequence, PlaysTheAnimationAtItsStepOrOrbitsAStillScene) {
    const Scene moving = load_scene("toplight-orbit", SceneSearchPaths::defaults());
    ASSERT_TRUE(moving.animation);
    experiments::Protocol protocol;
    protocol.kind = experiments::ProtocolKind::animation;
    protocol.frames = 0;
    const experiments::Sequence whole(moving, protocol);
    EXPECT_EQ(whole.frames(), moving.animation->frame_count());
    EXPECT_DOUBLE_EQ(whole.time(3), moving.animation->frame_time(3));
    EXPECT_EQ(whole.state(5).light.position,
              scene_at(moving, moving.animation->frame_time(5)).light.position);
    protocol.step = 0.5;
    const experiments::Sequence coarse(moving, protocol);
    EXPECT_EQ(coarse.frames(),
              int(std::floor((moving.animation->end - moving.animation->start) / 0.5)) + 1);
    protocol.frames = coarse.frames() + 1;
    EXPECT_THROW(experiments::Sequence(moving, protocol), Error) << "more frames than it holds";

    const Scene still = load_scene("toplight", SceneSearchPaths::defaults());
    protocol = {};
    protocol.kind = experiments::ProtocolKind::animation;
    protocol.frames = 9;
    protocol.orbit_degrees = 80.0;
    const experiments::Sequence orbit(still, protocol);
    EXPECT_TRUE(orbit.orbit());
    EXPECT_EQ(orbit.frames(), 9);
    const Camera first = orbit.state(0).camera, last = orbit.state(8).camera;
    EXPECT_EQ(first.position, still.camera.position);
    EXPECT_NEAR(glm::distance(last.position, last.target),
                glm::distance(still.camera.position, still.camera.target), 1e-4);
    const glm::vec3 a = first.position - first.target, b = last.position - last.target;
    const glm::vec3 up = glm::normalize(still.camera.up);
    const glm::vec3 pa = glm::normalize(a - glm::dot(a, up) * up);
    const glm::vec3 pb = glm::normalize(b - glm::dot(b, up) * up);
    EXPECT_NEAR(glm::degrees(std::acos(glm::clamp(glm::dot(pa, pb), -1.0f, 1.0f))), 80.0, 0.05);
    EXPECT_EQ(orbit.state(4).light.position, still.light.position) << "only the camera moves";
}

TEST(Experiment, AnimationProtocolKeysAreCheckedAndOnlyForAnimations) {
    const std::string sweep =
        "[sweep]\nscenes = [\"toplight-orbit\"]\nmethods = [\"march\"]\nsizes = [\"32x16\"]\n";
    const Experiment x = parse_experiment(
        "name = \"a\"\n[protocol]\nkind = \"animation\"\nstep = 0.1\nframe_mode = "
        "\"pipelined\"\n[reference]\nstride = 3\npop_factor = 4\n" +
            sweep,
        "a.toml");
    EXPECT_TRUE(x.protocol.animated());
    EXPECT_EQ(x.protocol.frames, 0) << "the whole animation by default";
    EXPECT_TRUE(x.protocol.pipelined);
    EXPECT_EQ(x.scoring.stride, 3);
    EXPECT_EQ(x.scoring.pop_factor, 4.0);
    for (const auto& [text, key] : std::vector<std::pair<std::string, std::string>>{
             {"[protocol]\nkind = \"moving\"\n", "kind"},
             {"[protocol]\nstep = 0.1\n", "step"},
             {"[reference]\nstride = 2\n", "stride"},
             {"[protocol]\nkind = \"animation\"\nframe_mode = \"async\"\n", "frame_mode"},
             {"[protocol]\nkind = \"animation\"\n[reference]\nstride = 0\n", "stride"},
             {"[protocol]\nkind = \"animation\"\nframes = 500\n", "frames = 500"}}) {
        try {
            parse_experiment("name = \"b\"\n" + text + sweep, "b.toml");
            ADD_FAILURE() << "accepted: " << text;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("b.toml"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
        }
    }
}

const char* const kAnimated = R"(
name = "moving"
[protocol]
kind = "animation"
warmup = 1
frames = 6
[render]
shadow_map_size = 256
[sweep]
scenes = ["toplight-orbit", "toplight"]
methods = ["beamtree", "march"]
sizes = ["32x16"]
[sweep.params.march]
samples = 8
[reference]
stride = 2
[outputs]
plots = false
)";

std::map<std::string, std::string> rows_in(const fs::path& out) {
    std::map<std::string, std::string> found;
    if (fs::is_directory(out / "cells")) {
        for (const auto& e : fs::directory_iterator(out / "cells")) {
            found[e.path().filename().string()] = read_file(e.path());
        }
    }
    return found;
}

// Each animated row: its frames, every second one scored, and the temporal metrics.
void expect_animated_rows(const std::map<std::string, std::string>& after) {
    for (const auto& [name, text] : after) {
        const auto row = nlohmann::json::parse(text).at("row");
        EXPECT_EQ(row["protocol"], "animation");
        EXPECT_EQ(row["frames"], 6);
        EXPECT_EQ(row["scored_frames"], 3) << "frames 0, 2, 4";
        EXPECT_EQ(row["per_frame"]["frame"].size(), 6u);
        EXPECT_EQ(row["frame_ms_samples"].size(), 6u);
        for (size_t k = 0; k < 6; ++k) {
            EXPECT_EQ(row["per_frame"]["rel_rmse"][k].is_number(), k % 2 == 0) << name << " " << k;
        }
        for (const char* key :
             {"rel_rmse", "rel_rmse_p95", "rel_rmse_worst", "temporal_error", "flicker",
              "frame_ms_p95", "frame_ms_worst", "cpu_ms_update", "cpu_ms_critical"}) {
            ASSERT_TRUE(row[key].is_number()) << name << " " << key;
            EXPECT_GE(row[key].get<double>(), 0.0) << name << " " << key;
        }
        EXPECT_LT(row["rel_rmse"].get<double>(), 0.2) << name;
        EXPECT_TRUE(row["pops"].is_number_integer());
    }
}

// frames.csv: each row's frames once, in order.
void expect_frames_csv(const fs::path& out) {
    std::ifstream frames(out / "frames.csv");
    std::string header;
    std::getline(frames, header);
    EXPECT_TRUE(header.starts_with("cell,scene,method,width,height,params,rep,frame,")) << header;
    std::map<std::string, std::vector<int>> listed;
    for (std::string line; std::getline(frames, line);) {
        std::vector<std::string> fields;
        std::istringstream in(line);
        for (std::string f; std::getline(in, f, ',');) {
            fields.push_back(f);
        }
        ASSERT_GE(fields.size(), 8u) << line;
        listed[fields[0]].push_back(std::stoi(fields[7]));
    }
    EXPECT_EQ(listed.size(), 4u);
    for (const auto& [cell, list] : listed) {
        EXPECT_EQ(list, (std::vector<int>{0, 1, 2, 3, 4, 5})) << cell;
    }
}

// Animation cells end to end: every frame measured, every stride-th scored, the temporal metrics
// and the per-frame series in the row, frames.csv and the table's section; then an interruption
// mid-cell (as a kill would stop it) and the rerun: rows written before are untouched, the
// interrupted cell is measured once, whole, and its scored frames' references were kept.
TEST(Bench, AnimatedCellsMeasureEveryFrameAndResumeAfterAnInterruption) {
    TempDir dir;
    const Experiment x = parse_experiment(kAnimated, (dir.path() / "moving.toml").string());
    const fs::path out = dir.path() / "out";
    ASSERT_EQ(x.cells().size(), 4u);
    const Cell victim = x.cells()[2];  // toplight (an orbit), beamtree

    std::map<std::string, std::vector<int>> played;  // cell → frames seen, in order
    experiments::BenchOptions options;
    options.out = out;
    options.on_frame = [&](const Cell& cell, int, int frame) {
        played[cell.id()].push_back(frame);
        if (cell == victim && frame == 3) {
            throw experiments::Interrupted("stopped mid-cell");
        }
    };
    EXPECT_THROW(experiments::run_bench(x, options), experiments::Interrupted);
    const auto before = rows_in(out);
    EXPECT_EQ(before.size(), 2u) << "the two cells before the interrupted one";
    for (const auto& [name, text] : before) {
        EXPECT_FALSE(name.starts_with(".")) << "a temporary left behind";
        EXPECT_EQ(name.find(victim.id()), std::string::npos) << "nothing of the interrupted cell";
    }
    // Its references were computed before its frames were measured, and are kept.
    const Scene still = load_scene("toplight", SceneSearchPaths::defaults());
    const experiments::Sequence orbit(still, x.protocol);
    for (int k = 0; k < orbit.frames(); k += 2) {
        EXPECT_TRUE(reference::find_cached(orbit.state(k), 32, 16, {})) << "frame " << k;
    }

    played.clear();
    options.on_frame = [&](const Cell& cell, int, int frame) {
        played[cell.id()].push_back(frame);
    };
    ASSERT_EQ(experiments::run_bench(x, options), 0);
    EXPECT_EQ(played.size(), 2u) << "only the cells without a row were played again";
    EXPECT_EQ(played[victim.id()], (std::vector<int>{0, 1, 2, 3, 4, 5}));
    const auto after = rows_in(out);
    EXPECT_EQ(after.size(), 4u);
    for (const auto& [name, text] : before) {
        EXPECT_EQ(after.at(name), text) << name << " was measured again";
    }

    expect_animated_rows(after);
    expect_frames_csv(out);
    const std::string table = read_file(out / "table.md");
    EXPECT_NE(table.find("## Along the animation"), std::string::npos) << table;
    EXPECT_NE(table.find("| toplight-orbit | beamtree |"), std::string::npos) << table;
    EXPECT_NE(table.find("toplight: an orbit of 90° in 6 frames"), std::string::npos) << table;
    EXPECT_NE(table.find("toplight-orbit: 6 frames of its animation"), std::string::npos) << table;
}

// results.csv: rows in sweep order (the parameter values in the file's order, dz 0.5 before
// 0.1), and scene files named by their stem, the path in scene_file.
TEST(Report, CsvRowsInSweepOrderWithSceneNames) {
    TempDir dir;
    const std::string file =
        std::string(SHAFTLAB_SOURCE_DIR) + "/experiments/toplight-hg.scene.toml";
    const Experiment x = parse_experiment(fmt::format(R"(
name = "t"
[sweep]
scenes = ["{}", "toplight"]
methods = ["planes", "beamtree"]
sizes = ["32x16"]
[sweep.params]
dz = [0.5, 0.1, 0.25]
)",
                                                      file),
                                          "t.toml");
    std::vector<experiments::StoredRow> rows;
    const std::vector<Cell> cells = x.cells();
    for (auto it = cells.rbegin(); it != cells.rend(); ++it) {  // stored in another order
        rows.push_back({*it, 0, {{"cell", it->id()}, {"frame_ms_median", 1.0}}});
    }
    const fs::path out = dir.path() / "out";
    fs::create_directories(out / "cells");
    for (const auto& r : rows) {
        write_text(
            out / "cells" / (r.cell.id() + ".rep0.json"),
            nlohmann::json{{"cell", experiments::cell_to_json(r.cell)}, {"rep", 0}, {"row", r.row}}
                .dump());
    }
    const auto loaded = experiments::load_rows(x, out);
    ASSERT_EQ(loaded.size(), cells.size());
    for (size_t i = 0; i < cells.size(); ++i) {
        EXPECT_EQ(loaded[i].cell, cells[i]) << i;
    }
    const std::string csv = experiments::results_csv(loaded);
    std::istringstream lines(csv);
    std::string header, line;
    std::getline(lines, header);
    EXPECT_TRUE(header.starts_with("experiment,cell,scene,scene_file,method")) << header;
    std::getline(lines, line);
    EXPECT_NE(line.find(",toplight-hg," + file + ","), std::string::npos) << line;
    EXPECT_NE(line.find("dz=0.5"), std::string::npos) << line;
    std::getline(lines, line);
    EXPECT_NE(line.find("dz=0.1"), std::string::npos) << "the file's order: " << line;
    EXPECT_EQ(csv.find("," + file + ","), csv.find(",toplight-hg,") + 12)
        << "the path only in scene_file";
}

}  // namespace
}  // namespace sl::test
