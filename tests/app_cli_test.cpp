// The shaftlab executable end to end: a good render writes its three files; every bad input
// prints one error line, exits non-zero and leaves no file behind.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/image.h"
#include "core/metrics.h"
#include "core/text.h"
#include "scenes/scene_file.h"

#include "tests/gl_support.h"

namespace sl::test {
namespace {

std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// `render` writes <scene>.<method>.{png,exr,json}; the JSON records the renderer and timings.
TEST(Cli, RenderWritesPngExrAndJson) {
    TempDir out;
    const CommandResult run = run_shaftlab(
        "render --scene multiple:6 --method none --size 64x36 --warmup 0 "
        "--frames 2 --out " +
        out.path().string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(out.file_count(), 4u);
    std::ifstream in(out / "multiple-6.none.json");
    const nlohmann::json json = nlohmann::json::parse(in);
    EXPECT_EQ(json["scene"], "multiple-6");
    EXPECT_EQ(json["width"], 64);
    EXPECT_EQ(json["height"], 36);
    EXPECT_NE(json["gl_renderer"].get<std::string>(), "");
    EXPECT_EQ(json["frames"], 2);
    const double gpu_ms = json["gpu_ms_total"];
    EXPECT_GT(gpu_ms, 0.0);
    EXPECT_LT(gpu_ms, 60'000.0) << "a GPU timer reported nonsense";
    // The harness's row writer wrote it (methods/result_row.h): a cell's columns, by their names.
    for (const char* column :
         {"params", "fps", "frame_ms_median", "frame_ms_p95", "gpu_ms_volume", "volume_cost_ms",
          "cpu_ms_prepare", "ray_frac_lit", "volume_frac_unlit", "beams", "samples_or_slices",
          "shadow", "shadow_map_size", "gl_version"}) {
        EXPECT_TRUE(json.contains(column)) << column;
    }
    EXPECT_TRUE(std::filesystem::exists(out / "multiple-6.none.png"));
    EXPECT_TRUE(std::filesystem::exists(out / "multiple-6.none.exr"));
}

// A tiny but normal camera up (1e-20: its square is below float32's range) renders exactly as
// the unit up does, with and without the beam tree and its Embree-cast region statistics: the
// scene file keeps the up's direction alone (a black-box fuzz's subnormal up aborted in Embree).
TEST(Cli, ATinyCameraUpRendersAsTheUnitOne) {
    TempDir scenes, out;
    const std::string scene =
        "[camera]\nposition = [0.0, 2.0, 6.0]\ntarget = [0.0, 0.5, 0.0]\nUP\n"
        "[light]\nposition = [0.5, 5.0, 0.5]\ntarget = [0.0, 0.0, 0.0]\n"
        "[medium]\nsigma_s = [0.1, 0.1, 0.1]\n"
        "[[objects]]\nshape = \"box\"\n[[objects]]\nshape = \"plane\"\n";
    auto with_up = [&](const std::string& up) {
        std::string text = scene;
        return text.replace(text.find("UP"), 2, "up = " + up);
    };
    write_text(scenes / "tiny.toml", with_up("[0.0, 1e-20, 0.0]"));
    write_text(scenes / "unit.toml", with_up("[0.0, 1.0, 0.0]"));
    for (const char* method : {"none", "beamtree"}) {
        for (const char* name : {"tiny", "unit"}) {
            const CommandResult run = run_shaftlab(fmt::format(
                "render --scene {} --method {} --size 64x36 --warmup 0 --frames 1 --out {}",
                (scenes / (std::string(name) + ".toml")).string(), method, out.path().string()));
            ASSERT_EQ(run.exit_code, 0) << name << " " << method << ": " << run.output;
        }
        const Image tiny = read_exr(out / fmt::format("tiny.{}.exr", method));
        const Image unit = read_exr(out / fmt::format("unit.{}.exr", method));
        ASSERT_EQ(tiny.rgb.size(), unit.rgb.size());
        EXPECT_TRUE(tiny.rgb == unit.rgb) << method;
    }
}

// `render --method reference` computes the reference once, caches it, and composites it.
TEST(Cli, ReferenceIsCachedAndComposited) {
    TempDir cache, out;
    const std::string env = "SHAFTLAB_CACHE=" + cache.path().string() + " ";
    const std::string args =
        "render --scene toplight --method reference --size 48x27 --warmup 0 --frames 1 --out " +
        out.path().string();
    const CommandResult first = run_shaftlab_with(env, args);
    ASSERT_EQ(first.exit_code, 0) << first.output;
    // One cached reference image (beside the bounding volumes the region statistics cache).
    const auto references = [&] {
        size_t count = 0;
        for (const auto& entry : std::filesystem::directory_iterator(cache.path())) {
            count += entry.path().filename().string().starts_with("reference-");
        }
        return count;
    };
    EXPECT_EQ(references(), 1u);
    const CommandResult second = run_shaftlab_with(env, args);
    ASSERT_EQ(second.exit_code, 0) << second.output;
    EXPECT_EQ(references(), 1u) << "computed again instead of read from the cache";
    const Image in_scattering = read_exr(out / "toplight.reference.inscatter.exr");
    const Image composite = read_exr(out / "toplight.reference.exr");
    double scattered = 0.0;
    for (size_t i = 0; i < composite.rgb.size(); ++i) {
        scattered += in_scattering.rgb[i];
        EXPECT_GE(composite.rgb[i] + 1e-6f, in_scattering.rgb[i]);
    }
    EXPECT_GT(scattered, 0.0);

    // `--compare reference`: the reference scores exactly against itself, `none` scores 1.
    const CommandResult compared = run_shaftlab_with(
        env,
        "render --scene toplight --method none --compare reference --size 48x27 --warmup 0 "
        "--frames 1 --out " +
            out.path().string());
    ASSERT_EQ(compared.exit_code, 0) << compared.output;
    std::ifstream json_file(out / "toplight.none.json");
    const nlohmann::json json = nlohmann::json::parse(json_file);
    EXPECT_EQ(json["reference"], "reference");
    EXPECT_NEAR(json["rel_rmse"].get<double>(), 1.0, 1e-9);
    EXPECT_GT(json["max_abs"].get<double>(), 0.0);
    const CommandResult bad =
        run_shaftlab("render --scene toplight --compare none --out " + out.path().string());
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_NE(bad.output.find("--compare 'none'"), std::string::npos) << bad.output;
}

// `methods` lists every method's parameters; `--set` sets them, recorded in the JSON, and an
// unknown name or a value out of range is an error naming both.
TEST(Cli, MethodParametersAreListedAndSet) {
    const CommandResult list = run_shaftlab("methods");
    ASSERT_EQ(list.exit_code, 0) << list.output;
    EXPECT_NE(list.output.find("shadow_samples"), std::string::npos) << list.output;
    EXPECT_NE(list.output.find("range [2, 65536]"), std::string::npos) << list.output;

    TempDir cache, out;
    const std::string env = "SHAFTLAB_CACHE=" + cache.path().string() + " ";
    const CommandResult set = run_shaftlab_with(
        env,
        "render --scene multiple:2 --method reference --set shadow_samples=16 --size 24x16 "
        "--warmup 0 --frames 1 --out " +
            out.path().string());
    ASSERT_EQ(set.exit_code, 0) << set.output;
    std::ifstream json_file(out / "multiple-2.reference.json");
    const nlohmann::json json = nlohmann::json::parse(json_file);
    EXPECT_EQ(json["param_shadow_samples"], "16");

    const std::pair<std::string, std::string> bad[] = {
        {"--method reference --set shadow_samples=1",
         "parameter 'shadow_samples': 1 is out of range [2, 65536]"},
        {"--method reference --set shadow_samples=2.5", "'2.5' is not an integer"},
        {"--method reference --set shadow_samples=nan", "'nan' is not an integer"},
        {"--method reference --set rays=4", "method 'reference' has no parameter 'rays'"},
        {"--method none --set x", "--set 'x': expected NAME=VALUE"},
    };
    for (const auto& [arguments, expected] : bad) {
        TempDir nothing;
        const CommandResult run =
            run_shaftlab_with(env, "render --scene multiple:2 " + arguments +
                                       " --size 24x16 --out " + nothing.path().string());
        EXPECT_NE(run.exit_code, 0) << arguments;
        EXPECT_NE(run.output.find(expected), std::string::npos) << arguments << ": " << run.output;
        EXPECT_EQ(nothing.file_count(), 0u);
    }
}

// The two headless backends (OSMesa, and EGL on Mesa's software device here) render the same frame;
// SHAFTLAB_GL names them and nothing else.
TEST(Cli, EglAndOsmesaBackendsRenderTheSameFrame) {
    // Mesa's EGL driver is unloaded at eglTerminate, so LeakSanitizer cannot attribute what it
    // keeps (an "<unknown module>", as for GLX in tests/CMakeLists.txt): no leak check there.
    const std::string egl_env = "SHAFTLAB_GL=egl ASAN_OPTIONS=detect_leaks=0 ";
    TempDir osmesa, egl;
    const std::string arguments = "render --scene multiple:2 --method hybrid3 --size 64x48 --out ";
    const CommandResult a =
        run_shaftlab_with("SHAFTLAB_GL=osmesa ", arguments + osmesa.path().string());
    if (a.output.find("this build has no OSMesa") != std::string::npos) {
        GTEST_SKIP() << "built with -DSHAFTLAB_WITH_OSMESA=OFF";
    }
    ASSERT_EQ(a.exit_code, 0) << a.output;
    const CommandResult b = run_shaftlab_with(egl_env, arguments + egl.path().string());
    ASSERT_EQ(b.exit_code, 0) << b.output;
    const CommandResult info = run_shaftlab_with(egl_env, "gl-info");
    EXPECT_NE(info.output.find("backend  egl"), std::string::npos) << info.output;
    const std::string name = "multiple-2.hybrid3.inscatter.exr";
    const ErrorMetrics error = compare_images(read_exr(egl / name), read_exr(osmesa / name));
    EXPECT_LT(error.rel_rmse, 1e-3);

    TempDir nothing;
    const CommandResult bad =
        run_shaftlab_with("SHAFTLAB_GL=vulkan ", arguments + nothing.path().string());
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_NE(bad.output.find("SHAFTLAB_GL='vulkan': expected 'osmesa' or 'egl'"),
              std::string::npos)
        << bad.output;
    EXPECT_EQ(nothing.file_count(), 0u);
}

// `sss` tools: a profile and a uniformity run write their files with the numbers of the seed's
// set-up; every bad input is one error line, a non-zero exit and no file.
TEST(Cli, SssToolsWriteTheirFilesAndRejectBadInputs) {
    TempDir profile, uniformity;
    const CommandResult p =
        run_shaftlab("sss profile --material marble --out " + profile.path().string());
    ASSERT_EQ(p.exit_code, 0) << p.output;
    const auto json = nlohmann::json::parse(read_text(profile / "marble.profile.json"));
    EXPECT_NEAR(json["A"].get<double>(), 3.9595, 1e-4);  // Fdr(1.5), Jensen's polynomial
    EXPECT_GT(json["r_max_mm_flux"].get<double>(), json["r_max_mm_profile"].get<double>());
    const CommandResult u = run_shaftlab("sss uniformity --mesh bunny00.off --points 400 --out " +
                                         uniformity.path().string());
    ASSERT_EQ(u.exit_code, 0) << u.output;
    const auto report = nlohmann::json::parse(read_text(uniformity / "uniformity.json"));
    EXPECT_GT(report["eliminated"]["relative_radius"].get<double>(),
              report["random"]["relative_radius"].get<double>())
        << report.dump();

    const std::pair<const char*, const char*> bad[] = {
        {"uniformity --mesh bunny00.off --points 1", "--points must be at least 2"},
        {"uniformity --mesh missing.off", "cannot open mesh file"},
        {"profile --material unobtainium", "unknown translucent material 'unobtainium'"},
        {"profile --material marble --thickness -1", "--thickness must be"},
        {"profile --material marble --thickness nan", "--thickness must be"},
        {"profile --material marble --epsilon 2", "--epsilon must lie in (0, 1)"},
    };
    for (const auto& [arguments, expected] : bad) {
        TempDir nothing;
        const CommandResult run =
            run_shaftlab(std::string("sss ") + arguments + " --out " + nothing.path().string());
        EXPECT_NE(run.exit_code, 0) << arguments;
        EXPECT_NE(run.output.find(expected), std::string::npos) << arguments << ": " << run.output;
        EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
        EXPECT_EQ(nothing.file_count(), 0u) << arguments;
    }
}

// `scenes` lists every scene that loads by name, the animated ones included, and each name it
// lists loads; `--generate` prints a scene that renders.
TEST(Cli, ScenesListsEverySceneThatLoadsByName) {
    const CommandResult run = run_shaftlab("scenes --names");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(run.output,
              "toplight\nparallel\nmultiple\ntoplight-orbit\nparallel-walk\nmultiple-moving\n"
              "ibl-spheres\nsss-bunny\nsss-dragon\nsss-shaft\n"
              "house\nhouse-sweep\nengine\nengine-orbit\narena\narena-sweep\n"
              "room\nparallel-lamps\nhouse-morning\nparallel-lamps-swing\nhouse-day\n");
    const CommandResult listing = run_shaftlab("scenes");
    ASSERT_EQ(listing.exit_code, 0) << listing.output;
    for (const std::string& name : named_scene_names()) {
        EXPECT_NE(listing.output.find(name + " "), std::string::npos) << name;
    }
    EXPECT_NE(listing.output.find("multiple-moving"), std::string::npos);
    EXPECT_NE(listing.output.find("animated 0-"), std::string::npos) << listing.output;
    EXPECT_NE(listing.output.find("lights: 0 spot, 1 point"), std::string::npos) << listing.output;
    EXPECT_NE(listing.output.find("lights: 0 spot, 0 point, 1 directional"), std::string::npos)
        << listing.output;
    EXPECT_NE(listing.output.find("spot cone 30 deg"), std::string::npos) << listing.output;
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
    const std::string view =
        "[camera]\nposition = [0.0, 1.0, 5.0]\ntarget = [0.0, 0.0, 0.0]\n"
        "[light]\nposition = [0.0, 5.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\n";
    write_text(scenes / "no-env.toml", view + "[environment]\nfile = \"atlantis\"\n");
    write_text(scenes / "env-size.toml",
               view + "[environment]\nfile = \"courtyard\"\nface_size = 100\n");
    write_text(scenes / "env-shading.toml",
               view + "[environment]\nfile = \"courtyard\"\nshading = \"phong\"\n");
    const std::string dir = scenes.path().string();
    write_text(scenes / "directory-base.toml", "[scene]\nbase = \"" + dir + "\"\n");
    const std::pair<std::string, std::string> cases[] = {
        {"--scene " + dir + "/no-env.toml", "[environment] file: no environment 'atlantis'"},
        {"--scene " + dir + "/env-size.toml", "[environment] face_size: 100 is not a power of two"},
        {"--scene " + dir + "/env-shading.toml",
         "[environment] shading: unknown IBL shading 'phong'"},
        {"--scene toplight --method magic",
         "unknown method 'magic' (known: none, beamtree, planes, hybrid1, hybrid2, march, hybrid3, "
         "froxel, lightvolume, epipolar, reference)"},
        {"--scene toplight --method march --set resolution_scale=0.3",
         "parameter 'resolution_scale': '0.3' is not one of 1, 0.5, 0.25"},
        {"--scene toplight --method march --set samples=0",
         "parameter 'samples': 0 is out of range"},
        {"--scene toplight --method planes --set dz=0", "parameter 'dz': 0 is out of range"},
        {"--scene toplight --method hybrid1 --set shadow=soft",
         "parameter 'shadow': 'soft' is not one of hard, pcf, vsm"},
        {"--scene toplight --size=-64x36", "--size '-64x36'"},
        {"--scene toplight --size 0x36", "width and height must be in 1..16384"},
        {"--scene toplight --size 64", "expected WIDTHxHEIGHT"},
        {"--scene toplight --size 100000x1", "width and height must be in 1..16384"},
        {"--scene " + dir + "/directory-base.toml", "directory-base.toml:2: [scene] base: " + dir +
                                                        ": cannot read scene file (it is a "
                                                        "directory)"},
        {"--scene nowhere", "unknown scene 'nowhere' (canonical"},
        {"--scene paralel", "unknown scene 'paralel' (did you mean 'parallel'?)"},
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

// `view` rejects bad options, scenes, methods and paths with one line before it opens a window,
// and says so when there is no display, writing nothing.
TEST(Cli, ViewRejectsBadInputBeforeOpeningAWindow) {
    TempDir dir;
    write_text(dir / "path.toml",
               "[animation]\n[[animation.light]]\ntime = 2\n[[animation.light]]\ntime = 1\n");
    const std::pair<std::string, std::string> cases[] = {
        {"--scene nowhere", "unknown scene 'nowhere'"},
        {"--scene toplight --method magic", "unknown method 'magic'"},
        {"--scene toplight --set samples=0", "parameter 'samples': 0 is out of range"},
        {"--scene toplight --layers volumes,fog", "unknown layer 'fog' (known: volumes"},
        {"--scene toplight --screenshot x.png", "need --frames N"},
        {"--scene toplight --frames 2 --path " + (dir / "absent.toml").string(),
         "cannot read the animation file"},
        {"--scene toplight --frames 2 --path " + (dir / "path.toml").string(),
         "path.toml:5: [[animation.light]] #2 time: 1 is not after the previous key's 2"},
        {"--scene toplight --size 8x8", "window size 8x8"},
    };
    for (const auto& [arguments, expected] : cases) {
        const CommandResult run = run_shaftlab("view " + arguments);
        EXPECT_EQ(run.exit_code, 1) << arguments;
        EXPECT_NE(run.output.find(expected), std::string::npos)
            << arguments << "\nexpected: " << expected << "\ngot: " << run.output;
        EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
    }
    const CommandResult headless =
        run_shaftlab_with("DISPLAY= WAYLAND_DISPLAY= ", "view --scene toplight --frames 1");
    EXPECT_EQ(headless.exit_code, 1);
    EXPECT_NE(headless.output.find("GLFW could not initialise (no display?)"), std::string::npos)
        << headless.output;
    EXPECT_EQ(dir.file_count(), 1u) << "nothing written";
}

// An output directory that cannot be created is an error, not a crash.
// `compare` prints the metrics and writes the difference picture; images of different sizes are
// one clear error and no picture.
TEST(Cli, CompareScoresAndRejectsMismatchedSizes) {
    TempDir dir;
    Image a(8, 4), b(8, 4), small(4, 4);
    for (int x = 0; x < 8; ++x) {
        a.set(x, 1, {1.0f, 1.0f, 1.0f});
        b.set(x, 1, {1.0f, 1.0f, x == 3 ? 0.5f : 1.0f});
    }
    write_exr(a, dir / "a.exr");
    write_exr(b, dir / "b.exr");
    write_exr(small, dir / "small.exr");
    const std::string d = dir.path().string();
    const CommandResult ok =
        run_shaftlab("compare " + d + "/a.exr " + d + "/b.exr --difference " + d + "/diff.png");
    EXPECT_EQ(ok.exit_code, 0) << ok.output;
    // sqrt(0.5² / (23 + 0.5²)): one channel of one pixel off by a half.
    EXPECT_NE(ok.output.find("rel_rmse 0.103695"), std::string::npos) << ok.output;
    EXPECT_TRUE(std::filesystem::exists(dir / "diff.png"));
    const CommandResult bad =
        run_shaftlab("compare " + d + "/a.exr " + d + "/small.exr --difference " + d + "/bad.png");
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_TRUE(bad.output.starts_with("shaftlab: error: ")) << bad.output;
    EXPECT_EQ(std::count(bad.output.begin(), bad.output.end(), '\n'), 1) << bad.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.png"));
    // A directory as the difference picture's path is named as such, before any work.
    const CommandResult directory =
        run_shaftlab("compare " + d + "/a.exr " + d + "/b.exr --difference /");
    EXPECT_NE(directory.exit_code, 0);
    EXPECT_NE(directory.output.find("--difference '/': a directory; expected the path of the PNG"),
              std::string::npos)
        << directory.output;
}

// A NaN or an infinity never scores: compare names the file and the first bad pixel, whether
// it is in the image (it scored "rel_rmse -nan") or in the reference (it scored a perfect 0).
TEST(Cli, CompareRefusesNonFiniteImages) {
    TempDir dir;
    Image good(8, 4), bad(8, 4);
    for (int x = 0; x < 8; ++x) {
        good.set(x, 1, {1.0f, 1.0f, 1.0f});
        bad.set(x, 1, {1.0f, 1.0f, 1.0f});
    }
    bad.set(5, 2, {0.0f, std::numeric_limits<float>::quiet_NaN(), 0.0f});
    write_exr(good, dir / "good.exr");
    write_unchecked_exr(bad, dir / "nan.exr");
    const std::string d = dir.path().string();
    for (const std::string& arguments :
         {"/nan.exr " + d + "/good.exr", "/good.exr " + d + "/nan.exr"}) {
        const CommandResult run =
            run_shaftlab("compare " + d + arguments + " --difference " + d + "/diff.png");
        EXPECT_EQ(run.exit_code, 1) << run.output;
        EXPECT_NE(run.output.find("nan.exr: pixel (5, 2) channel 1 is nan"), std::string::npos)
            << run.output;
        EXPECT_EQ(run.output.find("rel_rmse"), std::string::npos) << run.output;
        EXPECT_FALSE(std::filesystem::exists(dir / "diff.png"));
    }
}

// An environment of huge finite radiance (3.4e38, which made the SH9 sums and the prefilter
// overflow into a NaN image and exit 0) is refused with the pixel and the limit, before anything
// is rendered or written.
TEST(Cli, HugeEnvironmentRadianceIsRefused) {
    TempDir dir;
    Image sky(16, 8);
    for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 16; ++x) {
            sky.set(x, y, {1.0f, 1.0f, 1.0f});
        }
    }
    sky.set(3, 1, {3.4e38f, 3.4e38f, 3.4e38f});
    write_exr(sky, dir / "huge.exr");
    write_text(dir / "huge.toml",
               "[scene]\nbase = \"toplight\"\n[environment]\nfile = \"huge.exr\"\n"
               "face_size = 16\nsamples = 4\n");
    const CommandResult run =
        run_shaftlab("render --scene " + (dir / "huge.toml").string() +
                     " --method none --size 32x18 --out " + (dir / "out").string());
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_NE(run.output.find("huge.exr: pixel (3, 1) has radiance 3.4e+38"), std::string::npos)
        << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

// Every command's early failure (a bad scene, option, file or an empty sweep) is one line on
// stderr, a non-zero exit, and nothing on disk: not a file, not even the output folder (a bench
// whose sweep excluded every cell used to leave experiment.toml).
TEST(Cli, EveryCommandsEarlyFailureWritesNothing) {
    TempDir dir;
    const std::string d = dir.path().string();
    const std::string smoke = std::string(SHAFTLAB_SOURCE_DIR) + "/experiments/smoke.toml";
    write_text(dir / "bad.toml", "[camera\n");
    write_text(dir / "bad-animation.toml",
               "[scene]\nbase = \"toplight\"\n[[animation.light]]\ntime = -1.0\n");
    Image good(8, 4);
    write_exr(good, dir / "a.exr");
    write_exr(Image(4, 4), dir / "b.exr");
    const std::string out = d + "/never/made";
    const std::pair<std::string, std::string> cases[] = {
        {"render --scene " + d + "/bad.toml --out " + out, "malformed TOML"},
        {"regions --scene nowhere --out " + out, "unknown scene 'nowhere'"},
        {"regions --scene toplight --size 0x9 --out " + out, "width and height"},
        {"regions --scene " + std::string(SHAFTLAB_SOURCE_DIR) +
             "/tests/data/terrain-pieces/scene.toml --max-planes 24 --out " + out,
         "--max-planes 24: terrain-pieces cuts its objects into convex pieces"},
        {"compare " + d + "/a.exr " + d + "/b.exr --difference " + out + "/d.png",
         "cannot compare"},
        {"bench " + smoke +
             " --set 'sweep.methods=[\"planes\"]' --set 'exclude=[{method = "
             "\"planes\"}]' --out " +
             out,
         "the sweep is empty"},
        {"bench " + smoke + " --set protocol.frames=0 --out " + out, "frames"},
        {"merge " + d + " --out " + out, "not a bench output directory"},
        {"ibl prefilter atlantis --out " + out, "no environment 'atlantis'"},
        {"ibl reference --scene toplight --out " + out, "has no [environment]"},
        {"sss profile --material unobtainium --out " + out, "unknown translucent material"},
        {"sss uniformity --mesh " + d + "/absent.off --out " + out, "absent.off"},
        {"view --scene toplight --method magic --frames 1 --screenshot " + out + "/s.png",
         "unknown method 'magic'"},
        {"animate --scene toplight --out " + out, "the scene has no [animation] to play"},
        {"animate --scene toplight-orbit --frames 500 --out " + out,
         "--frames 500: the animation has 121 frames"},
        {"animate --scene " + d + "/bad-animation.toml --out " + out,
         "bad-animation.toml:4: [[animation.light]] #1 time: -1 is before the animation's start 0"},
        {"render --scene " + d + "/bad-animation.toml --out " + out,
         "is before the animation's start"},
    };
    for (const auto& [arguments, expected] : cases) {
        const CommandResult run = run_shaftlab(arguments);
        EXPECT_NE(run.exit_code, 0) << arguments;
        EXPECT_NE(run.output.find(expected), std::string::npos)
            << arguments << "\nexpected: " << expected << "\ngot: " << run.output;
        EXPECT_TRUE(run.output.starts_with("shaftlab: error: ")) << run.output;
        EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
        EXPECT_FALSE(std::filesystem::exists(dir / "never")) << arguments << " wrote something";
        std::filesystem::remove_all(dir / "never");
    }
}

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

// A scene of several lights has a tree per light: `regions` asks which (--light N), and
// --all-lights (what the main job runs over every scene) writes each into DIR/light<N>/; a scene
// of one light writes DIR/ as without it.
TEST(Cli, RegionsOfEveryLightGoEachIntoItsOwnDirectory) {
    TempDir out;
    const CommandResult ask =
        run_shaftlab("regions --scene parallel-lamps --size 32x18 --out " + out.path().string());
    EXPECT_NE(ask.exit_code, 0);
    EXPECT_NE(ask.output.find("choose one with --light 0 to 3"), std::string::npos) << ask.output;
    const CommandResult all = run_shaftlab(
        "regions --scene parallel-lamps --all-lights --size 32x18 --out " + out.path().string());
    ASSERT_EQ(all.exit_code, 0) << all.output;
    for (int i = 0; i < 4; ++i) {
        const std::filesystem::path dir = out / ("light" + std::to_string(i));
        for (const char* file : {"regions.ply", "regions.json", "regions.png"}) {
            EXPECT_TRUE(std::filesystem::exists(dir / file)) << dir / file;
        }
        std::ifstream json_file(dir / "regions.json");
        const nlohmann::json json = nlohmann::json::parse(json_file);
        EXPECT_GT(json["beams"].get<int>(), 0) << "light " << i;
    }
    EXPECT_FALSE(std::filesystem::exists(out / "light4"));
    TempDir one;
    const CommandResult single = run_shaftlab(
        "regions --scene multiple:3 --all-lights --size 32x18 --out " + one.path().string());
    ASSERT_EQ(single.exit_code, 0) << single.output;
    EXPECT_TRUE(std::filesystem::exists(one / "regions.json"));
    EXPECT_NE(run_shaftlab("regions --scene parallel-lamps --all-lights --light 1 --out " +
                           one.path().string())
                  .exit_code,
              0);
}

// `regions` writes the PLY, JSON and PNG; the JSON's region volumes tile the influence volume and
// the PLY's header counts match its body.
TEST(Cli, RegionsWritesPlyJsonAndPng) {
    TempDir out;
    const CommandResult run =
        run_shaftlab("regions --scene multiple:5 --size 64x36 --out " + out.path().string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(out.file_count(), 3u);
    std::ifstream json_file(out / "regions.json");
    const nlohmann::json json = nlohmann::json::parse(json_file);
    EXPECT_GT(json["beams"].get<int>(), 5);
    EXPECT_GE(json["build_ms"].get<double>(), 0.0);
    EXPECT_GE(json["extract_ms"].get<double>(), 0.0);
    const double sum = json["regions"]["lit"]["volume"].get<double>() +
                       json["regions"]["uncertain"]["volume"].get<double>() +
                       json["regions"]["unlit"]["volume"].get<double>();
    EXPECT_NEAR(sum / json["influence_volume"].get<double>(), 1.0, 1e-6);

    // Binary PLY: the header, then 3 doubles per vertex and per face a uchar count, the
    // indices, a uchar region and an int beam.
    std::ifstream ply(out / "regions.ply", std::ios::binary);
    std::string line;
    size_t vertices = 0, faces = 0, body = 0;
    while (std::getline(ply, line) && line != "end_header") {
        std::sscanf(line.c_str(), "element vertex %zu", &vertices);
        std::sscanf(line.c_str(), "element face %zu", &faces);
    }
    ply.seekg(std::streamoff(vertices * 3 * sizeof(double)), std::ios::cur);
    size_t indices = 0, region_counts[3] = {0, 0, 0};
    for (size_t f = 0; f < faces; ++f) {
        uint8_t count = 0, region = 9;
        ply.read(reinterpret_cast<char*>(&count), 1);
        ply.seekg(std::streamoff(count * sizeof(int32_t)), std::ios::cur);
        ply.read(reinterpret_cast<char*>(&region), 1);
        ply.seekg(std::streamoff(sizeof(int32_t)), std::ios::cur);
        ASSERT_TRUE(ply) << "face " << f;
        ASSERT_LT(region, 3);
        indices += count;
        ++region_counts[region];
        ++body;
    }
    EXPECT_EQ(ply.peek(), EOF) << "nothing after the faces";
    EXPECT_EQ(indices, vertices);
    body += vertices;
    EXPECT_GT(faces, 0u);
    EXPECT_EQ(body, vertices + faces);
    size_t json_faces = 0;
    for (const char* region : {"lit", "uncertain", "unlit"}) {
        json_faces += json["regions"][region]["faces"].get<size_t>();
    }
    EXPECT_EQ(json_faces, faces);
}

// Objects without an automatic inner volume are summed up in one warning line per scene (by
// reason), listed one by one in regions.json, and printed one by one with --verbose: two open
// height fields and a closed box give one line, two entries, and two more lines.
TEST(Cli, RegionsSumsUpObjectsWithoutInnerVolumesInOneLine) {
    TempDir dir;
    const std::string data = std::string(SHAFTLAB_SOURCE_DIR) + "/tests/data/terrain-pieces/";
    // The repro's scene (a floor and a terrain), with a second terrain and a box.
    write_text(dir / "scene.toml", fmt::format(R"([scene]
name = "two-terrains"
[camera]
position = [6.0, 4.0, 7.0]
target = [0.0, 1.5, 0.0]
[light]
position = [0.57, 6.0, -0.86]
target = [0.0, 0.0, 0.0]
cone_angle = 32.0
near = 0.5
far = 12.0
[beamtree]
pieces = true
[[objects]]
name = "floor"
shape = "plane"
size = [40.0, 0.0, 40.0]
[[objects]]
name = "terrain"
shape = "mesh"
file = "{0}terrain.obj"
[[objects]]
name = "second terrain"
shape = "mesh"
file = "{0}terrain.obj"
translate = [0.0, -0.5, 0.0]
[[objects]]
name = "box"
shape = "box"
translate = [3.0, 0.5, 3.0]
)",
                                               data));
    auto lines_with = [](const std::string& text, const std::string& needle) {
        size_t count = 0;
        for (size_t at = text.find(needle); at != std::string::npos;
             at = text.find(needle, at + 1)) {
            ++count;
        }
        return count;
    };
    const std::string scene = (dir / "scene.toml").string();
    const CommandResult run =
        run_shaftlab("regions --scene " + scene + " --size 32x18 --out " + (dir / "a").string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(lines_with(run.output, "warning:"), 1u) << run.output;
    EXPECT_NE(run.output.find("2 of 4 objects have no automatic inner volume: 2 because the mesh "
                              "is not closed"),
              std::string::npos)
        << run.output;
    std::ifstream json_file(dir / "a" / "regions.json");
    const nlohmann::json json = nlohmann::json::parse(json_file);
    ASSERT_EQ(json["objects_without_inner_volume"].size(), 2u) << json.dump(2);
    EXPECT_EQ(json["objects_without_inner_volume"][1]["object"], "second terrain");
    EXPECT_EQ(json["warnings"].size(), 1u);

    const CommandResult verbose = run_shaftlab("regions --verbose --scene " + scene +
                                               " --size 32x18 --out " + (dir / "b").string());
    ASSERT_EQ(verbose.exit_code, 0) << verbose.output;
    EXPECT_EQ(lines_with(verbose.output, "warning:"), 3u) << verbose.output;
    EXPECT_NE(verbose.output.find("object 'second terrain': no automatic inner volume"),
              std::string::npos)
        << verbose.output;

    // --occluders overrides the scene's setting: auto gives both terrains their triangles, and
    // nothing is left without a volume to warn about.
    const CommandResult exact = run_shaftlab("regions --occluders auto --scene " + scene +
                                             " --size 32x18 --out " + (dir / "c").string());
    ASSERT_EQ(exact.exit_code, 0) << exact.output;
    EXPECT_EQ(lines_with(exact.output, "warning:"), 0u) << exact.output;
    std::ifstream exact_file(dir / "c" / "regions.json");
    const nlohmann::json exact_json = nlohmann::json::parse(exact_file);
    EXPECT_EQ(exact_json["occluders"], "auto");
    EXPECT_EQ(exact_json["objects_as_triangles"].size(), 2u) << exact_json.dump(2);
    EXPECT_GT(exact_json["tree"]["exact_polygons"].get<int>(), 0);
    const CommandResult bad = run_shaftlab("regions --occluders exact --scene " + scene +
                                           " --size 32x18 --out " + (dir / "d").string());
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_NE(bad.output.find("--occluders: exact not in {volumes,triangles,auto}"),
              std::string::npos)
        << bad.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "d"));
}

// `regions --classify` prints one region per point: lit in the open cone under the light, unlit
// under the floor (a flat object is its own inner volume) and outside the influence volume.
TEST(Cli, RegionsClassifiesPoints) {
    TempDir dir;
    write_text(dir / "points.txt", "0.1 8 0.1\n0 -0.5 0\n50 50 50\n\n0 9 0.2\n");
    const CommandResult run =
        run_shaftlab("regions --scene multiple:3 --classify " + (dir / "points.txt").string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(run.output, "lit\nunlit\nunlit\nlit\n");

    write_text(dir / "bad.txt", "0 1 0\n1 2\n");
    const CommandResult bad =
        run_shaftlab("regions --scene multiple:3 --classify " + (dir / "bad.txt").string());
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_NE(bad.output.find("bad.txt:2: expected three numbers"), std::string::npos)
        << bad.output;
}

// A quick comparison without an experiment file: `bench --scene S --methods a,b --size WxH`
// measures those cells against the reference like a one-scene experiment, and every bench run
// writes summary.json (one entry per cell: its frame time with the interval, FPS, error). Half a
// quick comparison, or one beside a file, is refused.
TEST(Cli, BenchComparesMethodsFromTheCommandLineAndSummarisesInJson) {
    TempDir out;
    const CommandResult run = run_shaftlab(
        "bench --scene toplight --methods none,march --size "
        "48x27 --set protocol.frames=2 --out " +
        out.path().string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    std::ifstream in(out / "summary.json");
    const nlohmann::json summary = nlohmann::json::parse(in);
    EXPECT_EQ(summary["experiment"], "quick");
    ASSERT_EQ(summary["cells"].size(), 2u);
    EXPECT_EQ(summary["cells"][0]["method"], "none");
    EXPECT_EQ(summary["cells"][1]["method"], "march");
    for (const nlohmann::json& cell : summary["cells"]) {
        EXPECT_EQ(cell["scene"], "toplight");
        EXPECT_EQ(cell["width"], 48);
        EXPECT_GT(cell["fps"].get<double>(), 0.0);
        EXPECT_TRUE(cell["rel_rmse"].is_number());
        EXPECT_EQ(cell["frame_ms_interval"].size(), 2u);
    }
    EXPECT_TRUE(std::filesystem::exists(out / "table.md"));
    for (const auto& [arguments, words] : std::vector<std::pair<std::string, std::string>>{
             {"bench --scene toplight", "needs both --scene and --methods"},
             {"bench experiments/smoke.toml --methods march", "not both"},
             {"bench --scene toplight --methods merch", "unknown method 'merch' (did you mean"}}) {
        const CommandResult bad = run_shaftlab(arguments + " --out " + (out / "bad").string());
        EXPECT_NE(bad.exit_code, 0) << arguments;
        EXPECT_NE(bad.output.find(words), std::string::npos) << arguments << ": " << bad.output;
        EXPECT_FALSE(std::filesystem::exists(out / "bad")) << arguments;
    }
}

// A light inside an object's outer volume: `regions` is one clear error with no output, and so
// is a method that uses the beam tree; a method that does not renders it.
TEST(Cli, ALightInsideABoundingVolumeStopsOnlyTheMethodsThatUseTheTree) {
    TempDir dir;
    write_text(dir / "inside.toml",
               "[camera]\nposition = [0.0, 1.0, 5.0]\ntarget = [0.0, 0.0, 0.0]\n"
               "[light]\nposition = [0.0, 0.0, 0.0]\ntarget = [0.0, -1.0, 0.0]\n"
               "[[objects]]\nname = \"crate\"\nshape = \"box\"\nsize = [2.0, 2.0, 2.0]\n");
    const CommandResult run = run_shaftlab("regions --scene " + (dir / "inside.toml").string() +
                                           " --size 32x18 --out " + (dir / "out").string());
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("inside the outer bounding volume of object 'crate'"),
              std::string::npos)
        << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "regions.json"));
    // Only the methods that use the tree refuse the scene, and say what to do; the others render
    // it with a warning that its region statistics are left out.
    for (const char* method : {"none", "march"}) {
        const CommandResult render = run_shaftlab(
            fmt::format("render --scene {} --method {} --size 32x18 --warmup 0 "
                        "--frames 1 --out {}",
                        (dir / "inside.toml").string(), method, (dir / "render").string()));
        EXPECT_EQ(render.exit_code, 0) << method << ": " << render.output;
        EXPECT_NE(render.output.find("warning: no region statistics"), std::string::npos)
            << render.output;
    }
    const CommandResult refused =
        run_shaftlab("render --scene " + (dir / "inside.toml").string() +
                     " --method beamtree --size 32x18 --out " + (dir / "refused").string());
    EXPECT_NE(refused.exit_code, 0);
    EXPECT_NE(refused.output.find("[beamtree] pieces = true"), std::string::npos) << refused.output;
    EXPECT_NE(refused.output.find("a method without regions"), std::string::npos) << refused.output;
}

// `ibl prefilter` writes one EXR and PNG per level and a JSON summary whose levels halve in size
// and follow the chosen method's roughness; with --brute-force, each resolvable level is scored.
TEST(Cli, IblPrefilterWritesTheChain) {
    TempDir out;
    const CommandResult run =
        run_shaftlab("ibl prefilter courtyard --face-size 32 --samples 64 --brute-force 64 --out " +
                     out.path().string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const nlohmann::json summary = nlohmann::json::parse(read_text(out / "prefilter.json"));
    EXPECT_EQ(summary["method"], "importance");
    ASSERT_EQ(summary["levels"].size(), 3u);  // 32, 16, 8
    for (size_t l = 0; l < 3; ++l) {
        EXPECT_EQ(summary["levels"][l]["face_size"], 32 >> l);
        const Image strip = read_exr(out / fmt::format("level_{:02}.exr", l));
        EXPECT_EQ(strip.width, 6 * (32 >> l));
        EXPECT_TRUE(std::filesystem::exists(out / fmt::format("level_{:02}.png", l)));
    }
    const double error = summary["levels"][2]["rel_rmse_vs_brute_force"].get<double>();
    EXPECT_GT(error, 0.0);
    EXPECT_LT(error, 0.5);  // 64 samples on a 32² source at α = 1: filtered IS is biased there
    EXPECT_EQ(summary["sh9"].size(), 9u);

    TempDir cone;
    const CommandResult seed = run_shaftlab(
        "ibl prefilter courtyard --method cone --face-size 16 "
        "--samples 16 --out " +
        cone.path().string());
    ASSERT_EQ(seed.exit_code, 0) << seed.output;
    const nlohmann::json levels =
        nlohmann::json::parse(read_text(cone / "prefilter.json"))["levels"];
    ASSERT_EQ(levels.size(), 5u);                                // 16 .. 1
    EXPECT_FLOAT_EQ(levels[4]["roughness"].get<float>(), 0.2f);  // Moschos figure 3.24, level 4
}

// `ibl prefilter` rejects an unknown environment, method or size and a NaN image with one line
// and writes nothing.
TEST(Cli, IblPrefilterRejectsBadInput) {
    TempDir inputs;
    Image nan(8, 4);
    nan.set(1, 1, glm::vec3(std::nanf("")));
    write_unchecked_exr(nan, inputs / "nan.exr");
    const std::pair<std::string, std::string> cases[] = {
        {"atlantis", "no environment 'atlantis'"},
        {"courtyard --method magic", "unknown prefilter 'magic'"},
        {"courtyard --distribution phong", "unknown distribution 'phong'"},
        {"courtyard --face-size 48", "--face-size 48 must be a power of two"},
        {"courtyard --samples 0", "samples 0 must be in"},
        {(inputs / "nan.exr").string(), "nan.exr: pixel (1, 1) has radiance nan"},
    };
    for (const auto& [arguments, expected] : cases) {
        TempDir out;
        const std::string size =
            arguments.find("--face-size") == std::string::npos ? " --face-size 8" : "";
        const CommandResult run =
            run_shaftlab("ibl prefilter " + arguments + size + " --out " + out.path().string());
        EXPECT_NE(run.exit_code, 0) << arguments;
        EXPECT_NE(run.output.find(expected), std::string::npos)
            << arguments << "\nexpected: " << expected << "\ngot: " << run.output;
        EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
        EXPECT_EQ(out.file_count(), 0u) << arguments << " left files behind";
    }
}

// docs/methods.md is `shaftlab methods --markdown` (scripts/methods_doc.sh): the page cannot drift
// from the registry, its parameters and what each method accepts.
TEST(Docs, MethodsPageMatchesTheRegistry) {
    const CommandResult run = run_shaftlab("methods --markdown");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const std::string page =
        read_text_file(std::filesystem::path(SHAFTLAB_SOURCE_DIR) / "docs/methods.md", "page");
    EXPECT_EQ(run.output, page) << "docs/methods.md is stale: run scripts/methods_doc.sh";
}

// Flags and choices are set by name on the command line and written back by name in the JSON.
TEST(Cli, FlagsAndChoicesAreSetAndWrittenByName) {
    TempDir out;
    const CommandResult run = run_shaftlab(
        "render --scene toplight --method march --size 32x18 --frames 1 --warmup 0 --set "
        "jitter=true --set blur=gauss5 --set samples=8 --out " +
        out.path().string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const auto json =
        nlohmann::json::parse(read_text_file(out / "toplight.march.json", "render record"));
    EXPECT_EQ(json["param_jitter"], "true");
    EXPECT_EQ(json["param_blur"], "gauss5");
    const CommandResult wrong =
        run_shaftlab("render --scene toplight --method march --size 32x18 --set blur=gaus5 --out " +
                     out.path().string());
    EXPECT_NE(wrong.exit_code, 0);
    EXPECT_NE(wrong.output.find("none, gauss5, depth_aware"), std::string::npos) << wrong.output;
    const CommandResult flag =
        run_shaftlab("render --scene toplight --method march --size 32x18 --set jitter=2 --out " +
                     out.path().string());
    EXPECT_NE(flag.exit_code, 0);
    EXPECT_NE(flag.output.find("true or false"), std::string::npos) << flag.output;
}

}  // namespace
}  // namespace sl::test
