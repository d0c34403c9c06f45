// The scenes that load by name (scenes/scene_file.h): the canonical, animated, effect and real
// scenes from scenes/, and the generated families multiple:N and boxes:SEED.

#include <cstdlib>

#include "core/error.h"
#include "core/text.h"
#include "scenes/scene_file.h"
#include "scenes/scene_inheritance.h"

namespace sl {

namespace fs = std::filesystem;

bool is_generated_scene_name(const std::string& name) {
    return name.starts_with("multiple:") || name.starts_with("boxes:");
}

std::string generated_scene_text(const std::string& name) {
    // The integer after the family's prefix, in [lo, hi].
    auto number = [&](std::string_view prefix, long lo, long hi, const char* what) {
        const std::string text = name.substr(prefix.size());
        char* end = nullptr;
        const long value = std::strtol(text.c_str(), &end, 10);
        if (text.empty() || *end != '\0' || value < lo || value > hi) {
            fail("scene {}: {} must be an integer in [{}, {}]", quote(name), what, lo, hi);
        }
        return int(value);
    };
    if (name.starts_with("multiple:")) {
        return generate_multiple_scene(
            number("multiple:", 1, kMultipleMaxCount, "N in multiple:N"));
    }
    if (name.starts_with("boxes:")) {
        return generate_boxes_scene(number("boxes:", 0, kBoxesMaxSeed, "SEED in boxes:SEED"));
    }
    fail("scene {} is not a generated scene (multiple:N or boxes:SEED)", quote(name));
}

std::vector<std::string> canonical_scene_names() {
    return {"toplight", "parallel", "multiple"};
}

std::vector<std::string> animated_scene_names() {
    return {"toplight-orbit", "parallel-walk", "multiple-moving"};
}

std::vector<std::string> effect_scene_names() {
    return {"ibl-spheres", "sss-bunny", "sss-dragon", "sss-shaft"};
}

std::vector<std::string> real_scene_names() {
    return {"house", "house-sweep", "engine", "engine-orbit", "arena", "arena-sweep"};
}

std::vector<std::string> light_scene_names() {
    return {"room", "parallel-lamps", "house-morning", "parallel-lamps-swing", "house-day"};
}

std::vector<std::string> named_scene_names() {
    std::vector<std::string> names = canonical_scene_names();
    for (const auto& group :
         {animated_scene_names(), effect_scene_names(), real_scene_names(), light_scene_names()}) {
        names.insert(names.end(), group.begin(), group.end());
    }
    return names;
}

Scene load_scene(const std::string& name, const SceneSearchPaths& paths) {
    const SceneText text = scene_text(name, {}, paths);
    Scene scene = parse_scene(text.text, text.origin, text.dir, paths);
    if (!is_generated_scene_name(name)) {
        scene.source = text.origin;
    }
    return scene;
}

}  // namespace sl
