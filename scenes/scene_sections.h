#pragma once
// The readers of a scene file's sections (scenes/scene_file.h documents the format): each takes
// its table, validates every key as it reads it and finishes the table, so an unknown or bad key
// is an error naming the file, line, table and key. Internal to scenes/.

#include <toml++/toml.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/text.h"
#include "scenes/scene.h"
#include "scenes/scene_file.h"
#include "scenes/toml_reader.h"

namespace sl {

using TableReader = TomlTableReader;

// An empty table, for an optional section that is absent (its defaults still get checked).
const toml::table& empty_table();

// The value of `key` as one of `names`, or `fallback` when the key is absent.
template <typename Enum>
Enum parse_enum(TableReader& reader, std::string_view key, Enum fallback,
                const std::vector<std::pair<std::string, Enum>>& names) {
    const std::string value = reader.string(key, "");
    if (value.empty() && !reader.has(key)) {
        return fallback;
    }
    for (const auto& [name, e] : names) {
        if (name == value) {
            return e;
        }
    }
    std::string known;
    for (const auto& [name, e] : names) {
        known += (known.empty() ? "" : ", ") + name;
    }
    reader.error(key, fmt::format("unknown value {} (expected one of: {})", quote(value), known));
}

Camera read_camera(TableReader r);
SpotLight read_light(TableReader r);
// A [[lights]] entry of type "point" (its `type` key already read).
PointLight read_point_light(TableReader r);
// A [[lights]] entry of type "directional": direction (normalised), irradiance and entry; its
// region (and its entry when not given: then NaN) is resolved once the objects are read
// (resolve_directional_light).
DirectionalLight read_directional_light(TableReader r);
// The region of a directional light read above: the box around the scene's objects and its
// camera's position; and the entry plane touching it on the light's side where none was given.
// Throws sl::Error naming `where` when the entry plane leaves no part of the region beyond it.
void resolve_directional_light(DirectionalLight& light, const Scene& scene,
                               const std::string& where);
Medium read_medium(TableReader r);
Environment read_environment(TableReader r, const std::filesystem::path& base_dir,
                             const SceneSearchPaths& paths);
Material read_material(TableReader r, std::string name);
Subsurface read_subsurface(TableReader r);
BoundsSettings read_bounds(TableReader r);

}  // namespace sl
