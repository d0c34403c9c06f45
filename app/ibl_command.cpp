// `shaftlab ibl reference --scene S`: the GPU's environment light (spot light and medium off)
// against reference/environment_light.h, per object, with images and a heat map of the error.
// `shaftlab ibl prefilter ENV --out DIR`: bakes an environment's roughness chain with either
// prefilter (ibl/prefilter.h) and writes it as one EXR per level (the six faces side by side, GL
// order +X -X +Y -Y +Z -Z), PNG previews, and prefilter.json with the settings, per-level
// roughness and timings, the SH9 coefficients and, with --brute-force, each level's error against
// the brute-force integral of the lobe.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "core/error.h"
#include "core/metrics.h"
#include "core/output_files.h"
#include "frame/renderer.h"
#include "gl/platform.h"
#include "ibl/environment.h"
#include "methods/registry.h"
#include "reference/environment_light.h"
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

// A studio light's name (Blender's, e.g. "courtyard") or an .exr path, as scene files name them.
fs::path resolve_environment(const std::string& name) {
    const fs::path file = environment_file(name, {}, SceneSearchPaths::defaults());
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) {
        fail("no environment {} ({} does not exist)", quote(name), file.string());
    }
    return file;
}

ibl::PrefilterSettings prefilter_settings(const PrefilterArguments& a) {
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
    return settings;
}

// Level l of the chain into `out` (EXR and PNG strips), scored against the brute-force
// integral of `lobe` where the grid resolves its roughness; its JSON entry.
nlohmann::json write_level(const PrefilterArguments& a, const ibl::CubeMap& cube,
                           const ibl::PrefilteredChain& chain, size_t l, ibl::Distribution lobe,
                           OutputFiles& out) {
    const ibl::CubeMap& level = chain.levels[l];
    const std::string name = fmt::format("level_{:02}", l);
    const Image strip = ibl::faces_to_strip(level);
    out.add(name + ".exr", [&](const fs::path& file) { write_exr(strip, file); });
    out.add(name + ".png", [&](const fs::path& file) { write_png(strip, ToneMap{}, file); });
    nlohmann::json entry = {{"level", l},
                            {"face_size", level.size},
                            {"roughness", chain.roughness[l]},
                            {"seconds", chain.level_seconds[l]}};
    if (l > 0 && ibl::brute_force_resolves(chain.roughness[l], a.brute_force_grid)) {
        const auto start = std::chrono::steady_clock::now();
        const ibl::CubeMap truth =
            ibl::brute_force_level(cube, level.size, lobe, chain.roughness[l], a.brute_force_grid);
        entry["rel_rmse_vs_brute_force"] = ibl::relative_rmse(level, truth);
        entry["brute_force_seconds"] = ms_since(start) / 1000.0;
        std::printf("  level %zu: %4d^2  alpha %.3f  %.2f s  rel RMSE vs brute force %.4f\n", l,
                    level.size, chain.roughness[l], chain.level_seconds[l],
                    entry["rel_rmse_vs_brute_force"].get<double>());
    } else {
        std::printf("  level %zu: %4d^2  alpha %.3f  %.2f s\n", l, level.size, chain.roughness[l],
                    chain.level_seconds[l]);
    }
    return entry;
}

