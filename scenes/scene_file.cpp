#include "scenes/scene_file.h"

#include <map>
#include <memory>

#include <fmt/format.h>

#include "core/error.h"
#include "core/text.h"
#include "scenes/animation_toml.h"
#include "scenes/scene_inheritance.h"
#include "scenes/scene_objects.h"
#include "scenes/scene_sections.h"

// A scene file read whole: its base filled in (scenes/scene_inheritance.h), then each section by
// its reader (scenes/scene_sections.h), the objects and models (scenes/scene_objects.h) and the
// animation. Where files are looked up is scene_paths.cpp; the scenes known by name,
// scene_catalogue.cpp; a view written back as a scene file, scene_view.cpp.

namespace sl {

namespace fs = std::filesystem;

namespace {

// [materials.NAME] tables after the built-in "default"; `index` maps each name to its place.
void read_materials(TableReader& top, const std::string& origin, std::map<std::string, int>& index,
                    Scene& scene) {
    scene.materials.push_back(Material{.name = "default"});
    index["default"] = 0;
    const toml::table* materials = top.table("materials");
    if (!materials) {
        return;
    }
    for (const auto& [key, node] : *materials) {
        const std::string name(key.str());
        if (!node.is_table()) {
            fail("{}:{}: [materials] {}: expected a table", origin, node.source().begin.line, name);
        }
        index[name] = int(scene.materials.size());
        scene.materials.push_back(read_material(
            TableReader(*node.as_table(), origin, fmt::format("[materials.{}]", name)), name));
    }
}

// [[objects]], each a shape with its material, placement and inner boxes.
void read_objects(TableReader& top, const std::string& origin, const fs::path& base_dir,
                  const SceneSearchPaths& paths, const std::map<std::string, int>& material_index,
                  Scene& scene) {
    const toml::array* objects = top.array("objects");
    if (!objects) {
        return;
    }
    MeshCache meshes;
    for (size_t i = 0; i < objects->size(); ++i) {
        const toml::table* table = (*objects)[i].as_table();
        if (!table) {
            fail("{}: objects must be an array of tables ([[objects]])", origin);
        }
        const std::string context = fmt::format("[[objects]] #{}", i + 1);
        TableReader r(*table, origin, context);
        Object object;
        object.name = r.string("name", fmt::format("object{}", i + 1));
        object.mesh = read_shape(r, base_dir, paths, meshes);
        const std::string material = r.string("material", "default");
        const auto it = material_index.find(material);
        if (it == material_index.end()) {
            r.error("material", fmt::format("unknown material {}", quote(material)));
        }
        object.material = it->second;
        object.placement = read_placement(r, Placement{});
        object.transform = object.placed();
        object.inner_boxes = read_inner_boxes(r, origin, context);
        r.finish();
        scene.objects.push_back(std::move(object));
    }
}

// [[models]], each a model file's parts as objects.
void read_models(TableReader& top, const std::string& origin, const fs::path& base_dir,
                 const SceneSearchPaths& paths, std::map<std::string, int>& material_index,
                 Scene& scene) {
    const toml::array* models = top.array("models");
    if (!models) {
        return;
    }
    for (size_t i = 0; i < models->size(); ++i) {
        const toml::table* table = (*models)[i].as_table();
        if (!table) {
            fail("{}: models must be an array of tables ([[models]])", origin);
        }
        TableReader r(*table, origin, fmt::format("[[models]] #{}", i + 1));
        read_model(r, base_dir, paths, material_index, scene);
        r.finish();
    }
}

// The scene's lights: [light] (one spot light), or [[lights]] (any number of spot, point and
// directional lights), not both. Directional lights are resolved once the objects are read.
std::vector<LightSource> read_lights(TableReader& top, const std::string& origin) {
    const toml::array* lights = top.array("lights");
    const toml::table* light = top.table("light");
    if (lights && light) {
        fail(
            "{}:{}: [light] and [[lights]] both given: write one spot light as [light], or every "
            "light as a [[lights]] entry",
            origin, light->source().begin.line);
    }
    if (!lights) {
        if (!light) {
            fail(
                "{}: missing the light: a [light] table (one spot light) or [[lights]] entries "
                "(type = \"spot\", \"point\" or \"directional\")",
                origin);
        }
        return {read_light(TableReader(*light, origin, "[light]"))};
    }
    if (lights->empty()) {
        fail("{}: [[lights]] is empty: a scene needs at least one light", origin);
    }
    std::vector<LightSource> sources;
    for (size_t i = 0; i < lights->size(); ++i) {
        const toml::table* table = (*lights)[i].as_table();
        if (!table) {
            fail("{}: lights must be an array of tables ([[lights]])", origin);
        }
        TableReader r(*table, origin, fmt::format("[[lights]] #{}", i + 1));
        const std::string type = r.string("type", "");
        if (type == "spot") {
            sources.emplace_back(read_light(std::move(r)));
        } else if (type == "point") {
            sources.emplace_back(read_point_light(std::move(r)));
        } else if (type == "directional") {
            sources.emplace_back(read_directional_light(std::move(r)));
        } else {
            r.error("type", type.empty()
                                ? "missing: expected \"spot\", \"point\" or \"directional\""
                                : fmt::format("unknown light type {}: expected \"spot\", "
                                              "\"point\" or \"directional\"",
                                              quote(type)));
        }
    }
    // Each spot light (a point light's six faces) is a shadow map, a tree and a method instance
    // per frame: a bound that keeps a typo of a scene generator from asking for a million.
    size_t spots = 0;
    for (const LightSource& source : sources) {
        spots += std::holds_alternative<PointLight>(source) ? 6 : 1;
    }
    if (spots > kMaxSpotLights) {
        fail(
            "{}: [[lights]]: {} lights make {} spot lights (a point light counts six faces); at "
            "most {} are taken",
            origin, sources.size(), spots, kMaxSpotLights);
    }
    return sources;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& origin, const fs::path& base_dir,
                  const SceneSearchPaths& paths) {
    const toml::table root = resolve_base(parse_toml(text, origin), origin, base_dir, paths);
    TableReader top(root, origin, "");
    Scene scene;

    const toml::table* scene_table = top.table("scene");
    TableReader scene_reader(scene_table ? *scene_table : empty_table(), origin, "[scene]");
    scene.name = scene_reader.string("name", fs::path(origin).stem().string());
    scene.ambient = scene_reader.non_negative_vec3("ambient", scene.ambient);
    scene_reader.finish();

    auto required = [&](std::string_view key) -> const toml::table& {
        const toml::table* table = top.table(key);
        if (!table) {
            fail("{}: missing required table [{}]", origin, key);
        }
        return *table;
    };
    auto optional = [&](std::string_view key) -> const toml::table& {
        const toml::table* table = top.table(key);
        return table ? *table : empty_table();
    };
    scene.camera = read_camera(TableReader(required("camera"), origin, "[camera]"));
    std::vector<LightSource> lights = read_lights(top, origin);
    scene.medium = read_medium(TableReader(optional("medium"), origin, "[medium]"));
    if (const toml::table* environment = top.table("environment")) {
        scene.environment =
            read_environment(TableReader(*environment, origin, "[environment]"), base_dir, paths);
    }
    if (const toml::table* subsurface = top.table("sss")) {
        scene.subsurface = read_subsurface(TableReader(*subsurface, origin, "[sss]"));
    }
    scene.bounds = read_bounds(TableReader(optional("beamtree"), origin, "[beamtree]"));

    std::map<std::string, int> material_index;
    read_materials(top, origin, material_index, scene);
    read_objects(top, origin, base_dir, paths, material_index, scene);
    read_models(top, origin, base_dir, paths, material_index, scene);
    for (size_t i = 0; i < lights.size(); ++i) {
        if (auto* sun = std::get_if<DirectionalLight>(&lights[i])) {
            const toml::array* array = top.array("lights");
            const int line = array ? int((*array)[i].source().begin.line) : 0;
            resolve_directional_light(*sun, scene,
                                      fmt::format("{}:{}: [[lights]] #{}", origin, line, i + 1));
        }
    }
    scene.set_lights(std::move(lights));
    if (const toml::table* animation = top.table("animation")) {
        scene.animation = std::make_shared<Animation>(read_animation(*animation, origin, scene));
    }
    top.finish();
    return scene;
}

Scene load_scene_file(const fs::path& path, const SceneSearchPaths& paths) {
    Scene scene =
        parse_scene(read_text_file(path, "scene file"), path.string(), path.parent_path(), paths);
    scene.source = path;
    return scene;
}

}  // namespace sl
