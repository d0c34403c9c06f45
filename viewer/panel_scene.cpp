#include "viewer/window.h"

#include <algorithm>
#include <variant>

#include <fmt/format.h>
#include <imgui.h>
#include <glm/geometric.hpp>

namespace sl::viewer {

namespace {

// A spot light's widgets (its [light], or a [[lights]] entry); true when one changed it.
bool edit_spot(SpotLight& l) {
    bool changed = false;
    changed |= ImGui::DragFloat3("position", &l.position.x, 0.02f);
    changed |= ImGui::DragFloat3("target", &l.target.x, 0.02f);
    changed |= ImGui::SliderFloat("cone", &l.cone_half_angle_degrees, 1.0f, 80.0f, "%.1f deg");
    changed |= ImGui::DragFloatRange2("range", &l.near, &l.far, 0.05f, 0.01f, 1000.0f);
    changed |= ImGui::DragFloat3("intensity", &l.intensity.x, 1.0f, 0.0f, 1e6f);
    changed |= ImGui::SliderFloat("falloff", &l.falloff_degrees, 0.0f, l.cone_half_angle_degrees,
                                  "%.1f deg");
    l.near = std::max(l.near, 1e-3f);
    l.far = std::max(l.far, l.near * 1.01f);
    l.falloff_degrees = std::min(l.falloff_degrees, l.cone_half_angle_degrees);
    return changed && glm::length(l.target - l.position) > 1e-4f;
}

bool edit_point(PointLight& l) {
    bool changed = false;
    changed |= ImGui::DragFloat3("position", &l.position.x, 0.02f);
    changed |= ImGui::DragFloatRange2("range", &l.near, &l.far, 0.05f, 0.01f, 1000.0f);
    changed |= ImGui::DragFloat3("intensity", &l.intensity.x, 1.0f, 0.0f, 1e6f);
    l.near = std::max(l.near, 1e-3f);
    l.far = std::max(l.far, l.near * 1.01f);
    return changed;
}

// A sun's direction and irradiance; its entry plane follows the direction where the scene gave
// none (DirectionalLight::enter_region), else it is edited too.
bool edit_directional(DirectionalLight& l) {
    bool changed = false;
    glm::vec3 direction = l.direction;
    if (ImGui::DragFloat3("direction", &direction.x, 0.01f, -1.0f, 1.0f) &&
        glm::length(direction) > 1e-3f) {
        l.direction = glm::normalize(direction);
        changed = true;
    }
    changed |= ImGui::DragFloat3("irradiance", &l.irradiance.x, 0.05f, 0.0f, 1e6f);
    if (l.default_entry) {
        if (changed) {
            l.enter_region();
        }
        ImGui::TextDisabled("entry: the plane touching the scene's box");
    } else {
        changed |= ImGui::DragFloat3("entry", &l.entry.x, 0.02f);
    }
    return changed;
}

}  // namespace

void Viewer::ui_light() {
    if (!scene_.lights.empty()) {
        ui_lights();
        return;
    }
    if (edit_spot(scene_.light)) {
        scene_changed();
    }
    ImGui::TextDisabled("ctrl + drag in the view moves it too");
}

void Viewer::ui_lights() {
    std::vector<LightSource> lights = scene_.lights;
    const auto name = [&](size_t i) { return fmt::format("{}: {}", i, light_type(lights[i])); };
    edited_light_ = std::min(edited_light_, lights.size() - 1);
    if (ImGui::BeginCombo("edit", name(edited_light_).c_str())) {
        for (size_t i = 0; i < lights.size(); ++i) {
            if (ImGui::Selectable(name(i).c_str(), i == edited_light_)) {
                edited_light_ = i;
            }
        }
        ImGui::EndCombo();
    }
    LightSource& light = lights[edited_light_];
    const bool changed = std::holds_alternative<SpotLight>(light)
                             ? edit_spot(std::get<SpotLight>(light))
                         : std::holds_alternative<PointLight>(light)
                             ? edit_point(std::get<PointLight>(light))
                             : edit_directional(std::get<DirectionalLight>(light));
    if (changed) {
        scene_.set_lights(std::move(lights));
        scene_changed();
    }
    // The overlays show one spot light's (or point-light face's) regions at a time.
    const int spots = int(scene_.spot_lights().size());
    int shown = int(overlay_light_);
    if (ImGui::SliderInt("overlay", &shown, 0, spots - 1, "spot light or face %d")) {
        overlay_light_ = size_t(std::clamp(shown, 0, spots - 1));
        build_overlay();
    }
    ImGui::TextDisabled("%zu lights, %d spot lights and point-light faces", scene_.lights.size(),
                        spots);
}

void Viewer::ui_objects() {
    const char* preview =
        selected_object_ >= 0 ? scene_.objects[size_t(selected_object_)].name.c_str() : "(none)";
    if (ImGui::BeginCombo("object", preview)) {
        for (size_t i = 0; i < scene_.objects.size(); ++i) {
            if (ImGui::Selectable(scene_.objects[i].name.c_str(), int(i) == selected_object_)) {
                selected_object_ = int(i);
            }
        }
        ImGui::EndCombo();
    }
    if (selected_object_ < 0) {
        ImGui::TextDisabled("choose one to move it");
        return;
    }
    Object& o = scene_.objects[size_t(selected_object_)];
    bool changed = ImGui::DragFloat3("translate", &o.placement.translate.x, 0.02f);
    changed |= ImGui::DragFloat3("rotate", &o.placement.rotate_degrees.x, 0.5f);
    if (changed) {
        o.transform = o.placed();
        scene_changed();
    }
    ImGui::TextDisabled("alt + drag in the view moves it too");
    ImGui::Text("update %.2f ms (tree and regions through the per-frame path)", update_ms_);
}

void Viewer::ui_medium() {
    Medium& m = scene_.medium;
    bool changed = false;
    changed |= ImGui::DragFloat3("sigma_s", &m.sigma_s.x, 0.002f, 0.0f, 100.0f, "%.4f");
    changed |= ImGui::DragFloat3("sigma_a", &m.sigma_a.x, 0.002f, 0.0f, 100.0f, "%.4f");
    int phase = int(m.phase);
    if (ImGui::BeginCombo("phase", to_string(m.phase))) {
        for (int i = 0; i <= int(PhaseFunction::nishita_hazy); ++i) {
            if (ImGui::Selectable(to_string(PhaseFunction(i)), i == phase)) {
                m.phase = PhaseFunction(i);
                changed = true;
            }
        }
        ImGui::EndCombo();
    }
    changed |= ImGui::SliderFloat("g", &m.g, -0.99f, 0.99f);
    int model = int(m.model);
    if (ImGui::Combo("model", &model, "simplified\0physical\0")) {
        m.model = MediumModel(model);
        changed = true;
    }
    if (m.model == MediumModel::simplified) {
        changed |= ImGui::DragFloat("a0", &m.a0, 0.01f, 0.0f, 100.0f);
        changed |= ImGui::DragFloat("a1", &m.a1, 0.01f, 0.0f, 100.0f);
        if (m.a0 == 0.0f && m.a1 == 0.0f)
            m.a0 = 1e-3f;
    }
    if (changed) {
        scene_changed();
    }
}

}  // namespace sl::viewer
