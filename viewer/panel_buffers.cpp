#include "viewer/window.h"

#include <imgui.h>

#include <tuple>

namespace sl::viewer {

using gl::GL;

gl::TextureViews Viewer::all_textures() const {
    gl::TextureViews views = renderer_->textures();
    for (gl::TextureView& view : method_->textures())
        views.push_back(std::move(view));
    if (overlay_settings_.volumes && overlay_.thickness())
        views.push_back({"viewer/region lengths (lit, uncertain, unlit)", overlay_.thickness()});
    if (layer("light-view") && overlay_.light_view())
        views.push_back({"viewer/light view of the leaves", overlay_.light_view()});
    if (heat_map_)
        views.push_back({"viewer/error heat map", heat_map_.id()});
    return views;
}

void Viewer::ui_previewer() {
    ImGui::SetNextWindowPos(ImVec2(float(width_) - 528, float(height_) - 400),
                            ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(520, 392), ImGuiCond_FirstUseEver);
    bool open = true;
    ImGui::Begin("buffers", &open);
    const gl::TextureViews views = all_textures();
    const gl::TextureView* selected = nullptr;
    for (const gl::TextureView& view : views) {
        if (view.name == preview_name_)
            selected = &view;
    }
    // A texture asked for by name that is not made yet (a method's overlay appears the frame after
    // the previewer first asks for its textures) stays asked for: the first is shown meanwhile.
    if (!selected && !views.empty()) {
        selected = &views.front();
    }
    if (ImGui::BeginCombo("buffer", selected ? selected->name.c_str() : preview_name_.c_str())) {
        for (const gl::TextureView& view : views) {
            if (ImGui::Selectable(view.name.c_str(), view.name == preview_name_)) {
                preview_name_ = view.name;
                selected = &view;
            }
        }
        ImGui::EndCombo();
    }
    if (selected && selected->name != fitted_name_) {
        // A new buffer starts with its values' range.
        fitted_name_ = selected->name;
        std::tie(preview_settings_.lo, preview_settings_.hi) = value_range(
            selected->texture, preview_settings_.channel, preview_settings_.logarithmic);
    }
    if (selected) {
        const TextureInfo info = texture_info(selected->texture);
        ImGui::Text("%dx%d, format 0x%x%s", info.width, info.height, info.internal_format,
                    info.depth ? " (depth)" : "");
        ImGui::Combo("channel", &preview_settings_.channel, "rgb\0r\0g\0b\0a\0");
        ImGui::DragFloatRange2("range", &preview_settings_.lo, &preview_settings_.hi, 0.01f);
        ImGui::Checkbox("log10", &preview_settings_.logarithmic);
        ImGui::SameLine();
        if (ImGui::Button("fit range")) {
            const auto [lo, hi] = value_range(selected->texture, preview_settings_.channel,
                                              preview_settings_.logarithmic);
            preview_settings_.lo = lo;
            preview_settings_.hi = hi;
        }
        preview_.draw(selected->texture, preview_settings_, 480);
        GL.BindFramebuffer(GL_FRAMEBUFFER, 0);
        const float width = std::min(ImGui::GetContentRegionAvail().x, float(preview_.width()));
        const float height = width * float(preview_.height()) / float(preview_.width());
        ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(preview_.preview())),
                     ImVec2(width, height), ImVec2(0, 1), ImVec2(1, 0));
    }
    ImGui::End();
    if (!open)
        layers_["previewer"] = false;
}

}  // namespace sl::viewer
