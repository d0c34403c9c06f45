#include "viewer/view_path.h"

#include <fstream>
#include <sstream>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "scenes/toml_reader.h"

namespace sl::viewer {

template <typename T>
std::optional<T> ViewPath::Track<T>::at(int frame) const {
    if (keys.empty()) {
        return std::nullopt;
    }
    if (frame <= keys.front().first) {
        return keys.front().second;
    }
    for (size_t i = 1; i < keys.size(); ++i) {
        if (frame == keys[i].first) {
            return keys[i].second;  // exact at its key
        }
        if (frame < keys[i].first) {
            const auto& [f0, v0] = keys[i - 1];
            const auto& [f1, v1] = keys[i];
            const float t = float(frame - f0) / float(f1 - f0);
            return v0 + t * (v1 - v0);
        }
    }
    return keys.back().second;
}

ViewPath ViewPath::load(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        fail("{}: cannot read the path file", path.string());
    }
    std::ostringstream text;
    text << in.rdbuf();
    return parse(text.str(), path.string());
}

ViewPath ViewPath::parse(const std::string& text, const std::string& origin) {
    toml::table root;
    try {
        root = toml::parse(text, origin);
    } catch (const toml::parse_error& e) {
        fail("{}:{}: malformed TOML: {}", origin, e.source().begin.line, e.description());
    }
    TomlTableReader top(root, origin, "");
    const toml::array* keys = top.array("key");
    top.finish();
    if (!keys || keys->empty()) {
        fail("{}: a path needs at least one [[key]]", origin);
    }
    ViewPath path;
    int previous = -1;
    for (size_t i = 0; i < keys->size(); ++i) {
        const toml::table* table = (*keys)[i].as_table();
        if (!table) {
            fail("{}: key must be an array of tables ([[key]])", origin);
        }
        TomlTableReader r(*table, origin, fmt::format("[[key]] #{}", i + 1));
        const int frame = r.integer_in("frame", -1, 0, 1 << 24);
        if (!r.has("frame")) {
            r.error("frame", "missing: every key needs its frame");
        }
        if (frame <= previous) {
            r.error("frame", fmt::format("{} is not after the previous key's {}", frame, previous));
        }
        previous = frame;
        path.last_frame_ = frame;
        auto vec3 = [&](const char* key, Track<glm::vec3>& track) {
            if (r.has(key)) {
                track.keys.emplace_back(frame, r.vec3(key));
            }
        };
        vec3("camera_position", path.camera_position_);
        vec3("camera_target", path.camera_target_);
        vec3("light_position", path.light_position_);
        vec3("light_target", path.light_target_);
        if (r.has("cone_angle")) {
            path.cone_angle_.keys.emplace_back(frame,
                                               float(r.number_in("cone_angle", 0, 0, 89, true)));
        }
        r.finish();
    }
    return path;
}

void ViewPath::apply(int frame, Scene& scene) const {
    if (auto p = camera_position_.at(frame))
        scene.camera.position = *p;
    if (auto p = camera_target_.at(frame))
        scene.camera.target = *p;
    if (auto p = light_position_.at(frame))
        scene.light.position = *p;
    if (auto p = light_target_.at(frame))
        scene.light.target = *p;
    if (auto a = cone_angle_.at(frame))
        scene.light.cone_half_angle_degrees = *a;
    if (glm::length(scene.camera.target - scene.camera.position) <= 0.0f ||
        glm::length(scene.light.target - scene.light.position) <= 0.0f) {
        fail("path at frame {}: a target coincides with its position", frame);
    }
}

}  // namespace sl::viewer
