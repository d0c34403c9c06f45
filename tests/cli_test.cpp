// The shaftlab executable end to end: a good render writes its three files; every bad input
// prints one error line, exits non-zero and leaves no file behind.

#include <array>
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "tests/support.h"

namespace sl::test {
namespace {

struct CommandResult {
    int exit_code;
    std::string output;  // stdout and stderr together
};

CommandResult run_shaftlab(const std::string& arguments) {
    const std::string command = std::string(SHAFTLAB_BINARY) + " " + arguments + " 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) {
        return {-1, "popen failed"};
    }
    std::string output;
    std::array<char, 4096> buffer{};
    while (size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) {
        output.append(buffer.data(), n);
    }
    const int status = pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

// `render` writes <scene>.<method>.{png,exr,json}; the JSON records the renderer and timings.
TEST(Cli, RenderWritesPngExrAndJson) {
    TempDir out;
    const CommandResult run = run_shaftlab(
        "render --scene multiple:6 --method none --size 64x36 --warmup 0 "
        "--frames 2 --out " +
        out.path().string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(out.file_count(), 3u);
    std::ifstream in(out / "multiple-6.none.json");
    const nlohmann::json json = nlohmann::json::parse(in);
    EXPECT_EQ(json["scene"], "multiple-6");
    EXPECT_EQ(json["width"], 64);
    EXPECT_EQ(json["height"], 36);
    EXPECT_NE(json["gl"]["renderer"].get<std::string>(), "");
    EXPECT_EQ(json["protocol"]["measured_frames"], 2);
    const double gpu_ms = json["timings_ms"]["gpu"]["total"];
    EXPECT_GT(gpu_ms, 0.0);
    EXPECT_LT(gpu_ms, 60'000.0) << "a GPU timer reported nonsense";
    EXPECT_TRUE(std::filesystem::exists(out / "multiple-6.none.png"));
    EXPECT_TRUE(std::filesystem::exists(out / "multiple-6.none.exr"));
}

// `scenes` lists the canonical scenes; `--generate` prints a scene that renders.
TEST(Cli, ScenesListsCanonicalScenes) {
    const CommandResult run = run_shaftlab("scenes --names");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(run.output, "toplight\nparallel\nmultiple\n");
    EXPECT_EQ(run_shaftlab("scenes --help").exit_code, 0);
    EXPECT_EQ(run_shaftlab("render --help").exit_code, 0);
}

// Each bad input: exit code non-zero, one line naming what is wrong, no output file.
TEST(Cli, BadInputsFailCleanlyWithoutOutput) {
    TempDir scenes;
    write_text(scenes / "nan.toml",
               "[camera]\nposition = [0.0, 1.0, 5.0]\ntarget = [0.0, 0.0, 0.0]\nfov = nan\n"
               "[light]\nposition = [0.0, 5.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\n");
    write_text(scenes / "zero-fov.toml",
               "[camera]\nposition = [0.0, 1.0, 5.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 0\n"
               "[light]\nposition = [0.0, 5.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\n");
    write_text(scenes / "broken.toml", "[camera\n");
    write_text(scenes / "bad-mesh.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n");
    write_text(scenes / "bad-mesh.toml",
               "[camera]\nposition = [0.0, 1.0, 5.0]\ntarget = [0.0, 0.0, 0.0]\n"
               "[light]\nposition = [0.0, 5.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\n"
               "[[objects]]\nshape = \"mesh\"\nfile = \"bad-mesh.off\"\n");
    const std::string dir = scenes.path().string();
    const std::pair<std::string, std::string> cases[] = {
        {"--scene toplight --method magic", "unknown method 'magic' (known: none)"},
        {"--scene toplight --size=-64x36", "--size '-64x36'"},
        {"--scene toplight --size 0x36", "width and height must be in 1..16384"},
        {"--scene toplight --size 64", "expected WIDTHxHEIGHT"},
        {"--scene nowhere", "unknown scene 'nowhere'"},
        {"--scene " + dir + "/absent.toml", "absent.toml: cannot read scene file"},
        {"--scene " + dir + "/nan.toml", "nan.toml:4: [camera] fov: value nan is not finite"},
        {"--scene " + dir + "/zero-fov.toml", "[camera] fov: must be in (0, 180)"},
        {"--scene " + dir + "/broken.toml", "broken.toml:1: malformed TOML"},
        {"--scene " + dir + "/bad-mesh.toml", "bad-mesh.off:6: face index 5 out of range"},
        {"--scene toplight --shadow soft", "--shadow"},
        {"--scene toplight --frames 0", "--frames"},
        {"--scene toplight --bogus", "bogus"},
    };
    for (const auto& [arguments, expected] : cases) {
        TempDir out;
        const std::string size =
            arguments.find("--size") == std::string::npos ? " --size 32x18" : "";
        const CommandResult run =
            run_shaftlab("render " + arguments + size + " --out " + out.path().string());
        EXPECT_NE(run.exit_code, 0) << arguments;
        EXPECT_NE(run.output.find(expected), std::string::npos)
            << arguments << "\nexpected: " << expected << "\ngot: " << run.output;
        EXPECT_TRUE(run.output.starts_with("shaftlab: error: ")) << run.output;
        EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
        EXPECT_EQ(out.file_count(), 0u) << arguments << " left files behind";
    }
}

// An output directory that cannot be created is an error, not a crash.
TEST(Cli, UnwritableOutputIsAnError) {
    TempDir dir;
    write_text(dir / "file", "x");
    const CommandResult run = run_shaftlab(
        "render --scene multiple:2 --size 16x16 --warmup 0 --frames 1 "
        "--out " +
        (dir / "file" / "sub").string());
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("cannot create output directory"), std::string::npos) << run.output;
}

}  // namespace
}  // namespace sl::test
