#include "scenes/scene_sections.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "scenes/animation_toml.h"

namespace sl {

namespace fs = std::filesystem;

const toml::table& empty_table() {
    static const toml::table table;
    return table;
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
    l.shape = parse_enum(r, "shape", l.shape,
                         {{"cone", SpotShape::cone}, {"pyramid", SpotShape::pyramid}});
    if (l.shape == SpotShape::pyramid && l.falloff_degrees > 0.0f) {
        r.error("falloff",
                "a pyramid has a hard edge: falloff is for shape = \"cone\" (write falloff = 0, "
                "or shape = \"cone\")");
    }
    if (!distinct_in_float(l.position, l.target)) {
        r.error("target",
                "light target equals its position (or is too near it for float32 to "
                "give a direction)");
    }
    r.finish();
    return l;
}

PointLight read_point_light(TableReader r) {
    PointLight l;
    l.position = r.vec3("position");
    l.near = float(r.number_in("near", l.near, 0.0, 1e9, true));
    l.far = float(r.number_in("far", l.far, l.near, 1e9, true));
    l.intensity = r.non_negative_vec3("intensity", l.intensity);
    r.finish();
    return l;
}

DirectionalLight read_directional_light(TableReader r) {
    DirectionalLight l;
    const glm::dvec3 direction(r.vec3("direction"));
    // In double, judged by its direction alone, as the camera's up vector is.
    if (!(glm::length(direction) > 0.0)) {
        r.error("direction", "the direction the light travels must not be [0, 0, 0]");
    }
    l.direction = glm::vec3(glm::normalize(direction));
    l.irradiance = r.non_negative_vec3("irradiance", l.irradiance);
    l.entry = r.has("entry") ? r.vec3("entry") : glm::vec3(std::numeric_limits<float>::quiet_NaN());
    r.finish();
    return l;
}

void resolve_directional_light(DirectionalLight& light, const Scene& scene,
                               const std::string& where) {
    Bounds bounds;
    bounds.extend(scene.camera.position);
    for (const Object& object : scene.objects) {
        const Bounds local = object.mesh->bounds();
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 corner(i & 1 ? local.max.x : local.min.x,
                                   i & 2 ? local.max.y : local.min.y,
                                   i & 4 ? local.max.z : local.min.z);
            bounds.extend(glm::vec3(object.transform * glm::vec4(corner, 1.0f)));
        }
    }
    light.region = {bounds.min, bounds.max};
    if (std::isnan(light.entry.x)) {
        light.default_entry = true;
        light.enter_region();  // the plane touching the region on the light's side
        return;
    }
    const glm::dvec3 d(light.direction);
    double farthest = std::numeric_limits<double>::lowest();
    for (int i = 0; i < 8; ++i) {
        farthest = std::max(farthest, glm::dot(glm::dvec3(light.region.corner(i)), d));
    }
    const double entry = glm::dot(glm::dvec3(light.entry), d);
    const double size = glm::length(glm::dvec3(bounds.max) - glm::dvec3(bounds.min));
    if (!(farthest - entry > 1e-4 * std::max(size, 1.0))) {
        fail(
            "{}: key \"entry\": the entry plane lies beyond the whole scene (its objects and the "
            "camera, {:.3g} m along the light past their far side): give a point on the light's "
            "side of them, or leave entry out for the plane touching them",
            where, entry - farthest);
    }
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
    // Only Henyey-Greenstein and Schlick have an asymmetry to set: a g the phase function would
    // ignore is refused rather than dropped.
    if (m.g != 0.0f && m.phase != PhaseFunction::henyey_greenstein &&
        m.phase != PhaseFunction::schlick) {
        r.error("g", fmt::format("g = {} is ignored by phase {}: only \"henyey-greenstein\" and "
                                 "\"schlick\" take g (set phase to one of them, or g = 0)",
                                 m.g, quote(to_string(m.phase))));
    }
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

BoundsSettings read_bounds(TableReader r) {
    BoundsSettings b;
    b.max_outer_planes = r.integer_in("max_outer_planes", 0, 0, 100000);
    if (b.max_outer_planes > 0 && b.max_outer_planes < 8) {
        r.error("max_outer_planes", "must be 0 (full hull) or at least 8");
    }
    b.automatic_inner = r.boolean("automatic_inner", true);
    b.pieces = r.boolean("pieces", false);
    if (b.pieces && b.max_outer_planes > 0) {
        // Pieces are cut from full hulls: reduced hulls would silently take their place.
        r.error("pieces", fmt::format("convex pieces need full hulls, but max_outer_planes = {} "
                                      "reduces every hull; set max_outer_planes = 0 (a base "
                                      "scene may set it) or pieces = false",
                                      b.max_outer_planes));
    }
    const std::string occluders = r.string("occluders", to_string(b.occluders));
    const auto* chosen = std::find_if(std::begin(kOccluders), std::end(kOccluders),
                                      [&](Occluders o) { return occluders == to_string(o); });
    if (chosen == std::end(kOccluders)) {
        r.error("occluders",
                fmt::format("unknown value {} (volumes, triangles, auto)", quote(occluders)));
    }
    b.occluders = *chosen;
    b.max_triangles = r.integer_in("max_triangles", b.max_triangles, 0, 10000000);
    b.min_inner_fill = r.number_in("min_inner_fill", b.min_inner_fill, 0.0, 1.0);
    r.finish();
    return b;
}

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

}  // namespace sl
