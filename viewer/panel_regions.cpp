#include "viewer/window.h"

#include <imgui.h>

namespace sl::viewer {

void Viewer::ui_regions() {
    if (!scene_.lights.empty()) {
        // Each light has its own tree; the overlay and the figures below are one's (the light
        // panel's "overlay" chooses it).
        ImGui::TextDisabled("spot light or face %zu of %zu (each has its own tree)", overlay_light_,
                            scene_.spot_lights().size());
    }
    ImGui::Checkbox("volumes", &overlay_settings_.volumes);
    ImGui::SameLine();
    ImGui::Checkbox("outlines", &overlay_settings_.outlines);
    const char* names[3] = {"lit", "uncertain", "unlit"};
    for (int r = 0; r < 3; ++r) {
        const auto& c = kRegionColors[size_t(r)];
        ImGui::ColorButton(names[r], ImVec4(c[0], c[1], c[2], 1.0f), ImGuiColorEditFlags_NoTooltip,
                           ImVec2(12, 12));
        ImGui::SameLine();
        bool shown = overlay_settings_.regions[size_t(r)];
        if (ImGui::Checkbox(names[r], &shown))
            overlay_settings_.regions[size_t(r)] = shown;
        if (r < 2)
            ImGui::SameLine();
    }
    ImGui::SliderFloat("opacity", &overlay_settings_.opacity, 0.05f, 20.0f, "%.2f",
                       ImGuiSliderFlags_Logarithmic);
    ImGui::Text("%zu beams; faces %zu / %zu / %zu", beams_, region_faces_[0], region_faces_[1],
                region_faces_[2]);
    if (influence_volume_ > 0.0) {
        ImGui::Text("volume fraction: lit %.1f%%, uncertain %.1f%%, unlit %.1f%%",
                    100.0 * region_volume_[0] / influence_volume_,
                    100.0 * region_volume_[1] / influence_volume_,
                    100.0 * region_volume_[2] / influence_volume_);
    }
    ImGui::Text("beam tree %.2f ms, regions %.2f ms, prepare %.2f ms", tree_ms_, extract_ms_,
                prepare_ms_);
    // What the objects enter the tree as; a change rebuilds the regions and prepares the method.
    if (ImGui::BeginCombo("occluders", to_string(scene_.bounds.occluders))) {
        for (const Occluders choice : kOccluders) {
            if (ImGui::Selectable(to_string(choice), choice == scene_.bounds.occluders) &&
                choice != scene_.bounds.occluders) {
                scene_.bounds.occluders = choice;
                applied_.reset();  // the volumes changed: everything is built again
                scene_changed();
            }
        }
        ImGui::EndCombo();
    }
    help_marker(
        "volumes: bounding volumes (uncertain between outer and inner); triangles: every "
        "object's triangles, exact; auto: triangles for the objects without an inner volume, "
        "then for those whose inner volumes fill less than min_inner_fill of their hulls, "
        "within max_triangles");
    ImGui::Text("exact occluders: %zu objects, %zu triangles", exact_.list.size(),
                exact_.triangles);
    if (!exact_.list.empty() && ImGui::TreeNode("exact_objects", "which, and why")) {
        for (const bt::ExactOccluders::Object& o : exact_.list) {
            ImGui::BulletText("%s: %zu triangles; %s", o.name.c_str(), o.triangles, o.why.c_str());
        }
        ImGui::TreePop();
    }
}

void Viewer::ui_light_view() {
    ImGui::SetNextWindowPos(ImVec2(356, float(height_) - 300), ImGuiCond_FirstUseEver);
    bool open = true;
    ImGui::Begin("light view of the leaves", &open, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(overlay_.light_view())),
                 ImVec2(kLightViewSize, kLightViewSize), ImVec2(0, 1), ImVec2(1, 0));
    ImGui::TextDisabled("leaves: open yellow, solid grey, blocker purple");
    ImGui::End();
    if (!open)
        layers_["light-view"] = false;
}

}  // namespace sl::viewer
