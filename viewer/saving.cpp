#include "viewer/window.h"

#include <imgui.h>

#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "core/output_files.h"
#include "gl/debug.h"
#include "viewer/saved_view.h"

namespace sl::viewer {

using gl::GL;

void Viewer::screenshot(const std::string& path) {
    std::vector<unsigned char> rgb(size_t(width_) * height_ * 3);
    GL.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    GL.ReadBuffer(GL_BACK);
    GL.PixelStorei(GL_PACK_ALIGNMENT, 1);
    GL.ReadPixels(0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
    gl::check_errors("reading the window back");
    std::vector<unsigned char> flipped(rgb.size());
    const size_t row = size_t(width_) * 3;
    for (int y = 0; y < height_; ++y) {
        std::copy_n(&rgb[size_t(height_ - 1 - y) * row], row, &flipped[size_t(y) * row]);
    }
    const std::filesystem::path file = std::filesystem::absolute(path);
    OutputFiles outputs(file.parent_path());
    outputs.add(file.filename().string(), [&](const std::filesystem::path& temporary) {
        write_png(flipped, width_, height_, temporary);
    });
    outputs.commit();
    saved_message_ = "screenshot: " + file.string();
    std::printf("shaftlab view: %s\n", saved_message_.c_str());
}

void Viewer::write_in_scattering(const std::string& path) {
    const Image image = renderer_->read_in_scattering();
    const std::filesystem::path file = std::filesystem::absolute(path);
    OutputFiles outputs(file.parent_path());
    outputs.add(file.filename().string(),
                [&](const std::filesystem::path& temporary) { write_exr(image, temporary); });
    outputs.commit();
}

void Viewer::ui_save() {
    char buffer[512];
    std::snprintf(buffer, sizeof(buffer), "%s", save_path_.c_str());
    if (ImGui::InputText("file", buffer, sizeof(buffer)))
        save_path_ = buffer;
    if (ImGui::Button("save as experiment")) {
        try {
            const SavedView saved = save_view_as_experiment(
                save_path_, scene_, options_.scene, *method_, width_, height_, options_.shadow);
            saved_message_ = "saved " + saved.experiment.string();
        } catch (const Error& e) {
            status_ = e.what();
        }
    }
    ImGui::SameLine();
    if (ImGui::Button("screenshot"))
        take_screenshot_ = true;
    if (!saved_message_.empty())
        ImGui::TextWrapped("%s", saved_message_.c_str());
}

}  // namespace sl::viewer
