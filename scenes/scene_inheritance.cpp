#include "scenes/scene_inheritance.h"

#include <algorithm>
#include <optional>
#include <vector>

#include "core/error.h"
#include "core/suggest.h"
#include "core/text.h"

namespace sl {

namespace fs = std::filesystem;

namespace {

// Keys of `over` replace those of `base`; tables merge key by key, arrays ([[objects]]) replace.
// Done as `base` filling in what `over` lacks, so that `over`'s own nodes keep their lines for
// error messages (a copied node loses its source).
void fill_from(toml::table& over, const toml::table& base) {
    for (const auto& [key, node] : base) {
        toml::node* mine = over.get(key);
        if (!mine) {
            over.insert(key, node);
        } else if (mine->is_table() && node.is_table()) {
            fill_from(*mine->as_table(), *node.as_table());
        }
    }
}

}  // namespace

SceneText scene_text(const std::string& name, const fs::path& dir, const SceneSearchPaths& paths) {
    if (is_generated_scene_name(name)) {
        return {generated_scene_text(name), name, paths.scenes};
    }
    const auto names = named_scene_names();
    if (std::find(names.begin(), names.end(), name) != names.end()) {
        const fs::path path = paths.scenes / (name + ".toml");
        return {read_text_file(path, "scene file"), path.string(), paths.scenes};
    }
    if (fs::path(name).extension() == ".toml" || name.find('/') != std::string::npos) {
        fs::path path = name;
        std::error_code ec;
        if (path.is_relative() && !dir.empty() && fs::is_regular_file(dir / path, ec)) {
            path = dir / path;
        }
        return {read_text_file(path, "scene file"), path.string(), path.parent_path()};
    }
    const auto listed = [](const std::vector<std::string>& group) {
        std::string list;
        for (const std::string& member : group) {
            list += (list.empty() ? "" : ", ") + member;
        }
        return list;
    };
    fail(
        "unknown scene {}{} (canonical: {}, multiple:N; random: boxes:SEED; animated: {}; "
        "effects: {}; real: {}; lights: {}; or a .toml file)",
        quote(name), did_you_mean(name, names), listed(canonical_scene_names()),
        listed(animated_scene_names()), listed(effect_scene_names()), listed(real_scene_names()),
        listed(light_scene_names()));
}

toml::table parse_toml(const std::string& text, const std::string& origin) {
    try {
        return toml::parse(text, origin);
    } catch (const toml::parse_error& e) {
        fail("{}:{}: malformed TOML: {}", origin, e.source().begin.line, e.description());
    }
}

// `[scene] base = "NAME"`: the scene is its base (a canonical name, multiple:N or a file,
// relative to this file's folder) with this file's keys on top. The base's mesh files keep
// resolving from the base's folder. Bases may chain, up to a depth of 8.
toml::table resolve_base(toml::table root, const std::string& origin, const fs::path& dir,
                         const SceneSearchPaths& paths, int depth) {
    toml::table* scene = root["scene"].as_table();
    const toml::node* base_node = scene ? scene->get("base") : nullptr;
    if (!base_node) {
        return root;
    }
    const std::optional<std::string> base_name = base_node->value<std::string>();
    if (!base_name || base_name->empty()) {
        fail("{}:{}: [scene] base: expected the name or file of a scene", origin,
             base_node->source().begin.line);
    }
    if (depth >= 8) {
        fail("{}: [scene] base: bases nest deeper than 8 (a cycle?)", origin);
    }
    SceneText base;
    try {
        base = scene_text(*base_name, dir, paths);
    } catch (const Error& e) {
        fail(
            "{}:{}: [scene] base: {} (a base is a canonical scene's name, multiple:N, "
            "boxes:SEED or a scene file)",
            origin, base_node->source().begin.line, e.what());
    }
    toml::table merged =
        resolve_base(parse_toml(base.text, base.origin), base.origin, base.dir, paths, depth + 1);
    if (toml::array* objects = merged["objects"].as_array()) {
        for (toml::node& object : *objects) {
            toml::table* table = object.as_table();
            const std::optional<std::string> file =
                table ? (*table)["file"].value<std::string>() : std::nullopt;
            std::error_code ec;
            if (file && fs::path(*file).is_relative() &&
                fs::is_regular_file(base.dir / *file, ec)) {
                table->insert_or_assign("file", fs::absolute(base.dir / *file).string());
            }
        }
    }
    if (toml::table* environment = merged["environment"].as_table()) {
        const std::optional<std::string> file = (*environment)["file"].value<std::string>();
        std::error_code ec;
        if (file && fs::path(*file).is_relative() && fs::is_regular_file(base.dir / *file, ec)) {
            environment->insert_or_assign("file", fs::absolute(base.dir / *file).string());
        }
    }
    // The lights are one thing written two ways: a scene's own [[lights]] replaces its base's
    // [light], and its own [light] its base's [[lights]] (a [light] over a [light] merges key by
    // key, as every table does).
    if (root.contains("lights")) {
        merged.erase("light");
    }
    if (root.contains("light")) {
        merged.erase("lights");
    }
    scene->erase("base");
    if (toml::table* merged_scene = merged["scene"].as_table()) {
        merged_scene->erase("name");  // the derived scene is named by its own file
    }
    fill_from(root, merged);
    return root;
}

}  // namespace sl
