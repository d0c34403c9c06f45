// `shaftlab sss bench --scene S`: frame rates of the translucent objects' splatting over splat
// grids x diffusion models (x camera distances), Rohat tables 6.1, 6.3 and 6.7 re-run here.
// `shaftlab sss uniformity --mesh M --points N`: weighted sample elimination on a mesh, timed,
// with the uniformity of the random start and of the result (against Rohat table 5.4).
// `shaftlab sss profile --material NAME`: a material's diffusion properties, r_max and R_d(r).
// Every command writes JSON and a Markdown table, all or nothing.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "core/error.h"
#include "core/output_files.h"
#include "frame/renderer.h"
#include "frame/volume_method.h"
#include "gl/platform.h"
#include "methods/registry.h"
#include "scenes/scene_file.h"
#include "sss/diffusion.h"
#include "sss/surface_samples.h"

namespace sl::app {

namespace {

namespace fs = std::filesystem;

std::vector<std::string> split(const std::string& text, char separator) {
    std::vector<std::string> parts;
    std::stringstream stream(text);
    for (std::string part; std::getline(stream, part, separator);) {
        if (!part.empty()) {
            parts.push_back(part);
        }
    }
    return parts;
}

struct BenchArguments {
    std::string scene = "sss-bunny";
    std::string grids = "30x29,35x34,40x39,45x44,50x49,55x54";
    std::string models = "dipole,multipole";
    std::string distances = "1";
    std::string size = "512x512";
    std::string radius = "profile";
    std::string out = "out/sss";
    int frames = 5;
    int warmup = 2;
    bool footprint = true;
};

int run_bench(const BenchArguments& a) {
    int width = 0, height = 0;
    parse_size(a.size, width, height);
    if (a.frames < 1 || a.warmup < 0) {
        fail("--frames must be at least 1 and --warmup at least 0, got {} and {}", a.frames,
             a.warmup);
    }
    const Scene base = load_scene(a.scene, SceneSearchPaths::defaults());
    if (!base.has_translucent_objects()) {
        fail("scene {} has no translucent object", quote(a.scene));
    }
    if (a.radius != "profile" && a.radius != "flux") {
        fail("--radius must be profile (the seed's eq. 4.3) or flux, got {}", quote(a.radius));
    }
    std::vector<std::pair<int, int>> grids;
    for (const std::string& g : split(a.grids, ',')) {
        int n = 0, m = 0;
        parse_size(g, n, m, "--grids");
        grids.emplace_back(n, m);
    }
    const std::vector<std::string> models = split(a.models, ',');
    for (const std::string& model : models) {
        if (model != "dipole" && model != "multipole") {
            fail("unknown diffusion model {} (dipole, multipole)", quote(model));
        }
    }
    std::vector<double> distances;
    for (const std::string& d : split(a.distances, ',')) {
        try {
            distances.push_back(std::stod(d));
        } catch (const std::exception&) {
            fail("--distances: {} is not a number", quote(d));
        }
        if (!(distances.back() > 0.0)) {
            fail("--distances: {} must be > 0 (a factor on the camera's distance)", d);
        }
    }
    if (grids.empty() || models.empty() || distances.empty()) {
        fail("sss bench needs at least one grid, model and distance");
    }

    const auto platform = gl::create_headless_platform();
    nlohmann::ordered_json rows = nlohmann::json::array();
    OutputFiles files(a.out);
    std::string table = fmt::format(
        "Scene `{}`, {}x{}, r_max criterion `{}`, footprint filter {}; frames per second "
        "(1000 / median GPU frame ms) and, in parentheses, the subsurface pass's ms.\n\n",
        base.name, width, height, a.radius, a.footprint ? "on" : "off");
    table += "| model | distance |";
    for (const auto& [n, m] : grids) {
        table += fmt::format(" {}×{} |", n, m);
    }
    table += "\n|---|---|";
    for (size_t i = 0; i < grids.size(); ++i) {
        table += "---|";
    }
    table += "\n";
    for (const std::string& model : models) {
        for (const double distance : distances) {
            table += fmt::format("| {} | {} |", model, distance);
            for (const auto& [n, m] : grids) {
                Scene scene = base;
                scene.subsurface.grid_x = n;
                scene.subsurface.grid_y = m;
                scene.subsurface.flux_radius = a.radius == "flux";
                scene.subsurface.footprint = a.footprint;
                for (Material& material : scene.materials) {
                    if (material.translucency) {
                        material.translucency->model =
                            model == "dipole" ? DiffusionModel::dipole : DiffusionModel::multipole;
                    }
                }
                Camera& camera = scene.camera;
                camera.position =
                    camera.target + float(distance) * (camera.position - camera.target);
                frame::SceneRenderer renderer(scene, {.width = width, .height = height});
                const auto method = methods::create_volume_method("none");
                method->prepare(scene);
                for (int i = 0; i < a.warmup; ++i) {
                    renderer.draw(*method);
                }
                std::vector<double> total, subsurface;
                for (int i = 0; i < a.frames; ++i) {
                    const frame::FrameTimings t = renderer.draw(*method);
                    total.push_back(t.gpu.total_ms());
                    subsurface.push_back(t.gpu.subsurface_ms);
                }
                const double total_ms = sl::median(total);
                const double subsurface_ms = sl::median(subsurface);
                const sss::SubsurfacePass& pass = *renderer.subsurface();
                rows.push_back({{"model", model},
                                {"distance", distance},
                                {"grid", fmt::format("{}x{}", n, m)},
                                {"gpu_ms_total", total_ms},
                                {"gpu_ms_subsurface", subsurface_ms},
                                {"fps", 1000.0 / total_ms},
                                {"r_max_mm", pass.materials().front().r_max_mm},
                                {"splat_draws", pass.stats().splat_draws},
                                {"grid_samples", pass.stats().grid_samples}});
                table += fmt::format(" {:.2f} ({:.0f}) |", 1000.0 / total_ms, subsurface_ms);
                fmt::print("{} {}x{} distance {}: {:.1f} ms GPU, subsurface {:.1f} ms\n", model, n,
                           m, distance, total_ms, subsurface_ms);
                if (n == grids[grids.size() / 2].first && m == grids[grids.size() / 2].second) {
                    const frame::Frame frame = renderer.read_back();
                    const std::string name =
                        fmt::format("{}.{}.{}x{}.d{}.png", base.name, model, n, m, distance);
                    files.add(name, [&](const fs::path& path) {
                        write_png(frame.display_srgb8, width, height, path);
                    });
                }
            }
            table += "\n";
        }
    }
    nlohmann::ordered_json report = {{"scene", base.name},
                                     {"size", a.size},
                                     {"radius", a.radius},
                                     {"footprint", a.footprint},
                                     {"frames", a.frames},
                                     {"warmup", a.warmup},
                                     {"renderer", platform->info().renderer},
                                     {"rows", rows}};
    files.add_text("sss_bench.json", report.dump(2) + "\n");
    files.add_text("sss_bench.md", table);
    for (const fs::path& path : files.commit()) {
        fmt::print("wrote {}\n", path.string());
    }
    return 0;
}

struct UniformityArguments {
    std::string mesh = "ChineseDragon-10kv.off";
    int points = 10000;
    int candidates = 5;
    int seed = 1;
    std::string out = "out/sss";
};

int run_uniformity(const UniformityArguments& a) {
    if (a.points < 2 || a.candidates < 2) {
        fail("--points must be at least 2 and --candidates at least 2");
    }
    fs::path path = a.mesh;
    if (!fs::exists(path)) {
        path = SceneSearchPaths::defaults().data / "meshes" / a.mesh;
    }
    Mesh mesh = load_mesh(path);
    validate_mesh(mesh, path.string());
    fit_mesh(mesh, 1.0f);
    const size_t n = size_t(a.points);
    const auto start = std::chrono::steady_clock::now();
    const sss::SurfaceSamples candidates = sss::random_surface_points(
        mesh, glm::mat4(1.0f), n * size_t(a.candidates), uint64_t(a.seed));
    const double random_ms = ms_since(start);
    const auto eliminate_start = std::chrono::steady_clock::now();
    const sss::SurfaceSamples uniform = sss::eliminate_samples(candidates, n);
    const double eliminate_ms = ms_since(eliminate_start);
    const sss::SurfaceSamples random =
        sss::random_surface_points(mesh, glm::mat4(1.0f), n, uint64_t(a.seed) + 1);
    const sss::Uniformity before = sss::measure_uniformity(random.positions, random.area);
    const sss::Uniformity after = sss::measure_uniformity(uniform.positions, uniform.area);
    auto json_of = [](const sss::Uniformity& u) {
        return nlohmann::ordered_json{{"relative_radius", u.relative_radius},
                                      {"min_distance", u.min_distance},
                                      {"mean_nearest", u.mean_nearest},
                                      {"nearest_cv", u.nearest_cv},
                                      {"packing_radius", u.packing_radius}};
    };
    nlohmann::ordered_json report = {{"mesh", path.filename().string()},
                                     {"triangles", mesh.triangles.size()},
                                     {"points", n},
                                     {"candidates", n * size_t(a.candidates)},
                                     {"random_ms", random_ms},
                                     {"elimination_ms", eliminate_ms},
                                     {"random", json_of(before)},
                                     {"eliminated", json_of(after)}};
    const std::string table = fmt::format(
        "| mesh | triangles | points | candidates | time (s) | relative radius random → "
        "eliminated | nearest-neighbour CV random → eliminated |\n|---|---|---|---|---|---|---|\n"
        "| {} | {} | {} | {} | {:.3f} | {:.3f} → {:.3f} | {:.3f} → {:.3f} |\n",
        path.filename().string(), mesh.triangles.size(), n, n * size_t(a.candidates),
        (random_ms + eliminate_ms) / 1000.0, before.relative_radius, after.relative_radius,
        before.nearest_cv, after.nearest_cv);
    OutputFiles files(a.out);
    files.add_text("uniformity.json", report.dump(2) + "\n");
    files.add_text("uniformity.md", table);
    fmt::print("{}", table);
    for (const fs::path& p : files.commit()) {
        fmt::print("wrote {}\n", p.string());
    }
    return 0;
}

struct ProfileArguments {
    std::string material = "marble";
    double thickness = 0.0;  // mm; 0: the dipole
    double epsilon = 0.01;
    int samples = 200;
    std::string out = "out/sss";
};

int run_profile(const ProfileArguments& a) {
    const sss::ScatteringMaterial& m = sss::material_preset(a.material);
    const sss::RgbDiffusion d = sss::RgbDiffusion::of(m);
    if (a.samples < 2) {
        fail("--samples must be at least 2, got {}", a.samples);
    }
    if (!(a.thickness >= 0.0) || !std::isfinite(a.thickness)) {
        fail("--thickness must be a finite number of mm >= 0, got {}", a.thickness);
    }
    if (!(a.epsilon > 0.0 && a.epsilon < 1.0)) {
        fail("--epsilon must lie in (0, 1), got {}", a.epsilon);
    }
    const double r_profile = sss::splat_radius(d, a.epsilon, false);
    const double r_flux = sss::splat_radius(d, a.epsilon, true);
    std::string csv = "r_mm,R_r,R_g,R_b,T_r,T_g,T_b\n";
    for (int i = 0; i < a.samples; ++i) {
        const double r = r_flux * i / (a.samples - 1);
        glm::dvec3 R, T(0.0);
        for (int c = 0; c < 3; ++c) {
            if (a.thickness > 0.0) {
                const sss::ReflectanceTransmittance rt = sss::multipole(r, a.thickness, d[c]);
                R[c] = rt.R;
                T[c] = rt.T;
            } else {
                R[c] = sss::dipole_rd(r, d[c]);
            }
        }
        csv += fmt::format("{},{},{},{},{},{},{}\n", r, R.x, R.y, R.z, T.x, T.y, T.z);
    }
    nlohmann::ordered_json channels = nlohmann::json::array();
    for (int c = 0; c < 3; ++c) {
        channels.push_back({{"sigma_t_reduced", d[c].sigma_t_reduced},
                            {"sigma_tr", d[c].sigma_tr},
                            {"albedo_reduced", d[c].albedo_reduced},
                            {"z_r", d[c].z_r},
                            {"z_v", d[c].z_v},
                            {"total_diffuse_reflectance", sss::total_diffuse_reflectance(d[c])}});
    }
    const nlohmann::ordered_json report = {{"material", m.name},
                                           {"source", m.source},
                                           {"eta", m.eta},
                                           {"A", sss::boundary_term(m.eta)},
                                           {"r_max_mm_profile", r_profile},
                                           {"r_max_mm_flux", r_flux},
                                           {"epsilon", a.epsilon},
                                           {"channels", channels}};
    OutputFiles files(a.out);
    files.add_text(m.name + ".profile.csv", csv);
    files.add_text(m.name + ".profile.json", report.dump(2) + "\n");
    fmt::print("{}: r_max {:.2f} mm (eq. 4.3), {:.2f} mm (flux)\n", m.name, r_profile, r_flux);
    for (const fs::path& p : files.commit()) {
        fmt::print("wrote {}\n", p.string());
    }
    return 0;
}

}  // namespace

Command add_sss_command(CLI::App& app) {
    CLI::App* sss = app.add_subcommand("sss", "Translucent materials: benchmarks and tools");
    sss->require_subcommand(1);
    CLI::App* bench = sss->add_subcommand(
        "bench", "Frame rates over splat grids x models (Rohat tables 6.1-6.7)");
    auto b = std::make_shared<BenchArguments>();
    bench->add_option("--scene", b->scene, "A scene with translucent objects")
        ->capture_default_str();
    bench->add_option("--grids", b->grids, "Splat grids NxM, comma separated")
        ->capture_default_str();
    bench->add_option("--models", b->models, "dipole and/or multipole")->capture_default_str();
    bench->add_option("--distances", b->distances, "Factors on the camera's distance to its target")
        ->capture_default_str();
    bench->add_option("--size", b->size, "Image size WIDTHxHEIGHT")->capture_default_str();
    bench->add_option("--radius", b->radius, "r_max criterion: profile (eq. 4.3) or flux")
        ->capture_default_str();
    bench->add_option("--frames", b->frames, "Measured frames (median)")
        ->check(CLI::Range(1, 10000))
        ->capture_default_str();
    bench->add_option("--warmup", b->warmup, "Frames before measuring")->capture_default_str();
    bench->add_flag("--no-footprint{false}", b->footprint, "The seed's point samples");
    bench->add_option("--out", b->out, "Output directory")->capture_default_str();
    CLI::App* uniformity =
        sss->add_subcommand("uniformity", "Weighted sample elimination on a mesh, timed");
    auto u = std::make_shared<UniformityArguments>();
    uniformity->add_option("--mesh", u->mesh, "An .off/.obj file or a mesh of the data directory")
        ->capture_default_str();
    uniformity->add_option("--points", u->points, "Points kept")->capture_default_str();
    uniformity->add_option("--candidates", u->candidates, "Random candidates per point kept")
        ->capture_default_str();
    uniformity->add_option("--seed", u->seed, "Random seed")->capture_default_str();
    uniformity->add_option("--out", u->out, "Output directory")->capture_default_str();
    CLI::App* profile = sss->add_subcommand("profile", "A material's profile and splat radius");
    auto p = std::make_shared<ProfileArguments>();
    profile->add_option("--material", p->material, "A preset (apple, marble, jade, ...)")
        ->capture_default_str();
    profile->add_option("--thickness", p->thickness, "Slab thickness in mm (0: the dipole)")
        ->capture_default_str();
    profile->add_option("--epsilon", p->epsilon, "The tail left out (eq. 4.3)")
        ->capture_default_str();
    profile->add_option("--samples", p->samples, "Radii written")->capture_default_str();
    profile->add_option("--out", p->out, "Output directory")->capture_default_str();
    return [b, bench, u, uniformity, p, profile]() -> int {
        if (bench->parsed()) {
            return run_bench(*b);
        }
        if (uniformity->parsed()) {
            return run_uniformity(*u);
        }
        if (profile->parsed()) {
            return run_profile(*p);
        }
        return 1;
    };
}

}  // namespace sl::app
