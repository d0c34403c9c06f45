#include "viewer/window.h"

#include <algorithm>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <imgui.h>

#include "core/error.h"
#include "methods/registry.h"

namespace sl::viewer {

namespace {

// What one parameter's widget was changed to this frame, and whether the change is final (a
// click, not a drag still under way).
struct ParameterEdit {
    std::optional<std::string> text;
    bool commit = false;
};

// The parameter's widget: a drag for an integer, a slider for a real (logarithmic over a wide
// range), a checkbox, or a combo of its choices.
ParameterEdit parameter_widget(const frame::Parameter& p) {
    ParameterEdit edit;
    switch (p.type) {
        case frame::Parameter::Type::integer: {
            int v = int(p.value);
            const float speed = float(std::max(1.0, (p.max - p.min) / 400.0));
            if (ImGui::DragInt(p.name.c_str(), &v, speed, int(p.min), int(p.max), "%d",
                               ImGuiSliderFlags_AlwaysClamp)) {
                edit.text = fmt::format("{}", v);
            }
            break;
        }
        case frame::Parameter::Type::real: {
            double v = p.value;
            const bool logarithmic = p.min > 0.0 && p.max / p.min > 100.0;
            ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp;
            if (logarithmic)
                flags |= ImGuiSliderFlags_Logarithmic;
            if (ImGui::SliderScalar(p.name.c_str(), ImGuiDataType_Double, &v, &p.min, &p.max,
                                    "%.4g", flags)) {
                edit.text = fmt::format("{}", v);
            }
            break;
        }
        case frame::Parameter::Type::boolean: {
            bool on = p.value != 0.0;
            if (ImGui::Checkbox(p.name.c_str(), &on)) {
                edit.text = on ? "true" : "false";
                edit.commit = true;
            }
            break;
        }
        case frame::Parameter::Type::choice: {
            if (ImGui::BeginCombo(p.name.c_str(), p.text().c_str())) {
                for (const std::string& choice : p.choices) {
                    if (ImGui::Selectable(choice.c_str(), choice == p.text())) {
                        edit.text = choice;
                        edit.commit = true;
                    }
                }
                ImGui::EndCombo();
            }
            break;
        }
    }
    help_marker(p.description);
    edit.commit |= ImGui::IsItemDeactivatedAfterEdit();
    return edit;
}

}  // namespace

void Viewer::ui_method() {
    const std::string current = method_->name();
    if (ImGui::BeginCombo("method", current.c_str())) {
        for (const std::string& name : methods::volume_method_names()) {
            if (ImGui::Selectable(name.c_str(), name == current) && name != current) {
                switch_method(name);
            }
        }
        ImGui::EndCombo();
    }
    const std::vector<frame::Parameter> parameters = method_->parameters();
    for (const frame::Parameter& p : parameters) {
        const ParameterEdit edit = parameter_widget(p);
        if (edit.text) {
            try {
                method_->set(p.name, *edit.text);
                method_->validate();
            } catch (const Error& e) {
                status_ = e.what();
                method_->set(p.name, p.text());  // back to the last value that held
            }
        }
        if (edit.commit) {
            prepare_method();  // parameters read in prepare() take effect
        }
    }
    if (!parameters.empty() && ImGui::Button("defaults")) {
        for (const frame::Parameter& p : parameters) {
            frame::Parameter d = p;
            d.value = p.default_value;
            method_->set(p.name, d.text());
        }
        prepare_method();
    }
}

}  // namespace sl::viewer
