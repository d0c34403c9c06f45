#include "scenes/variations.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <regex>

#include <fmt/ranges.h>

#include "core/error.h"
#include "core/suggest.h"
#include "core/text.h"

namespace sl {

namespace {

// The largest splat grid side (Rohat's tables go to 95); also keeps N x M within an int.
constexpr int kMaxGridSide = 4096;

bool parse_grid(const std::string& value, int& n, int& m) {
    static const std::regex pattern(R"((\d{1,4})x(\d{1,4}))");
    std::smatch match;
    if (!std::regex_match(value, match, pattern)) {
        return false;
    }
    n = std::stoi(match[1]);
    m = std::stoi(match[2]);
    return n >= 1 && m >= 1 && n <= kMaxGridSide && m <= kMaxGridSide;
}

bool parse_factor(const std::string& value, double& factor) {
    char* end = nullptr;
    factor = std::strtod(value.c_str(), &end);
    return !value.empty() && *end == '\0' && std::isfinite(factor) && factor > 0.0 && factor <= 1e3;
}

}  // namespace

const std::vector<SceneVariation>& scene_variations() {
    static const std::vector<SceneVariation> variations = {
        {"sss_grid", "a splat grid NxM with sides in 1..4096"},
        {"sss_model", "dipole or multipole"},
        {"sss_radius", "profile or flux"},
        {"sss_footprint", "true or false"},
        {"camera_distance", "a factor in (0, 1000] on the camera's distance to its target", true},
    };
    return variations;
}

bool is_scene_variation(const std::string& name) {
    const auto& all = scene_variations();
    return std::any_of(all.begin(), all.end(),
                       [&](const SceneVariation& v) { return v.name == name; });
}

bool scene_variation_changes_view(const std::string& name) {
    const auto& all = scene_variations();
    return std::any_of(all.begin(), all.end(),
                       [&](const SceneVariation& v) { return v.name == name && v.changes_view; });
}

std::string scene_variation_error(const std::string& name, const std::string& value) {
    const auto& all = scene_variations();
    const auto found = std::find_if(all.begin(), all.end(),
                                    [&](const SceneVariation& v) { return v.name == name; });
    if (found == all.end()) {
        std::vector<std::string> names;
        for (const SceneVariation& v : all) {
            names.push_back(v.name);
        }
        return fmt::format("unknown scene variation {}{} (known: {})", quote(name),
                           did_you_mean(name, names), fmt::join(names, ", "));
    }
    int n = 0, m = 0;
    double factor = 0.0;
    const bool fine = name == "sss_grid"          ? parse_grid(value, n, m)
                      : name == "sss_model"       ? value == "dipole" || value == "multipole"
                      : name == "sss_radius"      ? value == "profile" || value == "flux"
                      : name == "sss_footprint"   ? value == "true" || value == "false"
                      : name == "camera_distance" ? parse_factor(value, factor)
                                                  : false;
    return fine ? std::string()
                : fmt::format("{} {}: expected {}", name, quote(value), found->values);
}

void apply_scene_variation(Scene& scene, const std::string& name, const std::string& value) {
    if (const std::string error = scene_variation_error(name, value); !error.empty()) {
        fail("{}", error);
    }
    if (name.starts_with("sss_") && !scene.has_translucent_objects()) {
        fail("{} {}: scene {} has no translucent object", name, quote(value), quote(scene.name));
    }
    if (name == "sss_grid") {
        parse_grid(value, scene.subsurface.grid_x, scene.subsurface.grid_y);
    } else if (name == "sss_model") {
        for (Material& material : scene.materials) {
            if (material.translucency) {
                material.translucency->model =
                    value == "dipole" ? DiffusionModel::dipole : DiffusionModel::multipole;
            }
        }
    } else if (name == "sss_radius") {
        scene.subsurface.flux_radius = value == "flux";
    } else if (name == "sss_footprint") {
        scene.subsurface.footprint = value == "true";
    } else if (name == "camera_distance") {
        double factor = 1.0;
        parse_factor(value, factor);
        Camera& camera = scene.camera;
        camera.position = camera.target + float(factor) * (camera.position - camera.target);
    }
}

}  // namespace sl