int run_prefilter(const PrefilterArguments& a) {
    const ibl::PrefilterSettings settings = prefilter_settings(a);
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
        levels.push_back(write_level(a, cube, chain, l, lobe, out));
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

struct ReferenceArguments {
    std::string scene;
    std::string out = "out/ibl-reference";
    std::string size = "320x180";
    int samples = 1024;
    bool occlusion = false;
};

// The GPU's environment light against the exact reference, overall and per object.
int run_reference(const ReferenceArguments& a) {
    int width = 0, height = 0;
    parse_size(a.size, width, height);
    if (a.samples < 1 || a.samples > 1 << 20) {
        fail("--samples {} must be in 1..{}", a.samples, 1 << 20);
    }
    const Scene scene =
        reference::environment_only_scene(load_scene(a.scene, SceneSearchPaths::defaults()));
    if (!scene.environment.enabled()) {
        fail("scene {} has no [environment]", quote(a.scene));
    }
    const auto platform = gl::create_headless_platform();
    frame::SceneRenderer renderer(scene, {.width = width, .height = height});
    const auto method = methods::create_volume_method("none");
    method->prepare(scene);
    renderer.draw(*method);  // warm-up
    const frame::FrameTimings timings = renderer.draw(*method);
    const frame::Frame frame = renderer.read_back();

    const auto start = std::chrono::steady_clock::now();
    std::vector<int> objects;
    const Image exact = reference::render_environment_reference(
        scene, *renderer.environment().loaded(), width, height,
        {.samples = a.samples, .occlusion = a.occlusion}, &objects);
    const double reference_seconds = ms_since(start) / 1000.0;

    // Relative RMSE over the pixels of each object, and over every surface pixel.
    const std::vector<double> errors =
        labelled_rel_rmse(frame.surface, exact, objects, int(scene.objects.size()));
    nlohmann::json per_object = nlohmann::json::object();
    for (size_t k = 0; k < scene.objects.size(); ++k) {
        if (std::find(objects.begin(), objects.end(), int(k)) != objects.end()) {
            const Material& m = scene.materials[size_t(scene.objects[k].material)];
            per_object[scene.objects[k].name] = {{"rel_rmse", errors[k]},
                                                 {"roughness", m.roughness},
                                                 {"f0", {m.f0.r, m.f0.g, m.f0.b}}};
        }
    }
    const double surface_rel_rmse = errors.back();
    const ErrorMetrics image_metrics = compare_images(frame.surface, exact);
    const nlohmann::json summary = {{"scene", scene.name},
                                    {"environment", scene.environment.file.string()},
                                    {"prefilter", scene.environment.prefilter.describe()},
                                    {"shading", ibl::to_string(scene.environment.shading)},
                                    {"size", {width, height}},
                                    {"samples", a.samples},
                                    {"occlusion", a.occlusion},
                                    {"surface_rel_rmse", surface_rel_rmse},
                                    {"image",
                                     {{"rel_rmse", image_metrics.rel_rmse},
                                      {"max_abs", image_metrics.max_abs},
                                      {"psnr", image_metrics.psnr}}},
                                    {"objects", per_object},
                                    {"gpu_ms_surface", timings.gpu.surface_ms},
                                    {"reference_seconds", reference_seconds}};
    OutputFiles out(a.out);
    out.add("gpu.exr", [&](const fs::path& file) { write_exr(frame.surface, file); });
    out.add("reference.exr", [&](const fs::path& file) { write_exr(exact, file); });
    out.add("gpu.png", [&](const fs::path& file) { write_png(frame.surface, ToneMap{}, file); });
    out.add("reference.png", [&](const fs::path& file) { write_png(exact, ToneMap{}, file); });
    out.add("error.png", [&](const fs::path& file) {
        write_png(error_heat_map(frame.surface, exact, 0.5), width, height, file);
    });
    out.add_text("reference.json", summary.dump(2) + "\n");
    out.commit();
    std::printf("%s (%s, %s): surface rel RMSE %.4f vs the %s reference (%d samples, %.1f s)\n",
                scene.name.c_str(), ibl::to_string(scene.environment.shading),
                ibl::to_string(scene.environment.prefilter.method), surface_rel_rmse,
                a.occlusion ? "occluded" : "unoccluded", a.samples, reference_seconds);
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
    CLI::App* reference = ibl->add_subcommand(
        "reference", "Score the GPU's environment light against the exact (Monte Carlo) reference");
    auto r = std::make_shared<ReferenceArguments>();
    reference->add_option("--scene", r->scene, "A scene with an [environment]")->required();
    reference->add_option("--out", r->out, "Output directory")->capture_default_str();
    reference->add_option("--size", r->size, "Image size WIDTHxHEIGHT")->capture_default_str();
    reference->add_option("--samples", r->samples, "Samples per pixel (specular and diffuse each)")
        ->capture_default_str();
    reference->add_flag("--occlusion", r->occlusion,
                        "Trace each sample's visibility (no real-time path models it)");
    return [a, prefilter, r, reference]() -> int {
        if (prefilter->parsed()) {
            return run_prefilter(*a);
        }
        if (reference->parsed()) {
            return run_reference(*r);
        }
        return 1;
    };
}

}  // namespace sl::app
