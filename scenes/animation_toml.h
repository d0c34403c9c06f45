#pragma once
// Reading `[animation]` from a parsed TOML file (scene_file.cpp, animation.cpp).

#include <toml++/toml.h>

#include <string>

#include "scenes/animation.h"
#include "scenes/toml_reader.h"

namespace sl {

// The `[animation]` table; object names resolve against `scene`. Throws sl::Error naming the
// file, line and key.
// An object's translate, rotate and scale keys ([[objects]], [[animation.objects]]), each part
// `fallback`'s where the table has no key.
Placement read_placement(TomlTableReader& r, const Placement& fallback);

Animation read_animation(const toml::table& table, const std::string& origin, const Scene& scene);

}  // namespace sl
