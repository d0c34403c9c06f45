#include "viewer/window.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "beamtree/beam_tree.h"
#include "beamtree/frame_regions.h"
#include "beamtree/regions.h"
#include "core/error.h"
#include "core/statistics.h"
#include "gl/debug.h"
#include "gl/shaders.h"
#include "ibl/environment.h"
#include "methods/configured_method.h"
#include "scenes/scene_file.h"
#include "viewer/saved_view.h"

namespace sl::viewer {

using gl::GL;
using sl::ms_since;

const std::vector<std::string>& layer_names() {
    static const std::vector<std::string> names = {"volumes", "outlines",  "light-view",
                                                   "error",   "previewer", "timings"};
    return names;
}

Viewer::Viewer(const ViewerOptions& options)
    : options_(options),
      scene_(load_scene(options.scene, SceneSearchPaths::defaults())),
      controller_(scene_.camera) {
    for (const std::string& name : layer_names()) {
        layers_[name] = false;
    }
    for (const std::string& name : options.layers) {
        if (!layers_.contains(name)) {
            std::string known;
            for (const std::string& n : layer_names())
                known += (known.empty() ? "" : ", ") + n;
            fail("unknown layer {} (known: {})", quote(name), known);
        }
        layers_[name] = true;
    }
    const size_t spots = scene_.spot_lights().size();
    if (options.light < 0 || size_t(options.light) >= spots) {
        fail("--light {}: scene {} has {} spot light(s) and point-light faces (0 to {})",
             options.light, quote(scene_.name), spots, spots - 1);
    }
    overlay_light_ = size_t(options.light);
    overlay_settings_.volumes = layers_["volumes"];
    overlay_settings_.outlines = layers_["outlines"];
    // Fail on an unknown method, setting or path before opening a window.
    method_ = methods::create_configured_method(options.method, options.shadow,
                                                methods::parse_settings(options.settings));
    if (!options.path.empty()) {
        path_ = load_animation_file(options.path, scene_);
    } else if (scene_.animation && scripted() && options.orbit_degrees == 0.0f) {
        path_ = *scene_.animation;  // an animated scene plays itself
    }
    if (options.width < 16 || options.height < 16 || options.width > 8192 ||
        options.height > 8192) {
        fail("window size {}x{} must be in 16..8192", options.width, options.height);
    }
    save_path_ = options.save_experiment.empty()
                     ? fmt::format("experiments/view-{}-{}.toml", scene_.name, method_->name())
                     : options.save_experiment;
    if (!(options.error_scale > 0.0f)) {
        fail("--error-scale {} must be positive", options.error_scale);
    }
    heat_scale_ = options.error_scale;
    preview_name_ = options.preview.empty() ? "frame/in-scattering I_s" : options.preview;

    platform_ =
        gl::create_glfw_platform(options.width, options.height,
                                 fmt::format("shaftlab view: {}", scene_.name), !options.hidden);
    glfwSwapInterval(scripted() ? 0 : 1);
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // the layout is the code's, not a file's
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(static_cast<GLFWwindow*>(platform_->native_window()), true);
    ImGui_ImplOpenGL3_Init("#version 450 core");

    blit_program_ = gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                                        {GL_FRAGMENT_SHADER, "viewer/shaders/blit.frag"}});
    empty_array_ = gl::create_vertex_array();
    scene_changed();
    if (!status_.empty()) {
        fail("{}", status_);
    }
}

