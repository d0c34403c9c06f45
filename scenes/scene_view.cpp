// A view of a scene written as a scene file that derives from it (scenes/scene_file.h,
// scene_view_toml): what the viewer saves.

#include <fmt/format.h>

#include "scenes/scene_file.h"
#include "scenes/toml_reader.h"

namespace sl {

namespace fs = std::filesystem;

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
    auto spot = [&](const SpotLight& light, const char* header) {
        text += fmt::format(
            "{}position = {}\ntarget = {}\ncone_angle = {}\nnear = {}\nfar = {}\n"
            "intensity = {}\nfalloff = {}\nshape = {}\n\n",
            header, toml_vec3(light.position), toml_vec3(light.target),
            toml_float(light.cone_half_angle_degrees), toml_float(light.near),
            toml_float(light.far), toml_vec3(light.intensity), toml_float(light.falloff_degrees),
            toml_quoted(light.shape == SpotShape::pyramid ? "pyramid" : "cone"));
    };
    if (scene.lights.empty()) {
        spot(l, "[light]\n");
    }
    for (const LightSource& source : scene.lights) {
        if (const auto* s = std::get_if<SpotLight>(&source)) {
            spot(*s, "[[lights]]\ntype = \"spot\"\n");
            continue;
        }
        if (const auto* sun = std::get_if<DirectionalLight>(&source)) {
            text += fmt::format(
                "[[lights]]\ntype = \"directional\"\ndirection = {}\nirradiance = {}\nentry = "
                "{}\n\n",
                toml_vec3(sun->direction), toml_vec3(sun->irradiance), toml_vec3(sun->entry));
            continue;
        }
        const PointLight& p = std::get<PointLight>(source);
        text += fmt::format(
            "[[lights]]\ntype = \"point\"\nposition = {}\nnear = {}\nfar = {}\nintensity = "
            "{}\n\n",
            toml_vec3(p.position), toml_float(p.near), toml_float(p.far), toml_vec3(p.intensity));
    }
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

}  // namespace sl
