#include "scenes/scene_file.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "core/error.h"
#include "scenes/animation_toml.h"
#include "scenes/model.h"
#include "scenes/toml_reader.h"

#ifndef SHAFTLAB_SCENES_DIR
#error "SHAFTLAB_SCENES_DIR must be defined by the build"
#endif
#ifndef SHAFTLAB_DATA_DIR
#error "SHAFTLAB_DATA_DIR must be defined by the build"
#endif
#ifndef SHAFTLAB_ENVIRONMENTS_DIR
#error "SHAFTLAB_ENVIRONMENTS_DIR must be defined by the build"
#endif

namespace sl {

namespace fs = std::filesystem;

SceneSearchPaths SceneSearchPaths::defaults() {
    SceneSearchPaths paths{SHAFTLAB_SCENES_DIR, SHAFTLAB_DATA_DIR, SHAFTLAB_ENVIRONMENTS_DIR};
    if (const char* scenes = std::getenv("SHAFTLAB_SCENES"); scenes && *scenes) {
        paths.scenes = scenes;
    }
    if (const char* data = std::getenv("SHAFTLAB_DATA"); data && *data) {
        paths.data = data;
    }
    if (const char* environments = std::getenv("SHAFTLAB_ENVIRONMENTS");
        environments && *environments) {
        paths.environments = environments;
    }
    return paths;
}

namespace {

using TableReader = TomlTableReader;

const toml::table& empty_table() {
    static const toml::table table;
    return table;
}

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

Camera read_camera(TableReader r) {
    Camera c;
    c.position = r.vec3("position");
    c.target = r.vec3("target");
    c.up = r.vec3("up", c.up);
    c.fov_y_degrees = float(r.number_in("fov", c.fov_y_degrees, 0.0, 180.0, true, true));
    c.near = float(r.number_in("near", c.near, 0.0, 1e9, true));
    c.far = float(r.number_in("far", c.far, c.near, 1e9, true));
    c.exposure = float(r.number_in("exposure", c.exposure, 0.0, 1e9, true));
    if (!distinct_in_float(c.position, c.target)) {
        r.error("target",
                "camera target equals its position (or is too near it for float32 to "
                "give a view direction)");
    }
    if (c.up == glm::vec3(0.0f)) {
        r.error("up", "up vector must not be [0, 0, 0]");
    }
    // In double, on unit vectors: any finite up of any length is judged by its direction alone,
    // and kept as that direction, so that GLM's float32 lookAt never sees a tiny vector.
    const glm::dvec3 view = glm::normalize(glm::dvec3(c.target) - glm::dvec3(c.position));
    const glm::dvec3 up = glm::normalize(glm::dvec3(c.up));
    if (glm::length(glm::cross(view, up)) <= 1e-6) {
        r.error("up", "up vector is parallel to the view direction");
    }
    c.up = glm::vec3(up);
    r.finish();
    return c;
}

SpotLight read_light(TableReader r) {
    SpotLight l;
    l.position = r.vec3("position");
    l.target = r.vec3("target");
    // Below 90° so that the influence pyramid (a square frustum) exists.
    l.cone_half_angle_degrees =
        float(r.number_in("cone_angle", l.cone_half_angle_degrees, 0.0, 89.0, true));
    l.near = float(r.number_in("near", l.near, 0.0, 1e9, true));
    l.far = float(r.number_in("far", l.far, l.near, 1e9, true));
    l.intensity = r.non_negative_vec3("intensity", l.intensity);
    l.falloff_degrees = float(r.number_in("falloff", 0.0, 0.0, l.cone_half_angle_degrees));
    if (!distinct_in_float(l.position, l.target)) {
        r.error("target",
                "light target equals its position (or is too near it for float32 to "
                "give a direction)");
    }
    r.finish();
    return l;
}

Medium read_medium(TableReader r) {
    Medium m;
    m.sigma_s = r.non_negative_vec3("sigma_s", m.sigma_s);
    m.sigma_a = r.non_negative_vec3("sigma_a", m.sigma_a);
    m.phase = parse_enum(r, "phase", m.phase,
                         {{"isotropic", PhaseFunction::isotropic},
                          {"henyey-greenstein", PhaseFunction::henyey_greenstein},
                          {"schlick", PhaseFunction::schlick},
                          {"rayleigh", PhaseFunction::rayleigh},
                          {"mie-hazy", PhaseFunction::mie_hazy},
                          {"mie-murky", PhaseFunction::mie_murky},
                          {"nishita-hazy", PhaseFunction::nishita_hazy}});
    m.g = float(r.number_in("g", m.g, -1.0, 1.0, true, true));
    m.model =
        parse_enum(r, "model", m.model,
                   {{"simplified", MediumModel::simplified}, {"physical", MediumModel::physical}});
    m.a0 = float(r.number_in("a0", m.a0, 0.0, 1e9));
    m.a1 = float(r.number_in("a1", m.a1, 0.0, 1e9));
    if (m.a0 == 0.0f && m.a1 == 0.0f) {
        r.error("a1", "a0 and a1 must not both be zero (the falloff 1/(a1 r² + a0) is undefined)");
    }
    r.finish();
    return m;
}

Environment read_environment(TableReader r, const fs::path& base_dir,
                             const SceneSearchPaths& paths) {
    Environment e;
    // `enabled = false`: a derived scene turning its base's environment off (no file needed).
    const bool enabled = r.boolean("enabled", true);
    const std::string file = r.string("file", "");
    if (file.empty() && enabled) {
        r.error("file", "expected an environment: a studio light's name or an .exr file");
    }
    std::error_code ec;
    if (!file.empty()) {
        e.file = environment_file(file, base_dir, paths);
    }
    if (enabled && !fs::is_regular_file(e.file, ec)) {
        r.error("file", fmt::format("no environment {} ({} does not exist; the studio lights "
                                    "come with Debian's blender-data)",
                                    quote(file), e.file.string()));
    }
    e.intensity = float(r.number_in("intensity", e.intensity, 0.0, 1e9));
    e.rotation_degrees = float(r.number_in("rotation", e.rotation_degrees, -360.0, 360.0));
    e.face_size = r.integer_in("face_size", e.face_size, 1, 4096);
    if (e.face_size & (e.face_size - 1)) {
        r.error("face_size", fmt::format("{} is not a power of two", e.face_size));
    }
    auto parsed = [&](std::string_view key, auto parse, auto fallback) {
        if (!r.has(key)) {
            return fallback;
        }
        const std::string value = r.string(key, "");
        try {
            return parse(value);
        } catch (const Error& error) {
            r.error(key, error.what());
        }
    };
    e.prefilter.method = parsed("prefilter", ibl::parse_prefilter_method, e.prefilter.method);
    e.prefilter.distribution =
        parsed("distribution", ibl::parse_distribution, e.prefilter.distribution);
    e.prefilter.samples = r.integer_in("samples", e.prefilter.samples, 1, 1 << 16);
    e.prefilter.filtered = r.boolean("filtered", e.prefilter.filtered);
    e.shading = parsed("shading", ibl::parse_shading, e.shading);
    e.skybox = r.boolean("skybox", e.skybox);
    if (!enabled) {
        e.file.clear();
    }
    r.finish();
    return e;
}

Material read_material(TableReader r, std::string name) {
    Material m;
    m.name = std::move(name);
    m.albedo = r.non_negative_vec3("albedo", m.albedo);
    if (m.albedo.x > 1 || m.albedo.y > 1 || m.albedo.z > 1) {
        r.error("albedo", "components must be in [0, 1]");
    }
    m.roughness = float(r.number_in("roughness", m.roughness, 0.0, 1.0));
    m.f0 = r.non_negative_vec3("f0", m.f0);
    m.casts_shadow = r.boolean("casts_shadow", m.casts_shadow);
    // Translucent: a preset's name (materials/scattering_material.h) with optional overrides, or
    // coefficients.
    if (r.has("translucent")) {
        Translucency t;
        const std::string preset = r.string("translucent", "");
        try {
            t.medium = preset == "custom"
                           ? sss::ScatteringMaterial{.name = "custom", .source = "scene file"}
                           : sss::material_preset(preset);
        } catch (const Error& e) {
            r.error("translucent", e.what());
        }
        t.medium.sigma_s_reduced =
            glm::dvec3(r.non_negative_vec3("sigma_s_reduced", glm::vec3(t.medium.sigma_s_reduced)));
        t.medium.sigma_a = glm::dvec3(r.non_negative_vec3("sigma_a", glm::vec3(t.medium.sigma_a)));
        t.medium.eta = r.number_in("eta", t.medium.eta, 0.0, 10.0, true);
        try {
            sss::validate(t.medium);
        } catch (const Error& e) {
            r.error("translucent", e.what());
        }
        const std::string model = r.string("model", "dipole");
        if (model != "dipole" && model != "multipole") {
            r.error("model",
                    fmt::format("unknown diffusion model {} (dipole, multipole)", quote(model)));
        }
        t.model = model == "dipole" ? DiffusionModel::dipole : DiffusionModel::multipole;
        if (const toml::array* coats = r.array("coats")) {
            for (size_t i = 0; i < coats->size(); ++i) {
                const toml::table* table = (*coats)[i].as_table();
                if (!table) {
                    r.error("coats", "expected an array of {material = ..., thickness = ...}");
                }
                TableReader c(*table, r.origin(), fmt::format("{} coats #{}", r.context(), i + 1));
                sss::Layer layer;
                try {
                    layer.material = sss::material_preset(c.string("material", ""));
                } catch (const Error& e) {
                    c.error("material", e.what());
                }
                layer.thickness_mm = c.number_in("thickness", 1.0, 0.0, 1000.0, true);
                c.finish();
                t.coats.push_back(layer);
            }
        }
        m.translucency = std::move(t);
    } else {
        for (const char* key : {"sigma_s_reduced", "sigma_a", "eta", "model", "coats"}) {
            if (r.has(key)) {
                r.error(key, "only for translucent materials (set `translucent`)");
            }
        }
    }
    r.finish();
    return m;
}

Subsurface read_subsurface(TableReader r) {
    Subsurface s;
    s.mm_per_unit = float(r.number_in("mm_per_unit", s.mm_per_unit, 0.0, 1e6, true));
    if (r.has("grid")) {
        const toml::array* grid = r.array("grid");
        if (!grid || grid->size() != 2 || !(*grid)[0].is_integer() || !(*grid)[1].is_integer()) {
            r.error("grid", "expected [N, M], two integers");
        }
        s.grid_x = int(*(*grid)[0].value<int64_t>());
        s.grid_y = int(*(*grid)[1].value<int64_t>());
        if (s.grid_x < 1 || s.grid_y < 1 || s.grid_x > 1024 || s.grid_y > 1024) {
            r.error("grid", "N and M must be in 1..1024");
        }
    }
    s.jitter = r.boolean("jitter", s.jitter);
    s.map_size = r.integer_in("map_size", s.map_size, 16, 8192);
    s.epsilon = float(r.number_in("epsilon", s.epsilon, 0.0, 1.0, true, true));
    const std::string radius = r.string("radius", "flux");
    if (radius != "flux" && radius != "profile") {
        r.error("radius", fmt::format("unknown r_max criterion {} (flux, profile)", quote(radius)));
    }
    s.flux_radius = radius == "flux";
    s.footprint = r.boolean("footprint", s.footprint);
    const std::string weighting = r.string("weighting", to_string(s.weighting));
    if (weighting != "jacobian" && weighting != "seed") {
        r.error("weighting",
                fmt::format("unknown weighting {} (jacobian, seed)", quote(weighting)));
    }
    s.weighting = weighting == "seed" ? SplatWeighting::seed : SplatWeighting::jacobian;
    s.profile_texels = r.integer_in("profile_texels", s.profile_texels, 4, 8192);
    s.environment_samples = r.integer_in("environment_samples", s.environment_samples, 0, 1 << 20);
    if (const toml::array* lights = r.array("lights")) {
        for (size_t i = 0; i < lights->size(); ++i) {
            const toml::table* table = (*lights)[i].as_table();
            if (!table) {
                r.error("lights", "expected an array of light tables");
            }
            s.lights.push_back(read_light(
                TableReader(*table, r.origin(), fmt::format("[sss] lights #{}", i + 1))));
        }
    }
    r.finish();
    return s;
}

}  // namespace

Placement read_placement(TomlTableReader& r, const Placement& fallback) {
    Placement p;
    p.translate = r.vec3("translate", fallback.translate);
    p.rotate_degrees = r.vec3("rotate", fallback.rotate_degrees);
    p.scale = fallback.scale;
    if (const toml::node* node = r.take("scale"); node && node->is_number()) {
        p.scale = glm::vec3(float(*node->value<double>()));
    } else if (node) {
        p.scale = r.vec3("scale", p.scale);
    }
    if (!std::isfinite(p.scale.x) || !std::isfinite(p.scale.y) || !std::isfinite(p.scale.z) ||
        p.scale.x == 0 || p.scale.y == 0 || p.scale.z == 0) {
        r.error("scale", "must be finite and non-zero");
    }
    return p;
}

namespace {

fs::path resolve_mesh_path(const std::string& file, const fs::path& base_dir,
                           const SceneSearchPaths& paths, TableReader& r) {
    const fs::path candidates[] = {base_dir / file, paths.data / "meshes" / file,
                                   paths.data / file};
    for (const fs::path& candidate : candidates) {
        if (fs::is_regular_file(candidate)) {
            return candidate;
        }
    }
    r.error("file", fmt::format("mesh {} not found (looked in {}, {}/meshes, {})", quote(file),
                                base_dir.string(), paths.data.string(), paths.data.string()));
}

// Meshes are shared between objects that name the same file and fit.
using MeshCache = std::map<std::string, std::shared_ptr<const Mesh>>;

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

// A scene's TOML text with the name its errors use and the folder its relative paths start from.
struct SceneText {
    std::string text;
    std::string origin;
    fs::path dir;
};

// A canonical name, multiple:N, or a file (relative paths from `dir` first, then as given).
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
        "unknown scene {} (canonical: {}, multiple:N; random: boxes:SEED; animated: {}; effects: "
        "{}; real: {}; or a .toml file)",
        quote(name), listed(canonical_scene_names()), listed(animated_scene_names()),
        listed(effect_scene_names()), listed(real_scene_names()));
}

}  // namespace

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

