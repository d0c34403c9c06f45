// Translucent-material tools (the splatting's frame rates over grids, models and distances are
// the harness's: experiments/sss_splats.toml with [sweep.scene]).
// `shaftlab sss uniformity --mesh M --points N`: weighted sample elimination on a mesh, timed,
// with the uniformity of the random start and of the result (against Rohat table 5.4).
// `shaftlab sss profile --material NAME`: a material's diffusion properties, r_max and R_d(r).
// Every command writes JSON and a Markdown table, all or nothing.

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "core/error.h"
#include "core/output_files.h"
#include "scenes/scene_file.h"
#include "sss/diffusion.h"
#include "sss/surface_samples.h"

namespace sl::app {

namespace {

namespace fs = std::filesystem;

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
    return [u, uniformity, p, profile]() -> int {
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
