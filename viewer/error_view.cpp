#include "viewer/window.h"

#include <imgui.h>

#include "core/error.h"
#include "reference/cache.h"

namespace sl::viewer {

using gl::GL;

void Viewer::update_error_view() {
    if (job_ && job_->done) {
        job_->thread.join();
        if (!job_->error.empty())
            status_ = "reference: " + job_->error;
        job_.reset();
        reference_key_ = 0;  // look again: it is in the cache now
    }
    const uint64_t key = reference::reference_key(scene_, width_, height_, reference_options_);
    if (key != reference_key_) {
        reference_key_ = key;
        reference_ = reference::find_cached(scene_, width_, height_, reference_options_);
    }
    if (!reference_) {
        return;
    }
    const Image image = renderer_->read_in_scattering();
    try {
        error_ = compare_images(image, *reference_);
    } catch (const Error& e) {
        status_ = e.what();  // a NaN in I_s: the heat map shows it at full scale
        error_ = {};
    }
    const std::vector<unsigned char> rgb = error_heat_map(image, *reference_, heat_scale_);
    std::vector<unsigned char> flipped(rgb.size());
    const size_t row = size_t(width_) * 3;
    for (int y = 0; y < height_; ++y) {  // GL rows run bottom to top
        std::copy_n(&rgb[size_t(height_ - 1 - y) * row], row, &flipped[size_t(y) * row]);
    }
    if (!heat_map_ || texture_info(heat_map_.id()).width != width_ ||
        texture_info(heat_map_.id()).height != height_) {
        heat_map_ = gl::create_texture_2d(GL_RGBA8, width_, height_, GL_NEAREST);
        heat_map_.label("error heat map");
    }
    GL.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    GL.TextureSubImage2D(heat_map_.id(), 0, 0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE,
                         flipped.data());
}

void Viewer::ui_error() {
    bool on = layer("error");
    if (ImGui::Checkbox("show the error heat map", &on))
        layers_["error"] = on;
    ImGui::SliderFloat("full scale", &heat_scale_, 0.01f, 4.0f, "%.2f x RMS",
                       ImGuiSliderFlags_Logarithmic);
    help_marker("per-pixel |I_s - reference| relative to the reference's RMS pixel");
    if (!on)
        return;
    if (reference_) {
        ImGui::Text("rel_rmse %.4g, max_abs %.4g, psnr %.1f dB", error_.rel_rmse, error_.max_abs,
                    error_.psnr);
    } else if (job_) {
        ImGui::ProgressBar(float(job_->progress.load()), ImVec2(-1, 0), "computing reference");
    } else {
        ImGui::TextWrapped("No cached reference for this view and size.");
        if (ImGui::Button("compute it (CPU, in the background)")) {
            job_ = std::make_unique<ReferenceJob>();
            job_->thread = std::thread([job = job_.get(), scene = scene_, w = width_, h = height_,
                                        o = reference_options_] {
                try {
                    reference::cached_reference(scene, w, h, o,
                                                [job](double f) { job->progress = f; });
                } catch (const std::exception& e) {
                    job->error = e.what();
                }
                job->done = true;
            });
        }
    }
}

}  // namespace sl::viewer
