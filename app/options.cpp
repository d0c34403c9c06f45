#include "app/options.h"

#include <regex>

#include "core/error.h"
#include "core/text.h"
#include "scenes/animation.h"
#include "scenes/scene_file.h"

namespace sl::app {

frame::ShadowSettings CommonOptions::shadow_settings() const {
    return {.filter = frame::parse_shadow_filter(shadow),
            .map_size = shadow_map_size,
            .radius = pcf_radius};
}

void add_common_options(CLI::App& command, CommonOptions& o, Common which) {
    if (which & Common::scene) {
        command
            .add_option("--scene", o.scene,
                        "Canonical name, multiple:N, boxes:SEED, or a .toml file")
            ->required();
    }
    if (which & Common::time) {
        command.add_option(
            "--time", o.time,
            "Seconds into the scene's [animation]: the still frame of a moving scene");
    }
    if (which & Common::method) {
        command
            .add_option("--method", o.method, "Volumetric method (`shaftlab methods` lists them)")
            ->capture_default_str();
        command.add_option("--set", o.settings,
                           "Set a parameter of the method, NAME=VALUE (repeatable; `shaftlab "
                           "methods` lists them)");
    }
    if (which & Common::size) {
        command.add_option("--size", o.size, "Image size WIDTHxHEIGHT")->capture_default_str();
    }
    if (which & Common::out) {
        command.add_option("--out", o.out, "Output directory")->capture_default_str();
    }
    if (which & Common::shadow) {
        command.add_option("--shadow", o.shadow, "Shadow map filter")
            ->check(CLI::IsMember({"hard", "pcf", "vsm"}))
            ->capture_default_str();
        command.add_option("--pcf-radius", o.pcf_radius, "PCF taps or VSM blur radius r: (2r+1)^2")
            ->check(CLI::Range(0, 8))
            ->capture_default_str();
        command.add_option("--shadow-map-size", o.shadow_map_size, "Shadow map resolution")
            ->check(CLI::Range(16, 16384))
            ->capture_default_str();
    }
    if (which & Common::warmup) {
        command.add_option("--warmup", o.warmup, "Frames drawn before measuring")
            ->check(CLI::Range(0, 1000))
            ->capture_default_str();
    }
}

Scene load_scene_at(const std::string& name, const std::optional<double>& time) {
    const Scene scene = load_scene(name, SceneSearchPaths::defaults());
    if (!time) {
        return scene;
    }
    if (!scene.animation) {
        fail("--time {}: scene {} has no [animation]", *time, quote(name));
    }
    return scene_at(scene, *time);
}

void parse_size(const std::string& text, int& width, int& height, const char* option) {
    static const std::regex pattern(R"((\d+)x(\d+))");
    std::smatch match;
    if (!std::regex_match(text, match, pattern)) {
        fail("{} {}: expected WIDTHxHEIGHT with positive integers, e.g. 640x360", option,
             quote(text));
    }
    // Past five digits a side is out of range whatever it is (and would overflow an int).
    auto side = [](const std::string& digits) {
        return digits.size() > 5 ? 100000 : std::stoi(digits);
    };
    width = side(match[1]);
    height = side(match[2]);
    if (width < 1 || height < 1 || width > 16384 || height > 16384) {
        fail("{} {}: width and height must be in 1..16384", option, quote(text));
    }
}

}  // namespace sl::app
