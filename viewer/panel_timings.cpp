#include "viewer/window.h"

#include <fmt/format.h>
#include <imgui.h>

namespace sl::viewer {

void Viewer::ui_timings() {
    ImGui::SetNextWindowPos(ImVec2(float(width_) - 368, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(360, 300), ImGuiCond_FirstUseEver);
    bool open = true;
    ImGui::Begin("timings", &open);
    ImGui::Text("frame %.2f ms (%.1f fps), draw() %.2f ms CPU", frame_history_.latest(),
                1000.0 / std::max(frame_history_.latest(), 1e-3f), timings_.cpu_ms);
    ImGui::PlotLines("frame ms", frame_history_.values.data(), int(kHistory),
                     int(frame_history_.next), nullptr, 0.0f, frame_history_.max() * 1.1f,
                     ImVec2(0, 50));
    if (ImGui::BeginTable("passes", 2)) {
        auto row = [](const std::string& name, double ms) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(name.c_str());
            ImGui::TableNextColumn();
            ImGui::Text("%8.3f ms", ms);
        };
        row("GPU shadow map", timings_.gpu.shadow_ms);
        row("GPU surfaces", timings_.gpu.surface_ms);
        row("GPU volume", timings_.gpu.volume_ms);
        for (const auto& [name, ms] : timings_.gpu.volume_sections)
            row("    " + name, ms);
        row("GPU composite", timings_.gpu.composite_ms);
        row("CPU beam tree (viewer)", tree_ms_);
        row("CPU regions (viewer)", extract_ms_);
        row("CPU method prepare", prepare_ms_);
        row("CPU method update (last change)", update_ms_);
        for (const auto& [name, value] : statistics_) {
            if (name.starts_with("cpu_ms_"))
                row("CPU " + name.substr(7), value);
        }
        ImGui::EndTable();
    }
    for (auto [name, history] :
         {std::pair{"shadow", &shadow_history_}, std::pair{"surfaces", &surface_history_},
          std::pair{"volume", &volume_history_}, std::pair{"composite", &composite_history_}}) {
        ImGui::PlotLines(name, history->values.data(), int(kHistory), int(history->next),
                         fmt::format("{:.2f} ms", history->latest()).c_str(), 0.0f,
                         history->max() * 1.1f + 1e-3f, ImVec2(0, 32));
    }
    if (!statistics_.empty() && ImGui::TreeNode("method counters")) {
        for (const auto& [name, value] : statistics_) {
            ImGui::Text("%s = %.6g", name.c_str(), value);
        }
        ImGui::TreePop();
    }
    ImGui::End();
    if (!open)
        layers_["timings"] = false;
}

}  // namespace sl::viewer
