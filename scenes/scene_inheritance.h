#pragma once
// A scene file's text and its base scene: `[scene] base = "NAME"` makes the scene its base (a
// canonical name, multiple:N, boxes:SEED or a file) with this file's keys on top, table by table
// and key by key; [[objects]] replace the base's. Internal to scenes/.

#include <toml++/toml.h>

#include <filesystem>
#include <string>

#include "scenes/scene_file.h"

namespace sl {

// A scene's TOML text with the name its errors use and the folder its relative paths start from.
struct SceneText {
    std::string text;
    std::string origin;
    std::filesystem::path dir;
};
// A canonical name, multiple:N, boxes:SEED, or a file (relative paths from `dir` first, then as
// given); an unknown name is an error listing the names known.
SceneText scene_text(const std::string& name, const std::filesystem::path& dir,
                     const SceneSearchPaths& paths);

// Parses TOML text; malformed text is an error naming `origin` and the line.
toml::table parse_toml(const std::string& text, const std::string& origin);

// `root` with its base (and the base's bases, up to a depth of 8) filled in under it; the base's
// relative mesh and environment files keep resolving from the base's folder.
toml::table resolve_base(toml::table root, const std::string& origin,
                         const std::filesystem::path& dir, const SceneSearchPaths& paths,
                         int depth = 0);

}  // namespace sl
