// `shaftlab ibl prefilter ENV --out DIR`: bakes an environment's roughness chain with either
// prefilter (ibl/prefilter.h) and writes it as one EXR per level (the six faces side by side, GL
// order +X -X +Y -Y +Z -Z), PNG previews, and prefilter.json with the settings, per-level
// roughness and timings, the SH9 coefficients and, with --brute-force, each level's error against
// the brute-force integral of the lobe.

#include <chrono>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "core/error.h"
#include "core/output_files.h"
#include "ibl/environment.h"
#include "scenes/scene_file.h"

namespace sl::app {

namespace {

namespace fs = std::filesystem;

struct PrefilterArguments {
    std::string environment;
    std::string out = "out/prefilter";
    std::string method = "importance";
    std::string distribution = "ggx";
    int samples = 256;
    int face_size = 512;
    int min_face_size = 8;
    int threads = 0;
    bool unfiltered = false;
    float rotation = 0.0f;
    int brute_force_grid = 0;
};

// A studio light's name (Blender's, e.g. "courtyard") or an .exr path.
fs::path resolve_environment(const std::string& name) {
    std::error_code ec;
    if (fs::is_regular_file(name, ec)) {
        return name;
    }
    const fs::path studio = SceneSearchPaths::defaults().environments / (name + ".exr");
    if (fs::is_regular_file(studio, ec)) {
        return studio;
    }
    fail("no environment '{}' (neither a file nor {})", name, studio.string());
}

int run_prefilter(const PrefilterArguments& a) {
    ibl::PrefilterSettings settings;
    settings.method = ibl::parse_prefilter_method(a.method);
    settings.distribution = ibl::parse_distribution(a.distribution);
    settings.samples = a.samples;
    settings.min_face_size = a.min_face_size;
    settings.threads = a.threads;
    settings.filtered = !a.unfiltered;
    if (a.face_size < 1 || a.face_size > 4096 || (a.face_size & (a.face_size - 1))) {
        fail("--face-size {} must be a power of two in 1..4096", a.face_size);
    }
    if (a.samples < 1 || a.samples > 1 << 20) {
        fail("prefilter: samples {} must be in 1..{}", a.samples, 1 << 20);
    }
    if (a.brute_force_grid < 0 || a.brute_force_grid > 1024) {
        fail("--brute-force {} must be a grid size in 0..1024", a.brute_force_grid);
    }
    const fs::path path = resolve_environment(a.environment);

    const auto load_start = std::chrono::steady_clock::now();
    const ibl::CubeMap cube =
        ibl::cube_from_equirect(ibl::load_equirect(path), a.face_size, a.rotation);
    const double load_ms = ms_since(load_start);
    std::printf("%s -> cube %d^2 in %.0f ms; prefilter: %s, %s threads\n", path.c_str(),
                a.face_size, load_ms, settings.describe().c_str(),
                a.threads ? std::to_string(a.threads).c_str() : "all");
    const ibl::PrefilteredChain chain = ibl::prefilter(cube, settings);
    const ibl::Sh9 sh = ibl::project_sh9(cube);

    nlohmann::json levels = nlohmann::json::array();
    OutputFiles out(a.out);
    // The lobe the level stands for: Beckmann at the table's roughness for the seed's cone
    // levels (the BRDF it shades with), the sampled distribution for the importance path.
    const ibl::Distribution lobe = settings.method == ibl::PrefilterMethod::cone
                                       ? ibl::Distribution::beckmann
                                       : settings.distribution;
    for (size_t l = 0; l < chain.levels.size(); ++l) {
        const ibl::CubeMap& level = chain.levels[l];
        const std::string name = fmt::format("level_{:02}", l);
        const Image strip = ibl::faces_to_strip(level);
        out.add(name + ".exr", [&](const fs::path& file) { write_exr(strip, file); });
        out.add(name + ".png", [&](const fs::path& file) { write_png(strip, ToneMap{}, file); });
        nlohmann::json entry = {{"level", l},
                                {"face_size", level.size},
                                {"roughness", chain.roughness[l]},
                                {"seconds", chain.level_seconds[l]}};
        // The lobe must span a few grid cells for the brute force to resolve it.
        const float cell = 2.0f / float(std::max(a.brute_force_grid, 1));
        if (a.brute_force_grid > 0 && l > 0 && chain.roughness[l] >= 4.0f * cell) {
            const auto start = std::chrono::steady_clock::now();
            const ibl::CubeMap truth = ibl::brute_force_level(
                cube, level.size, lobe, chain.roughness[l], a.brute_force_grid);
            entry["rel_rmse_vs_brute_force"] = ibl::relative_rmse(level, truth);
            entry["brute_force_seconds"] = ms_since(start) / 1000.0;
            std::printf("  level %zu: %4d^2  alpha %.3f  %.2f s  rel RMSE vs brute force %.4f\n", l,
                        level.size, chain.roughness[l], chain.level_seconds[l],
                        entry["rel_rmse_vs_brute_force"].get<double>());
        } else {
            std::printf("  level %zu: %4d^2  alpha %.3f  %.2f s\n", l, level.size,
                        chain.roughness[l], chain.level_seconds[l]);
        }
        levels.push_back(entry);
    }
    nlohmann::json sh_json = nlohmann::json::array();
    for (const glm::vec3& c : sh.coefficients)
        sh_json.push_back({c.r, c.g, c.b});
    const nlohmann::json summary = {
        {"environment", path.string()},
        {"face_size", a.face_size},
        {"rotation_degrees", a.rotation},
        {"method", ibl::to_string(settings.method)},
        {"distribution", ibl::to_string(settings.distribution)},
        {"lobe", ibl::to_string(lobe)},
        {"samples", settings.samples},
        {"filtered", settings.filtered},
        {"threads", a.threads},
        {"load_ms", load_ms},
        {"prefilter_seconds", chain.seconds},
        {"levels", levels},
        {"sh9", sh_json},
        {"strip_layout", "faces side by side: +X -X +Y -Y +Z -Z, GL texel order"}};
    out.add_text("prefilter.json", summary.dump(2) + "\n");
    out.commit();
    std::printf("prefiltered %zu levels in %.2f s -> %s\n", chain.levels.size(), chain.seconds,
                a.out.c_str());
    return 0;
}

}  // namespace

Command add_ibl_command(CLI::App& app) {
    CLI::App* ibl = app.add_subcommand("ibl", "Image-based lighting tools");
    ibl->require_subcommand(1);
    CLI::App* prefilter = ibl->add_subcommand(
        "prefilter", "Bake an environment's roughness chain (EXR per level, timings, SH9)");
    auto a = std::make_shared<PrefilterArguments>();
    prefilter
        ->add_option("environment", a->environment,
                     "Equirectangular .exr, or a studio light's name (courtyard, forest, ...)")
        ->required();
    prefilter->add_option("--out", a->out, "Output directory")->capture_default_str();
    prefilter
        ->add_option("--method", a->method, "importance (GGX/Beckmann) or cone (Moschos alg. 6)")
        ->capture_default_str();
    prefilter->add_option("--distribution", a->distribution, "ggx or beckmann (importance)")
        ->capture_default_str();
    prefilter->add_option("--samples", a->samples, "Samples per texel")->capture_default_str();
    prefilter->add_option("--face-size", a->face_size, "Level-0 face size (power of two)")
        ->capture_default_str();
    prefilter->add_option("--min-face-size", a->min_face_size, "Importance: the chain stops here")
        ->capture_default_str();
    prefilter->add_option("--threads", a->threads, "0: every hardware thread")
        ->capture_default_str();
    prefilter->add_flag("--no-filtered", a->unfiltered,
                        "Importance: read level 0 only (no filtered importance sampling)");
    prefilter->add_option("--rotation", a->rotation, "Degrees about +y")->capture_default_str();
    prefilter
        ->add_option("--brute-force", a->brute_force_grid,
                     "Score each level against the brute-force lobe integral on this grid "
                     "per face (slow; 0: off)")
        ->capture_default_str();
    return [a, prefilter]() -> int {
        if (prefilter->parsed()) {
            return run_prefilter(*a);
        }
        return 1;
    };
}

}  // namespace sl::app
