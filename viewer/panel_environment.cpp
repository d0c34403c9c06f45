#include "viewer/window.h"

#include <fmt/format.h>
#include <imgui.h>

#include <cmath>
#include <filesystem>

#include "scenes/scene_file.h"

namespace sl::viewer {

void Viewer::ui_environment() {
    Environment& e = scene_.environment;
    static const std::vector<std::string> studio_lights = [] {
        std::vector<std::string> names;
        std::error_code ec;
        for (const auto& entry :
             std::filesystem::directory_iterator(SceneSearchPaths::defaults().environments, ec)) {
            if (entry.path().extension() == ".exr")
                names.push_back(entry.path().stem().string());
        }
        std::sort(names.begin(), names.end());
        return names;
    }();
    const std::string current = e.enabled() ? e.file.stem().string() : "none";
    if (ImGui::BeginCombo("environment", current.c_str())) {
        if (ImGui::Selectable("none", !e.enabled()))
            e.file.clear();
        for (const std::string& name : studio_lights) {
            if (ImGui::Selectable(name.c_str(), name == current))
                e.file = SceneSearchPaths::defaults().environments / (name + ".exr");
        }
        ImGui::EndCombo();
    }
    help_marker(
        "Blender's studio lights (Debian blender-data); a change bakes the chain again "
        "unless it is in the cache");
    if (!e.enabled())
        return;
    ImGui::SliderFloat("intensity", &e.intensity, 0.01f, 10.0f, "%.3f",
                       ImGuiSliderFlags_Logarithmic);
    ImGui::Checkbox("skybox", &e.skybox);
    int shading = e.shading == ibl::Shading::moschos ? 1 : 0;
    if (ImGui::Combo("shading", &shading, "split-sum\0moschos (alg. 7-8)\0"))
        e.shading = shading ? ibl::Shading::moschos : ibl::Shading::split_sum;
    // The rest is baked: edited on a copy, applied with the button.
    Environment& pending = environment_pending_;
    bool& editing = environment_editing_;
    if (!editing) {
        pending = e;
    }
    int method = pending.prefilter.method == ibl::PrefilterMethod::cone ? 1 : 0;
    editing |= ImGui::Combo("prefilter", &method, "importance\0cone (Moschos alg. 6)\0");
    pending.prefilter.method =
        method ? ibl::PrefilterMethod::cone : ibl::PrefilterMethod::importance;
    if (pending.prefilter.method == ibl::PrefilterMethod::importance) {
        int distribution = pending.prefilter.distribution == ibl::Distribution::beckmann ? 1 : 0;
        editing |= ImGui::Combo("distribution", &distribution, "ggx\0beckmann\0");
        pending.prefilter.distribution =
            distribution ? ibl::Distribution::beckmann : ibl::Distribution::ggx;
    }
    editing |= ImGui::SliderInt("samples", &pending.prefilter.samples, 1, 4096, "%d",
                                ImGuiSliderFlags_Logarithmic);
    int size_index = std::clamp(int(std::log2(float(pending.face_size))) - 5, 0, 5);
    editing |= ImGui::Combo("face size", &size_index,
                            "32\0"
                            "64\0"
                            "128\0"
                            "256\0"
                            "512\0"
                            "1024\0");
    pending.face_size = 32 << size_index;
    editing |=
        ImGui::SliderFloat("rotation", &pending.rotation_degrees, -180.0f, 180.0f, "%.0f deg");
    if (editing && ImGui::Button("bake")) {
        e.prefilter = pending.prefilter;
        e.face_size = pending.face_size;
        e.rotation_degrees = pending.rotation_degrees;
        editing = false;
    }
    if (renderer_ && renderer_->environment().loaded()) {
        const ibl::PrefilteredChain& chain = renderer_->environment().loaded()->chain;
        ImGui::Text("%zu levels of %d..%d texels, %s", chain.levels.size(),
                    chain.levels.front().size, chain.levels.back().size,
                    chain.seconds > 0 ? fmt::format("baked in {:.2f} s", chain.seconds).c_str()
                                      : "from the cache");
    }
}

}  // namespace sl::viewer