Viewer::~Viewer() {
    if (job_) {
        if (job_->done) {
            job_->thread.join();
        } else {
            std::fprintf(stderr, "shaftlab view: leaving the reference computation unfinished\n");
            job_->thread.detach();
            job_.release();  // the thread still uses it; the process is ending
        }
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

void Viewer::build_overlay() {
    // The overlay's regions, with the methods' per-frame path (cached volumes), of the
    // light the overlays show (the scene itself when it has one light).
    const Scene one_light = scene_.lights.empty() ? Scene() : scene_.for_light(overlay_light_);
    const Scene& seen = scene_.lights.empty() ? scene_ : one_light;
    const bt::FrameRegions frame = bt::build_frame_regions(seen, {.pieces = true});
    tree_ms_ = frame.ms.volumes + frame.ms.tree;
    extract_ms_ = frame.ms.regions;
    const bt::Regions& regions = *frame.regions;
    overlay_.upload(regions, seen.light.far);
    beams_ = regions.beam_count;
    exact_ = frame.exact;
    for (int r = 0; r < 3; ++r) {
        region_faces_[size_t(r)] = regions.face_count(bt::Region(r));
    }
    region_volume_ = regions.volume;
    influence_volume_ = regions.influence_volume;
}

bool Viewer::layer(const char* name) const {
    return layers_.at(name);
}

void Viewer::switch_method(const std::string& name) {
    try {
        auto method = methods::create_configured_method(name, options_.shadow, {});
        const auto start = Clock::now();
        method->prepare(scene_);
        prepare_ms_ = ms_since(start);
        method_ = std::move(method);
        status_.clear();
    } catch (const Error& e) {
        status_ = e.what();  // the previous method stays
    }
}

void Viewer::prepare_method() {
    try {
        const auto start = Clock::now();
        method_->prepare(scene_);
        prepare_ms_ = ms_since(start);
    } catch (const Error& e) {
        status_ = e.what();
    }
}

void Viewer::scene_changed() {
    try {
        auto start = Clock::now();
        const SceneChange change =
            applied_ ? scene_change(*applied_, scene_) : SceneChange::everything(scene_);
        if (change.regions()) {
            build_overlay();
        }
        start = Clock::now();
        if (applied_) {
            method_->update(scene_, change);
            update_ms_ = ms_since(start);
        } else {
            method_->prepare(scene_);
            prepare_ms_ = ms_since(start);
        }
        applied_ = scene_;
        status_.clear();
    } catch (const Error& e) {
        // A light inside a bounding volume, a medium the method has no closed form for: say
        // so, and go back to the last state that worked (a failed update leaves the method as
        // it was; the overlay is rebuilt for that state).
        if (scripted() || !applied_) {
            throw;
        }
        status_ = e.what();
        scene_ = *applied_;
        applied_.reset();
        scene_changed();
    }
}

void Viewer::draw_frame() {
    int w = 0, h = 0;
    platform_->framebuffer_size(w, h);
    if (w <= 0 || h <= 0) {
        return;  // minimised
    }
    // An environment edited in the panel (file, size, rotation, prefilter) needs its chain baked
    // (or read from the cache) again; intensity, skybox and shading are uniforms.
    const bool rebake =
        renderer_ && !ibl::same_bake(renderer_->environment().source(), scene_.environment);
    if (!renderer_ || rebake || w != width_ || h != height_) {
        renderer_.reset();
        renderer_ = std::make_unique<frame::SceneRenderer>(
            scene_, frame::RenderOptions{.width = w, .height = h, .shadow = options_.shadow});
        width_ = w;
        height_ = h;
    }
    timings_ = renderer_->draw(*method_);
    frame_history_.push(ms_since(last_frame_));
    last_frame_ = Clock::now();
    cpu_history_.push(timings_.cpu_ms);
    shadow_history_.push(timings_.gpu.shadow_ms);
    surface_history_.push(timings_.gpu.surface_ms);
    volume_history_.push(timings_.gpu.volume_ms);
    composite_history_.push(timings_.gpu.composite_ms);
    if (layer("timings") || scripted()) {
        statistics_ = method_->frame_statistics();
    }

    GLuint shown = 0;
    GLuint depth = 0;
    for (const gl::TextureView& view : renderer_->textures()) {
        if (view.name == "frame/display")
            shown = view.texture;
        if (view.name == "frame/surface depth")
            depth = view.texture;
    }
    if (layer("error")) {
        update_error_view();
        if (reference_)
            shown = heat_map_.id();
    }
    GL.BindFramebuffer(GL_FRAMEBUFFER, 0);
    GL.Viewport(0, 0, w, h);
    GL.Disable(GL_BLEND);
    GL.Disable(GL_DEPTH_TEST);
    GL.UseProgram(blit_program_.id());
    GL.BindTextureUnit(0, shown);
    GL.BindVertexArray(empty_array_.id());
    GL.DrawArrays(GL_TRIANGLES, 0, 3);
    if (overlay_settings_.volumes || overlay_settings_.outlines) {
        overlay_.draw(0, depth, w, h, renderer_->uniforms().view_projection, overlay_settings_);
    }
    if (layer("light-view")) {
        const SpotLight light = scene_.spot_lights()[overlay_light_];
        overlay_.draw_light_view(light.projection() * light.view(), kLightViewSize);
    }
    gl::check_errors("drawing the viewer's frame");
}

std::optional<Clock::time_point> Viewer::play_script_frame(float orbit_step) {
    std::optional<Clock::time_point> change_start;
    if (path_) {
        // Frame k at start + k / fps, held at the end.
        const double time = std::min(path_->frame_time(frame_), path_->end);
        scene_ = scene_at(scene_, *path_, time);
        controller_ = CameraController(scene_.camera);
        const SceneChange change = scene_change(*applied_, scene_);
        if (change.light || change.medium || !change.objects.empty()) {
            change_start = Clock::now();
            scene_changed();
        }
    }
    if (frame_ > 0 && orbit_step != 0.0f) {
        controller_.orbit(orbit_step, 0.0f);
        controller_.apply(scene_.camera);
    }
    return change_start;
}

void Viewer::finish_script() {
    if (!options_.screenshot.empty())
        screenshot(options_.screenshot);
    if (!options_.in_scattering.empty())
        write_in_scattering(options_.in_scattering);
    if (!options_.save_experiment.empty()) {
        const SavedView saved =
            save_view_as_experiment(options_.save_experiment, scene_, options_.scene, *method_,
                                    width_, height_, options_.shadow);
        std::printf("shaftlab view: saved %s and %s\n", saved.experiment.c_str(),
                    saved.scene.c_str());
    }
    std::printf(
        "shaftlab view: %d frames of %s with %s at %dx%d; last frame %.2f ms GPU, %.2f ms "
        "CPU; beam tree %zu beams, %.2f ms\n",
        options_.frames, scene_.name.c_str(), method_->name().c_str(), width_, height_,
        timings_.gpu.total_ms(), timings_.cpu_ms, beams_, tree_ms_);
    if (!change_latency_ms_.empty()) {
        std::printf(
            "shaftlab view: %zu scene changes; from a change to the end of the first "
            "frame that shows it: median %.2f ms, max %.2f ms (method update %.2f ms, "
            "regions overlay %.2f ms of the last)\n",
            change_latency_ms_.size(), sl::median(change_latency_ms_),
            *std::max_element(change_latency_ms_.begin(), change_latency_ms_.end()), update_ms_,
            tree_ms_ + extract_ms_);
    }
    if (layer("error")) {
        if (reference_) {
            std::printf("shaftlab view: error against the cached reference: rel_rmse %.4g\n",
                        error_.rel_rmse);
        } else {
            std::printf("shaftlab view: no cached reference for this view\n");
        }
    }
}

int Viewer::run() {
    const float orbit_step = options_.frames > 1
                                 ? glm::radians(options_.orbit_degrees) / float(options_.frames - 1)
                                 : 0.0f;
    while (!platform_->should_close()) {
        platform_->poll_events();
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        const double dt = std::min(ImGui::GetIO().DeltaTime, 0.1f);
        std::optional<Clock::time_point> change_start;
        if (scripted()) {
            change_start = play_script_frame(orbit_step);
        } else {
            handle_input(dt);
        }
        draw_frame();
        if (change_start) {
            change_latency_ms_.push_back(ms_since(*change_start));  // draw_frame waits for the GPU
        }
        if (options_.ui) {
            draw_ui();
        }
        ImGui::Render();
        GL.BindFramebuffer(GL_FRAMEBUFFER, 0);
        GL.Viewport(0, 0, width_, height_);
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        gl::check_errors("drawing the user interface");

        const bool last = scripted() && frame_ + 1 >= options_.frames;
        if (take_screenshot_) {
            take_screenshot_ = false;
            screenshot(
                fmt::format("shaftlab-{}-{}-{:04}.png", scene_.name, method_->name(), frame_));
        }
        if (last) {
            finish_script();
        }
        platform_->swap_buffers();
        ++frame_;
        if (last) {
            break;
        }
    }
    return 0;
}

void help_marker(const std::string& text) {
    if (!text.empty() && ImGui::IsItemHovered()) {
        ImGui::SetTooltip("%s", text.c_str());
    }
}

void Viewer::draw_ui() {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(340, float(std::max(height_ - 16, 200))),
                             ImGuiCond_FirstUseEver);
    ImGui::Begin("shaftlab");
    ImGui::Text("%s: %zu objects, %zu triangles", scene_.name.c_str(), scene_.objects.size(),
                scene_.triangle_count());
    ImGui::Text("%.1f fps (%.1f ms) at %dx%d", 1000.0 / std::max(frame_history_.latest(), 1e-3f),
                frame_history_.latest(), width_, height_);
    if (!status_.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.35f, 0.3f, 1.0f));
        ImGui::TextWrapped("%s", status_.c_str());
        ImGui::PopStyleColor();
    }
    if (ImGui::CollapsingHeader("Method", ImGuiTreeNodeFlags_DefaultOpen))
        ui_method();
    if (ImGui::CollapsingHeader("Regions", ImGuiTreeNodeFlags_DefaultOpen))
        ui_regions();
    if (ImGui::CollapsingHeader("Camera"))
        ui_view();
    if (ImGui::CollapsingHeader("Light", ImGuiTreeNodeFlags_DefaultOpen))
        ui_light();
    if (ImGui::CollapsingHeader("Objects"))
        ui_objects();
    if (ImGui::CollapsingHeader("Medium"))
        ui_medium();
    if (ImGui::CollapsingHeader("Environment (IBL)"))
        ui_environment();
    if (ImGui::CollapsingHeader("Error view"))
        ui_error();
    if (ImGui::CollapsingHeader("Save"))
        ui_save();
    ImGui::Separator();
    for (const char* name : {"timings", "previewer", "light-view"}) {
        ImGui::Checkbox(name, &layers_[name]);
        ImGui::SameLine();
    }
    ImGui::NewLine();
    ImGui::TextDisabled("F1 panels  F12 screenshot  Tab orbit/fly  V/O layers");
    ImGui::End();
    if (layer("timings"))
        ui_timings();
    if (layer("previewer"))
        ui_previewer();
    if (layer("light-view"))
        ui_light_view();
}

int run_viewer(const ViewerOptions& options) {
    Viewer viewer(options);
    return viewer.run();
}

}  // namespace sl::viewer