namespace {

toml::table parse_toml(const std::string& text, const std::string& origin) {
    try {
        return toml::parse(text, origin);
    } catch (const toml::parse_error& e) {
        fail("{}:{}: malformed TOML: {}", origin, e.source().begin.line, e.description());
    }
}

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
    scene->erase("base");
    if (toml::table* merged_scene = merged["scene"].as_table()) {
        merged_scene->erase("name");  // the derived scene is named by its own file
    }
    fill_from(root, merged);
    return root;
}

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

bool glob_match(std::string_view pattern, std::string_view text) {
    // Iterative with one backtrack point: linear in practice, never exponential.
    size_t p = 0, t = 0, star = std::string_view::npos, resume = 0;
    while (t < text.size()) {
        if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == text[t])) {
            ++p;
            ++t;
        } else if (p < pattern.size() && pattern[p] == '*') {
            star = p++;
            resume = t;
        } else if (star != std::string_view::npos) {
            p = star + 1;
            t = ++resume;
        } else {
            return false;
        }
    }
    while (p < pattern.size() && pattern[p] == '*') {
        ++p;
    }
    return p == pattern.size();
}

bool matches_any(const std::vector<std::string>& patterns, const ModelPart& part) {
    return std::any_of(patterns.begin(), patterns.end(), [&](const std::string& pattern) {
        return glob_match(pattern, part.name) || glob_match(pattern, part.material);
    });
}

