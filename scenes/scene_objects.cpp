#include "scenes/scene_objects.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/glob.h"
#include "core/text.h"
#include "scenes/animation_toml.h"
#include "scenes/mesh.h"
#include "scenes/model.h"
#include "scenes/pk3.h"
#include "scenes/q3_bsp.h"

namespace sl {

namespace fs = std::filesystem;

fs::path resolve_mesh_path(const std::string& file, const fs::path& base_dir,
                           const SceneSearchPaths& paths, TableReader& r) {
    // An absolute path is taken as it is; a relative one is looked for beside the scene file,
    // then among the extracted meshes.
    std::vector<fs::path> candidates;
    if (fs::path(file).is_absolute()) {
        candidates = {fs::path(file)};
    } else {
        candidates = {base_dir / file, paths.data / "meshes" / file, paths.data / file};
    }
    std::string tried;
    for (const fs::path& candidate : candidates) {
        std::error_code ec;
        if (fs::is_regular_file(candidate, ec)) {
            return candidate;
        }
        tried += (tried.empty() ? "" : ", ") + candidate.string();
    }
    r.error("file", fmt::format("mesh {} not found (tried {})", quote(file), tried));
}

std::shared_ptr<const Mesh> read_shape(TableReader& r, const fs::path& base_dir,
                                       const SceneSearchPaths& paths, MeshCache& cache) {
    const std::string shape = r.string("shape");
    auto positive = [&](std::string_view key, double fallback) {
        return float(r.number_in(key, fallback, 0.0, 1e9, true));
    };
    auto positive_vec3 = [&](std::string_view key, glm::vec3 fallback) {
        const glm::vec3 v = r.vec3(key, fallback);
        if (!(v.x > 0 && v.y > 0 && v.z > 0)) {
            r.error(key, "components must be positive");
        }
        return v;
    };
    if (shape == "mesh") {
        const std::string file = r.string("file");
        const double fit = r.number_in("fit", 0.0, 0.0, 1e9);
        const fs::path path = resolve_mesh_path(file, base_dir, paths, r);
        const std::string key = fmt::format("{}|{}", path.string(), fit);
        if (auto it = cache.find(key); it != cache.end()) {
            return it->second;
        }
        Mesh mesh = load_mesh(path);
        if (fit > 0.0) {
            fit_mesh(mesh, float(fit));
        }
        return cache[key] = std::make_shared<const Mesh>(std::move(mesh));
    }
    if (shape == "box") {
        return std::make_shared<const Mesh>(make_box(positive_vec3("size", glm::vec3(1.0f))));
    }
    // Procedural shapes stay within kMaxShapeTriangles; finer ones are a mesh file's job.
    if (shape == "sphere") {
        const float radius = positive("radius", 0.5);
        // segments × segments / 2 quads: 1024 segments make 2^20 triangles.
        return std::make_shared<const Mesh>(
            make_sphere(radius, r.integer_in("segments", 32, 4, 1024)));
    }
    if (shape == "cylinder") {
        const float radius = positive("radius", 0.5);
        const float height = positive("height", 1.0);
        return std::make_shared<const Mesh>(
            make_cylinder(radius, height, r.integer_in("segments", 32, 3, 4096)));
    }
    if (shape == "torus") {
        const float major = positive("major_radius", 0.5);
        const float minor = positive("minor_radius", 0.2);
        if (minor >= major) {
            r.error("minor_radius", "must be smaller than major_radius");
        }
        const int major_segments = r.integer_in("major_segments", 48, 3, 4096);
        const int minor_segments = r.integer_in("minor_segments", 24, 3, 4096);
        if (2LL * major_segments * minor_segments > kMaxShapeTriangles) {
            r.error("minor_segments",
                    fmt::format("major_segments × minor_segments = {} × {} makes {} triangles, "
                                "at most {} for a procedural shape (use a mesh file)",
                                major_segments, minor_segments,
                                2LL * major_segments * minor_segments, kMaxShapeTriangles));
        }
        return std::make_shared<const Mesh>(
            make_torus(major, minor, major_segments, minor_segments));
    }
    if (shape == "plane") {
        const glm::vec3 size = r.vec3("size", glm::vec3(10.0f, 0.0f, 10.0f));
        if (!(size.x > 0 && size.z > 0) || size.y != 0) {
            r.error("size", "expected [x, 0, z] with x and z positive");
        }
        return std::make_shared<const Mesh>(make_plane({size.x, size.z}));
    }
    r.error("shape", fmt::format("unknown shape {} (expected mesh, box, sphere, cylinder, "
                                 "torus or plane)",
                                 quote(shape)));
}

std::vector<Box> read_inner_boxes(TableReader& r, const std::string& origin,
                                  const std::string& context) {
    std::vector<Box> boxes;
    const toml::array* array = r.array("inner");
    if (!array) {
        return boxes;
    }
    for (size_t i = 0; i < array->size(); ++i) {
        const toml::table* table = (*array)[i].as_table();
        if (!table) {
            r.error("inner", "expected an array of tables { min = [..], max = [..] }");
        }
        TableReader box(*table, origin, fmt::format("{} inner[{}]", context, i));
        Box b{box.vec3("min"), box.vec3("max")};
        if (!(b.min.x < b.max.x && b.min.y < b.max.y && b.min.z < b.max.z)) {
            box.error("max", "must exceed min in every component");
        }
        box.finish();
        boxes.push_back(b);
    }
    return boxes;
}

namespace {

// Glob patterns ('*' any run, '?' one character) over a part's name or its material's name.
std::vector<std::string> read_patterns(TableReader& r, std::string_view key,
                                       std::vector<std::string> fallback) {
    const toml::array* array = r.array(key);
    if (!array) {
        return fallback;
    }
    std::vector<std::string> patterns;
    for (const toml::node& node : *array) {
        const auto text = node.value<std::string_view>();
        if (!text) {
            r.error(key, "expected an array of name patterns (strings)");
        }
        patterns.emplace_back(*text);
    }
    return patterns;
}

bool matches_any(const std::vector<std::string>& patterns, const ModelPart& part) {
    return std::any_of(patterns.begin(), patterns.end(), [&](const std::string& pattern) {
        return glob_match(pattern, part.name) || glob_match(pattern, part.material);
    });
}

// The `map` key: for a pk3 archive (scenes/pk3.h) the map inside it to load, required; refused
// with any other file. "" for a model file.
std::string read_map_key(TableReader& r, const fs::path& path) {
    const std::string map = r.string("map", "");
    if (lower_extension(path) != ".pk3") {
        if (!map.empty()) {
            r.error("map", "names a map inside a .pk3 archive, and `file` is not one");
        }
        return map;
    }
    if (map.empty()) {
        std::vector<std::string> maps;
        try {
            maps = pk3::entries(path, ".bsp");
        } catch (const Error& e) {
            r.error("file", e.what());
        }
        std::string listed;
        for (size_t i = 0; i < maps.size() && i < 6; ++i) {
            listed += (i ? ", " : "") + quote(maps[i]);
        }
        r.error("map", fmt::format("required with a .pk3 file: the map inside it to load ({} "
                                   "maps, such as {})",
                                   maps.size(), listed.empty() ? "none" : listed));
    }
    return map;
}

// A [[models]] entry: every part of the model file becomes an object named "<name>/<part>" that
// keeps its node transform (Object::local) under the model's placement. Parts take a scene
// material per file material (its diffuse colour as albedo) unless `materials` retags them;
// `drop` removes parts; `glass` names the parts that cast no shadow (by default those whose
// file material is not opaque). A retagged part takes its scene material as it is, glass or not.
}  // namespace

void read_model(TableReader& r, const fs::path& base_dir, const SceneSearchPaths& paths,
                std::map<std::string, int>& material_index, Scene& scene) {
    const std::string file = r.string("file");
    const fs::path path = resolve_mesh_path(file, base_dir, paths, r);
    const std::string name = r.string("name", fs::path(file).stem().string());
    const Placement placement = read_placement(r, Placement{});
    const std::vector<std::string> drop = read_patterns(r, "drop", {});
    const bool glass_by_opacity = !r.has("glass");
    const std::vector<std::string> glass = read_patterns(r, "glass", {});
    std::vector<std::pair<std::string, int>> retag;
    if (const toml::table* materials = r.table("materials")) {
        for (const auto& [key, node] : *materials) {
            const auto target = node.value<std::string_view>();
            const auto it =
                target ? material_index.find(std::string(*target)) : material_index.end();
            if (it == material_index.end()) {
                r.error("materials", fmt::format("{}: expected the name of a [materials] table",
                                                 quote(std::string(key.str()))));
            }
            retag.emplace_back(std::string(key.str()), it->second);
        }
    }
    const std::string map = read_map_key(r, path);
    Model model;
    try {
        model = map.empty() ? load_model(path) : q3::load_model(path, map);
    } catch (const Error& e) {
        r.error(map.empty() ? "file" : "map", e.what());
    }
    size_t kept = 0;
    for (const ModelPart& part : model.parts) {
        if (matches_any(drop, part)) {
            continue;
        }
        Object object;
        object.name = fmt::format("{}/{}", name, part.name);
        object.mesh = part.mesh;
        object.placement = placement;
        object.local = part.transform;
        object.transform = object.placed();
        const bool is_glass = glass_by_opacity ? part.opacity < 1.0f : matches_any(glass, part);
        const auto it = std::find_if(retag.begin(), retag.end(), [&](const auto& entry) {
            return glob_match(entry.first, part.name) || glob_match(entry.first, part.material);
        });
        if (it != retag.end()) {
            object.material = it->second;
        } else {
            const std::string material =
                fmt::format("{}/{}{}", name, part.material.empty() ? "default" : part.material,
                            is_glass ? " (glass)" : "");
            auto [entry, added] = material_index.try_emplace(material, int(scene.materials.size()));
            if (added) {
                scene.materials.push_back(
                    Material{.name = material, .albedo = part.diffuse, .casts_shadow = !is_glass});
            }
            object.material = entry->second;
        }
        scene.objects.push_back(std::move(object));
        ++kept;
    }
    if (kept == 0) {
        r.error("drop", fmt::format("drops every one of the {} parts of {}", model.parts.size(),
                                    quote(file)));
    }
}

}  // namespace sl
