#include "viewer/window.h"

#include <imgui.h>

namespace sl::viewer {

void Viewer::ui_light() {
    if (!scene_.lights.empty()) {
        // Several lights: each is the scene file's ([[lights]]); the overlays show the first.
        ImGui::TextDisabled("[[lights]]: %zu (%zu spot lights and faces), set in the file",
                            scene_.lights.size(), scene_.spot_lights().size());
        return;
    }
    SpotLight& l = scene_.light;
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
    if (changed && glm::length(l.target - l.position) > 1e-4f) {
        scene_changed();
    }
    ImGui::TextDisabled("ctrl + drag in the view moves it too");
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