// A [[models]] entry: every part of the model file becomes an object named "<name>/<part>" that
// keeps its node transform (Object::local) under the model's placement. Parts take a scene
// material per file material (its diffuse colour as albedo) unless `materials` retags them;
// `drop` removes parts; `glass` names the parts that cast no shadow (by default those whose
// file material is not opaque). A retagged part takes its scene material as it is, glass or not.
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
    Model model;
    try {
        model = load_model(path);
    } catch (const Error& e) {
        r.error("file", e.what());
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

}  // namespace

Scene parse_scene(const std::string& text, const std::string& origin, const fs::path& base_dir,
                  const SceneSearchPaths& paths) {
    const toml::table root = resolve_base(parse_toml(text, origin), origin, base_dir, paths, 0);
    TableReader top(root, origin, "");
    Scene scene;

    const toml::table* scene_table = top.table("scene");
    TableReader scene_reader(scene_table ? *scene_table : empty_table(), origin, "[scene]");
    scene.name = scene_reader.string("name", fs::path(origin).stem().string());
    scene.ambient = scene_reader.non_negative_vec3("ambient", scene.ambient);
    scene_reader.finish();

    auto section = [&](std::string_view key) -> const toml::table& {
        const toml::table* table = top.table(key);
        if (!table) {
            fail("{}: missing required table [{}]", origin, key);
        }
        return *table;
    };
    scene.camera = read_camera(TableReader(section("camera"), origin, "[camera]"));
    scene.light = read_light(TableReader(section("light"), origin, "[light]"));
    const toml::table* medium = top.table("medium");
    scene.medium = read_medium(TableReader(medium ? *medium : empty_table(), origin, "[medium]"));

    if (const toml::table* environment = top.table("environment")) {
        scene.environment =
            read_environment(TableReader(*environment, origin, "[environment]"), base_dir, paths);
    }

    if (const toml::table* subsurface = top.table("sss")) {
        scene.subsurface = read_subsurface(TableReader(*subsurface, origin, "[sss]"));
    }

    if (const toml::table* bounds = top.table("beamtree")) {
        TableReader r(*bounds, origin, "[beamtree]");
        scene.bounds.max_outer_planes = r.integer_in("max_outer_planes", 0, 0, 100000);
        if (scene.bounds.max_outer_planes > 0 && scene.bounds.max_outer_planes < 8) {
            r.error("max_outer_planes", "must be 0 (full hull) or at least 8");
        }
        scene.bounds.automatic_inner = r.boolean("automatic_inner", true);
        scene.bounds.pieces = r.boolean("pieces", false);
        r.finish();
    }

    scene.materials.push_back(Material{.name = "default"});
    std::map<std::string, int> material_index{{"default", 0}};
    if (const toml::table* materials = top.table("materials")) {
        for (const auto& [key, node] : *materials) {
            const std::string name(key.str());
            if (!node.is_table()) {
                fail("{}:{}: [materials] {}: expected a table", origin, node.source().begin.line,
                     name);
            }
            material_index[name] = int(scene.materials.size());
            scene.materials.push_back(read_material(
                TableReader(*node.as_table(), origin, fmt::format("[materials.{}]", name)), name));
        }
    }

    MeshCache meshes;
    if (const toml::array* objects = top.array("objects")) {
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
    if (const toml::array* models = top.array("models")) {
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
    if (const toml::table* animation = top.table("animation")) {
        scene.animation = std::make_shared<Animation>(read_animation(*animation, origin, scene));
    }
    top.finish();
    return scene;
}

fs::path environment_file(const std::string& name, const fs::path& dir,
                          const SceneSearchPaths& paths) {
    if (fs::path(name).extension() == ".exr" || name.find('/') != std::string::npos) {
        return fs::path(name).is_relative() ? dir / name : fs::path(name);
    }
    return paths.environments / (name + ".exr");
}

Scene load_scene_file(const fs::path& path, const SceneSearchPaths& paths) {
    Scene scene =
        parse_scene(read_text_file(path, "scene file"), path.string(), path.parent_path(), paths);
    scene.source = path;
    return scene;
}

namespace {

// Shortest text that reads back to the same float, always a TOML float.
std::string toml_float(float value) {
    std::string text = fmt::format("{}", value);
    if (text.find_first_of(".eEn") == std::string::npos) {
        text += ".0";
    }
    return text;
}

std::string toml_vec3(glm::vec3 v) {
    return fmt::format("[{}, {}, {}]", toml_float(v.x), toml_float(v.y), toml_float(v.z));
}

}  // namespace

std::string scene_view_toml(const Scene& scene, const std::string& base, const std::string& name) {
    const Camera& c = scene.camera;
    const SpotLight& l = scene.light;
    const Medium& m = scene.medium;
    std::string text;
    text += fmt::format("[scene]\nbase = {}\nname = {}\nambient = {}\n\n", toml_quoted(base),
                        toml_quoted(name), toml_vec3(scene.ambient));
    text += fmt::format(
        "[camera]\nposition = {}\ntarget = {}\nup = {}\nfov = {}\nnear = {}\nfar = {}\n"
        "exposure = {}\n\n",
        toml_vec3(c.position), toml_vec3(c.target), toml_vec3(c.up), toml_float(c.fov_y_degrees),
        toml_float(c.near), toml_float(c.far), toml_float(c.exposure));
    text += fmt::format(
        "[light]\nposition = {}\ntarget = {}\ncone_angle = {}\nnear = {}\nfar = {}\n"
        "intensity = {}\nfalloff = {}\n\n",
        toml_vec3(l.position), toml_vec3(l.target), toml_float(l.cone_half_angle_degrees),
        toml_float(l.near), toml_float(l.far), toml_vec3(l.intensity),
        toml_float(l.falloff_degrees));
    text += fmt::format(
        "[medium]\nsigma_s = {}\nsigma_a = {}\nphase = {}\ng = {}\nmodel = {}\na0 = {}\n"
        "a1 = {}\n",
        toml_vec3(m.sigma_s), toml_vec3(m.sigma_a), toml_quoted(to_string(m.phase)),
        toml_float(m.g), toml_quoted(to_string(m.model)), toml_float(m.a0), toml_float(m.a1));
    const Environment& e = scene.environment;
    if (!e.enabled()) {
        text += "\n[environment]\nenabled = false\n";
        return text;
    }
    text += fmt::format(
        "\n[environment]\nfile = {}\nintensity = {}\nrotation = {}\nface_size = {}\n"
        "prefilter = {}\ndistribution = {}\nsamples = {}\nfiltered = {}\nshading = {}\n"
        "skybox = {}\n",
        toml_quoted(fs::absolute(e.file).string()), toml_float(e.intensity),
        toml_float(e.rotation_degrees), e.face_size,
        toml_quoted(ibl::to_string(e.prefilter.method)),
        toml_quoted(ibl::to_string(e.prefilter.distribution)), e.prefilter.samples,
        e.prefilter.filtered, toml_quoted(ibl::to_string(e.shading)), e.skybox);
    return text;
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
    return {"house", "house-sweep", "engine", "engine-orbit"};
}

std::vector<std::string> named_scene_names() {
    std::vector<std::string> names = canonical_scene_names();
    for (const auto& group : {animated_scene_names(), effect_scene_names(), real_scene_names()}) {
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
